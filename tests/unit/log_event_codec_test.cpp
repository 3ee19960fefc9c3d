// The bus log's scene and end events (hil/lcm/log_event_codec.hpp) read from an untrusted file: every string
// length field that lcm-gen's decoder would turn into an out-of-range std::string::assign (zero, negative,
// INT32_MIN, beyond the event) is refused with the field named, and every truncation of a valid event is
// refused. The libFuzzer target tests/fuzz/bus_log_fuzz.cpp found the INT32_MIN case.
#include <gtest/gtest.h>

#include <climits>
#include <cstdint>
#include <string>
#include <vector>

#include "hil/lcm/log_event_codec.hpp"

namespace gyrostab {
namespace {

hil::SceneEvent a_scene() {
  hil::SceneEvent e;
  e.log_version = hil::kLogVersion;
  e.name = "monorail";
  e.device = "monorail";
  e.seed = 7;
  e.tick_ns = 1'000'000;
  e.source = "sim/scenes/monorail.toml";
  e.toml = "[scene]\nname = \"monorail\"\n";
  return e;
}

hil::EndEvent an_end() {
  hil::EndEvent e;
  e.ticks = 1234;
  e.reason = hil::EndReason::kCompleted;
  e.detail = "completed";
  return e;
}

void put_i32(std::vector<std::uint8_t>& b, std::size_t at, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(u >> (24 - 8 * i));
}

// Byte offsets of the string length fields in an encoding (after the 8-byte fingerprint).
std::vector<std::size_t> scene_string_offsets(const hil::SceneEvent& e) {
  std::size_t at = 8 + 4;  // log_version
  std::vector<std::size_t> out;
  out.push_back(at);
  at += 4 + e.name.size() + 1;
  out.push_back(at);
  at += 4 + e.device.size() + 1 + 8 + 8;  // seed, tick_ns
  out.push_back(at);
  at += 4 + e.source.size() + 1;
  out.push_back(at);
  return out;
}

TEST(LogEventCodec, EventsRoundTrip) {
  const std::vector<std::uint8_t> s = hil::encode(a_scene());
  hil::SceneEvent scene;
  std::string why;
  ASSERT_TRUE(hil::decode(s.data(), static_cast<int>(s.size()), scene, why)) << why;
  EXPECT_EQ(scene.toml, a_scene().toml);
  EXPECT_EQ(scene.source, a_scene().source);
  const std::vector<std::uint8_t> e = hil::encode(an_end());
  hil::EndEvent end;
  ASSERT_TRUE(hil::decode(e.data(), static_cast<int>(e.size()), end, why)) << why;
  EXPECT_EQ(end.ticks, 1234);
  EXPECT_EQ(end.detail, "completed");
}

TEST(LogEventCodec, EveryBadStringLengthIsRefusedWithItsField) {
  const hil::SceneEvent e = a_scene();
  const std::vector<std::uint8_t> good = hil::encode(e);
  const std::vector<std::size_t> at = scene_string_offsets(e);
  ASSERT_EQ(at.size(), 4u);
  for (std::size_t f = 0; f < at.size(); ++f) {
    for (const std::int32_t len : {0, -1, -2, INT32_MIN, INT32_MAX, static_cast<std::int32_t>(good.size())}) {
      std::vector<std::uint8_t> bad = good;
      put_i32(bad, at[f], len);
      hil::SceneEvent out;
      std::string why;
      EXPECT_FALSE(hil::decode(bad.data(), static_cast<int>(bad.size()), out, why)) << "field " << f << " " << len;
      EXPECT_NE(why.find("string field"), std::string::npos) << why;
      EXPECT_NE(why.find("length " + std::to_string(len)), std::string::npos) << why;
    }
  }
}

template <class Event>
void expect_every_truncation_refused(const std::vector<std::uint8_t>& bytes) {
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    Event out;
    std::string why;
    EXPECT_FALSE(hil::decode(bytes.data(), static_cast<int>(n), out, why)) << n;
    EXPECT_FALSE(why.empty()) << n;
  }
}

TEST(LogEventCodec, EveryTruncationIsRefused) {
  expect_every_truncation_refused<hil::SceneEvent>(hil::encode(a_scene()));
  expect_every_truncation_refused<hil::EndEvent>(hil::encode(an_end()));
}

TEST(LogEventCodec, AnEndEventIsNotASceneEvent) {
  const std::vector<std::uint8_t> e = hil::encode(an_end());
  hil::SceneEvent out;
  std::string why;
  EXPECT_FALSE(hil::decode(e.data(), static_cast<int>(e.size()), out, why));
  EXPECT_NE(why.find("wrong type fingerprint"), std::string::npos) << why;
}

TEST(LogEventCodec, AFlippedBitInTheTextFailsTheCheckSum) {
  std::vector<std::uint8_t> s = hil::encode(a_scene());
  s[s.size() - 8 - 3] ^= 0x01;  // inside the TOML text, before its terminating zero
  hil::SceneEvent out;
  std::string why;
  EXPECT_FALSE(hil::decode(s.data(), static_cast<int>(s.size()), out, why));
  EXPECT_NE(why.find("check sum"), std::string::npos) << why;
}

}  // namespace
}  // namespace gyrostab
