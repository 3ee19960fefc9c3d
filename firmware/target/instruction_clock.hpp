// The controller images' profile clock: SysTick free-running over its full 24-bit range, its wraps counted by
// the SysTick interrupt (g_systicks, image_link.cpp), read as a 64-bit count and scaled to nanoseconds of the
// core clock the counter runs on (25 MHz on QEMU's mps2-an500: 40 ns per count).
// Why SysTick and not the DWT cycle counter (dwt_cycle_clock.hpp): QEMU 7.2 has no DWT (every register reads
// 0). Under QEMU's -icount shift=0 each instruction advances virtual time by exactly 1 ns and SysTick follows
// virtual time, so this clock counts executed instructions, in steps of 40, identically on every run. On a
// real Cortex-M7 it counts time at SysTick's resolution (1 / core clock).
#pragma once

#include <cstdint>

#include "firmware/target/cortex_m4_registers.hpp"

extern "C" volatile std::uint32_t g_systicks;  // SysTick wraps so far (image_link.cpp)

namespace gyrostab::firmware::target {

inline constexpr std::uint32_t kSysTickReload = 0x00FFFFFFu;  // the largest: one interrupt per 2^24 counts

struct InstructionClock {
  std::uint32_t ns_per_count{40};  // 1e9 / SysTick clock (25 MHz on mps2-an500)

  static void start() {
    namespace r = cortex_m4;
    r::reg(r::kSysTickLoad) = kSysTickReload;
    r::reg(r::kSysTickVal) = 0;
    r::reg(r::kSysTickCtrl) = r::kSysTickEnable | r::kSysTickInterrupt | r::kSysTickCoreClock;
  }

  // Counts since start() [counts]. A wrap between the two reads of g_systicks is read again.
  static std::uint64_t counts() {
    std::uint32_t wraps = 0;
    std::uint32_t value = 0;
    do {
      wraps = g_systicks;
      value = cortex_m4::reg(cortex_m4::kSysTickVal);
    } while (wraps != g_systicks);
    return (static_cast<std::uint64_t>(wraps) << 24) + (kSysTickReload - value);
  }

  std::int64_t operator()() const { return static_cast<std::int64_t>(counts() * ns_per_count); }
};

}  // namespace gyrostab::firmware::target
