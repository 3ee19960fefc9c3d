// libFuzzer target for the LCM frame decoders (hil/lcm/frame_codec.hpp): arbitrary bytes as a received
// sensor and actuator message of a device (the monorail's table). Beyond "no crash / no sanitizer report":
//   - a message whose size is not the type's encoded size is refused as kWrongSize;
//   - a refused message leaves the output frame and sim time untouched (nothing half-decoded is used);
//   - an accepted message re-encodes to exactly its input bytes, link envelope included (the wire format is
//     lossless: NaN payloads, signed zeros and wrapped unsigned fields included).
// Built only with -DGYROSTAB_FUZZ=ON and clang; run it with tools/fuzz/run-lcm-codec-fuzz.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "hil/lcm/frame_codec.hpp"
#include "gyrostab_signals/monorail_frames.hpp"

namespace {

const gyrostab::msg::DeviceSignals& kDevice = gyrostab::msg::monorail::kSignals;

template <class Frame>
void check(const std::uint8_t* data, std::size_t size, int encoded_size) {
  Frame out;
  std::memset(&out, 0xA5, sizeof out);
  Frame before;
  std::memcpy(&before, &out, sizeof out);
  std::int64_t sim_us = 0x5A5A5A5A;
  gyrostab::hil::LinkEnvelope env{1, 2, 3, 4, 5};
  const int n = size > 1'000'000 ? -1 : static_cast<int>(size);
  const gyrostab::hil::DecodeError e = gyrostab::hil::decode(data, n, kDevice, out, &sim_us, &env);
  if (n != encoded_size && e != gyrostab::hil::DecodeError::kWrongSize) __builtin_trap();
  if (e != gyrostab::hil::DecodeError::kOk) {
    if (std::memcmp(&out, &before, sizeof out) != 0 || sim_us != 0x5A5A5A5A) __builtin_trap();
    if (env.sender != 1 || env.session != 2 || env.freshness != 3 || env.mac != 4 || env.scene != 5) {
      __builtin_trap();
    }
    return;
  }
  std::uint8_t again[gyrostab::hil::kMaxEncodedSize];
  if (gyrostab::hil::encode(out, kDevice, sim_us, again, static_cast<int>(sizeof again), env) != n) __builtin_trap();
  if (std::memcmp(again, data, size) != 0) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  check<gyrostab::msg::AnySensorFrame>(data, size, gyrostab::hil::sensor_encoded_size(kDevice));
  check<gyrostab::msg::AnyActuatorFrame>(data, size, gyrostab::hil::actuator_encoded_size(kDevice));
  return 0;
}
