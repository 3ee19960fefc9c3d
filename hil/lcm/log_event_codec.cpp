#include "hil/lcm/log_event_codec.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

#include <gyrostab_msg/log_end_t.hpp>
#include <gyrostab_msg/scene_t.hpp>

namespace gyrostab::hil {

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : text) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 1099511628211ull;
  }
  return h;
}

namespace {

constexpr std::size_t kCheckBytes = 8;  // check_fnv1a64, the last field of both types

std::uint64_t check_of(const std::uint8_t* data, std::size_t size) {
  return fnv1a64(std::string_view(reinterpret_cast<const char*>(data), size - kCheckBytes));
}

// Encodes with check_fnv1a64 = 0, then writes the check sum of the bytes before it into its place (LCM puts
// an int64 big-endian, and it is the last field, so it is the last 8 bytes).
template <class Msg>
std::vector<std::uint8_t> encode_message(Msg& m) {
  m.check_fnv1a64 = 0;
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  const int n = m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  if (n < static_cast<int>(kCheckBytes)) return {};
  buf.resize(static_cast<std::size_t>(n));
  const std::uint64_t c = check_of(buf.data(), buf.size());
  for (std::size_t i = 0; i < kCheckBytes; ++i) {
    buf[buf.size() - kCheckBytes + i] = static_cast<std::uint8_t>(c >> (56 - 8 * i));
  }
  return buf;
}

// lcm-gen's decoder checks a string's length field only against the bytes left: a zero or negative one
// reaches std::string::assign as length - 1 (INT32_MIN - 1 overflows and would read 2 GiB past the event).
// So each type's encoding is walked first, field by field as its .lcm file declares them, and a string whose
// length field is not 1..(bytes left) is refused before lcm-gen's code sees it. A field added to the .lcm file
// and not here makes every event fail the walk, which the log round-trip tests catch.
enum class Field : std::uint8_t { kI32, kI64, kString };

constexpr Field kSceneFields[] = {Field::kI32, Field::kString, Field::kString, Field::kI64,
                                  Field::kI64, Field::kString, Field::kString, Field::kI64};
constexpr Field kEndFields[] = {Field::kI64, Field::kI32, Field::kI32, Field::kString, Field::kI64};

constexpr int kFingerprintBytes = 8;

std::int32_t big_endian_i32(const std::uint8_t* p) {
  return static_cast<std::int32_t>((std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) |
                                   (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]});
}

template <std::size_t N>
bool walk_fields(const std::uint8_t* data, int size, const Field (&fields)[N], const char* type,
                 std::string& why) {
  int pos = kFingerprintBytes;
  for (std::size_t i = 0; i < N; ++i) {
    const int fixed = fields[i] == Field::kI64 ? 8 : 4;
    if (size - pos < fixed) {
      why = std::string(type) + " ends inside field " + std::to_string(i + 1) + " of " + std::to_string(N) +
            " (" + std::to_string(size) + " bytes)";
      return false;
    }
    if (fields[i] == Field::kString) {
      const std::int32_t len = big_endian_i32(data + pos);
      if (len < 1 || len > size - pos - fixed) {
        why = std::string(type) + ": string field " + std::to_string(i + 1) + " at byte " + std::to_string(pos) +
              " has length " + std::to_string(len) + " (1 to " + std::to_string(size - pos - fixed) +
              " possible, its terminating zero included)";
        return false;
      }
      pos += len;
    }
    pos += fixed;
  }
  if (pos != size) {
    why = std::string(type) + " takes " + std::to_string(pos) + " of the event's " + std::to_string(size) +
          " bytes";
    return false;
  }
  return true;
}

// The fingerprint and the walk refuse everything lcm-gen's decoder would fail, throw or overrun on; what is
// left for it is a well-formed event, and the check sum then decides whether its bytes are the written ones.
template <class Msg, std::size_t N>
bool decode_message(const void* data, int size, const Field (&fields)[N], Msg& m, std::string& why) {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  if (size < kFingerprintBytes) {
    why = "an event of " + std::to_string(size) + " bytes is shorter than a type fingerprint";
    return false;
  }
  std::uint64_t fingerprint = 0;
  for (int i = 0; i < kFingerprintBytes; ++i) fingerprint = (fingerprint << 8) | bytes[i];
  if (fingerprint != static_cast<std::uint64_t>(Msg::getHash())) {
    why = "not a " + std::string(Msg::getTypeName()) + " (wrong type fingerprint)";
    return false;
  }
  if (!walk_fields(bytes, size, fields, Msg::getTypeName(), why)) return false;
  const int n = m.decode(data, 0, size);
  if (n < 0) {
    why = "not a valid " + std::string(Msg::getTypeName());
    return false;
  }
  if (n != size) {
    why = std::string(Msg::getTypeName()) + " decodes from " + std::to_string(n) + " of the event's " +
          std::to_string(size) + " bytes";
    return false;
  }
  if (static_cast<std::uint64_t>(m.check_fnv1a64) !=
      check_of(static_cast<const std::uint8_t*>(data), static_cast<std::size_t>(size))) {
    why = std::string(Msg::getTypeName()) + " does not match its check sum (a corrupt byte)";
    return false;
  }
  return true;
}

}  // namespace

std::vector<std::uint8_t> encode(const SceneEvent& e) {
  gyrostab_msg::scene_t m;
  m.log_version = e.log_version;
  m.name = e.name;
  m.device = e.device;
  m.seed = static_cast<std::int64_t>(e.seed);
  m.tick_ns = e.tick_ns;
  m.source = e.source;
  m.toml = e.toml;
  return encode_message(m);
}

std::vector<std::uint8_t> encode(const EndEvent& e) {
  gyrostab_msg::log_end_t m;
  m.ticks = e.ticks;
  m.reason = static_cast<std::int32_t>(e.reason);
  m.signal = e.signal;
  m.detail = e.detail;
  return encode_message(m);
}

bool decode(const void* data, int size, SceneEvent& out, std::string& why) {
  gyrostab_msg::scene_t m;
  if (!decode_message(data, size, kSceneFields, m, why)) return false;
  if (m.log_version != kLogVersion) {
    why = "log version " + std::to_string(m.log_version) + " (this build reads version " +
          std::to_string(kLogVersion) +
          (m.log_version == 1 ? ": version 1 logs carry the frame every device shared before the signal tables; "
                                "record the run again with this build"
                              : "") +
          ")";
    return false;
  }
  if (m.tick_ns < 1000) {
    why = "tick_ns " + std::to_string(m.tick_ns) + " (every scene ticks at 1 us or slower)";
    return false;
  }
  out.log_version = m.log_version;
  out.name = m.name;
  out.device = m.device;
  out.seed = static_cast<std::uint64_t>(m.seed);
  out.tick_ns = m.tick_ns;
  out.source = m.source;
  out.toml = m.toml;
  return true;
}

bool decode(const void* data, int size, EndEvent& out, std::string& why) {
  gyrostab_msg::log_end_t m;
  if (!decode_message(data, size, kEndFields, m, why)) return false;
  if (m.reason < 0 || m.reason > static_cast<std::int32_t>(EndReason::kOther)) {
    why = "unknown end reason " + std::to_string(m.reason);
    return false;
  }
  if (m.ticks < 0) {
    why = "negative tick count " + std::to_string(m.ticks);
    return false;
  }
  out.ticks = m.ticks;
  out.reason = static_cast<EndReason>(m.reason);
  out.signal = m.signal;
  out.detail = m.detail;
  return true;
}

}  // namespace gyrostab::hil
