// Link-level fault injection on the target link (`--target-fault`, docs/pil.md): what the plant's end does to
// the sensor frames of some ticks, or to the emulator, so that the image's reaction can be tested. Acts on the
// first transmission of a tick only (a lockstep resend is clean). Ticks [from, from + count).
#pragma once

#include <cstdint>

namespace gyrostab::hil {

struct TargetFaults {
  std::int64_t corrupt_from{-1}, corrupt_count{0};  // one byte of the wire changed: a CRC or framing refusal
  std::int64_t stale_from{-1}, stale_count{0};      // the previous frame's bytes again instead: alive repeated
  std::int64_t skip_from{-1}, skip_count{0};        // an alive counter value left out: alive skipped
  std::int64_t freeze_at{-1};                       // SIGSTOP the emulator before this tick's frame (a hang)
  std::int64_t kill_at{-1};                         // SIGKILL it before this tick's frame (the emulator dies)
  bool bad_config{false};                           // send a configuration the controller must refuse

  static bool covers(std::int64_t from, std::int64_t count, std::int64_t k) {
    return from >= 0 && k >= from && k < from + count;
  }
  bool any() const {
    return corrupt_from >= 0 || stale_from >= 0 || skip_from >= 0 || freeze_at >= 0 || kill_at >= 0 || bad_config;
  }
};

}  // namespace gyrostab::hil
