// The ARMv7-M SysTick timer (Cortex-M4 and M7 alike) as the tick source of the Cortex-M programs: reload
// value, counter cleared, interrupt on, clocked by the core.
#pragma once

#include <cstdint>

#include "firmware/target/cortex_m4_registers.hpp"

namespace gyrostab::firmware::cortex_m4 {

inline void start_systick(std::uint32_t cycles_per_tick) {
  reg(kSysTickLoad) = cycles_per_tick - 1u;
  reg(kSysTickVal) = 0;
  reg(kSysTickCtrl) = kSysTickEnable | kSysTickInterrupt | kSysTickCoreClock;
}

}  // namespace gyrostab::firmware::cortex_m4
