// docs/protocol.md's worked example of the MAC is true: the frame the project's codec encodes from the example's
// values, the bytes the MAC covers and the tag are the ones the page prints — and libsodium's SipHash-2-4 of the
// page's MAC input, computed independently of the project's authenticator, is the same tag.
#include <gtest/gtest.h>
#include <sodium.h>

#include <cstdint>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gyrostab_signals/monorail_frames.hpp"
#include "hil/lcm/frame_codec.hpp"
#include "hil/link/link_guard.hpp"

#ifndef GYROSTAB_SOURCE_DIR
#error "GYROSTAB_SOURCE_DIR: the checkout, for docs/protocol.md"
#endif

namespace gyrostab {
namespace {

std::map<std::string, std::string> example_block() {
  std::ifstream f(GYROSTAB_SOURCE_DIR "/docs/protocol.md");
  std::stringstream s;
  s << f.rdbuf();
  const std::string text = s.str();
  const auto a = text.find("<!-- protocol-example begin -->");
  const auto b = text.find("<!-- protocol-example end -->");
  std::map<std::string, std::string> out;
  if (a == std::string::npos || b == std::string::npos) return out;
  std::istringstream lines(text.substr(a, b - a));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream l(line);
    std::string key, rest;
    if (!(l >> key) || key.rfind("<!--", 0) == 0 || key.rfind("```", 0) == 0) continue;
    std::getline(l, rest);
    const auto first = rest.find_first_not_of(' ');
    out[key] = first == std::string::npos ? "" : rest.substr(first);
  }
  return out;
}

std::string hex(const std::vector<std::uint8_t>& b) {
  static const char* d = "0123456789abcdef";
  std::string s;
  for (const std::uint8_t x : b) {
    s += d[x >> 4];
    s += d[x & 15];
  }
  return s;
}

std::vector<std::uint8_t> unhex(const std::string& s) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < s.size(); i += 2) out.push_back(static_cast<std::uint8_t>(std::stoul(s.substr(i, 2), nullptr, 16)));
  return out;
}

std::uint64_t number(const std::string& hexdigits) { return std::stoull(hexdigits, nullptr, 16); }

void put_le(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

TEST(ProtocolExample, TheWorkedMacExampleIsWhatTheCodecAndLibsodiumCompute) {
  ASSERT_GE(sodium_init(), 0);
  const std::map<std::string, std::string> ex = example_block();
  for (const char* key : {"key", "data_id", "session", "freshness", "scene", "sender", "signals", "frame", "mac_input",
                          "tag"}) {
    ASSERT_TRUE(ex.count(key)) << "docs/protocol.md's example has no line '" << key << "'";
  }
  const msg::DeviceSignals& monorail = msg::monorail::kSignals;
  // The frame of the example: tick 0, the listed signals, the envelope's ids; freshness 1.
  msg::AnySensorFrame f{};
  std::istringstream values(ex.at("signals"));
  std::size_t n = 0;
  for (double v; values >> v;) f.signal[n++] = v;
  ASSERT_EQ(n, monorail.sensors.size()) << "one value per sensor signal of the monorail's table";
  hil::LinkEnvelope env;
  env.scene = number(ex.at("scene"));
  env.sender = number(ex.at("sender"));
  env.session = number(ex.at("session"));
  env.freshness = number(ex.at("freshness"));
  const auto data_id = static_cast<std::uint32_t>(number(ex.at("data_id")));
  ASSERT_EQ(data_id, hil::kSensorDataId);

  // The project's side: encode, then the guard's MAC over the covered bytes.
  std::vector<std::uint8_t> frame(static_cast<std::size_t>(hil::sensor_encoded_size(monorail)));
  ASSERT_EQ(hil::encode(f, monorail, 0, frame.data(), static_cast<int>(frame.size()), env),
            static_cast<int>(frame.size()));
  firmware::link::Key128 key;
  const std::vector<std::uint8_t> key_bytes = unhex(ex.at("key"));
  ASSERT_EQ(key_bytes.size(), 16u);
  for (std::size_t i = 0; i < 16; ++i) key.bytes[i] = key_bytes[i];
  hil::GuardConfig g{env.sender, env.session, env.scene, 0, key, hil::kSensorDataId, hil::kActuatorDataId};
  hil::LinkGuard guard(g);
  const std::size_t covered = static_cast<std::size_t>(hil::mac_covered_bytes(static_cast<int>(frame.size())));
  const hil::LinkEnvelope sealed = guard.protect(std::span<const std::uint8_t>(frame.data(), covered));
  EXPECT_EQ(sealed.freshness, env.freshness) << "a sender's first frame has freshness 1";
  hil::write_envelope(frame.data(), static_cast<int>(frame.size()), sealed);

  // Independently: the documented input, hashed by libsodium.
  std::vector<std::uint8_t> input;
  put_le(input, data_id, 4);
  put_le(input, env.session, 8);
  put_le(input, env.freshness, 8);
  input.insert(input.end(), frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(covered));
  unsigned char out[crypto_shorthash_siphash24_BYTES];
  crypto_shorthash_siphash24(out, input.data(), input.size(), key_bytes.data());
  std::uint64_t tag = 0;
  for (int i = 7; i >= 0; --i) tag = (tag << 8) | out[i];

  EXPECT_EQ(sealed.mac, tag) << "the project's MAC against libsodium's SipHash-2-4 of the documented input";
  std::ostringstream expected;
  expected << "frame       " << hex(frame) << "\nmac_input   " << hex(input) << "\ntag         " << std::hex
           << std::setfill('0') << std::setw(16) << tag << "\n";
  EXPECT_EQ(ex.at("frame"), hex(frame)) << "docs/protocol.md's example should read:\n" << expected.str();
  EXPECT_EQ(ex.at("mac_input"), hex(input)) << expected.str();
  EXPECT_EQ(number(ex.at("tag")), tag) << expected.str();
  // The frame's last 8 bytes are the tag, big-endian.
  std::uint64_t in_frame = 0;
  for (std::size_t i = frame.size() - 8; i < frame.size(); ++i) in_frame = (in_frame << 8) | frame[i];
  EXPECT_EQ(in_frame, tag);
}

}  // namespace
}  // namespace gyrostab
