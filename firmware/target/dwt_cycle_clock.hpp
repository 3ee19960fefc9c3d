// Target port of the scheduler's time source: the Cortex-M DWT cycle counter (32 bit, counts core clocks),
// extended to 64 bits and converted to nanoseconds. The extension assumes one read per counter wrap at least
// (2^32 cycles = 25.6 s at 168 MHz), which a 1 kHz scheduler does by a wide margin.
#pragma once

#include <cstdint>

#include "firmware/target/cortex_m4_registers.hpp"

namespace gyrostab::firmware::cortex_m4 {

class DwtCycleClock {
 public:
  constexpr explicit DwtCycleClock(std::uint32_t core_hz) : core_hz_(core_hz) {}

  // Enables the trace block and the cycle counter (once, at start-up).
  static void start() {
    reg(kDemcr) = reg(kDemcr) | kDemcrTrcena;
    reg(kDwtCyccnt) = 0;
    reg(kDwtCtrl) = reg(kDwtCtrl) | kDwtCtrlCyccntena;
  }

  // Time since start() [ns]. O(1): two 64-bit divisions (split so that cycles · 1e9 cannot overflow).
  std::int64_t operator()() {
    const std::uint32_t now = reg(kDwtCyccnt);
    cycles_ += now - last_;  // modulo 2^32: correct across one wrap
    last_ = now;
    const std::uint64_t seconds = cycles_ / core_hz_;
    const std::uint64_t rest_ns = (cycles_ % core_hz_) * 1'000'000'000u / core_hz_;
    return static_cast<std::int64_t>(seconds * 1'000'000'000u + rest_ns);
  }

 private:
  std::uint32_t core_hz_;    // core clock [Hz]
  std::uint32_t last_{0};    // counter at the previous read [cycles]
  std::uint64_t cycles_{0};  // cycles since start() [cycles]
};

}  // namespace gyrostab::firmware::cortex_m4
