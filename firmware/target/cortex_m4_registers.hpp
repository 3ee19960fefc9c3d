// The few Cortex-M4 core registers the target program touches (ARMv7-M Architecture Reference Manual,
// B3.2 System Control Space, C1.8 DWT): FPU access, SysTick, and the DWT cycle counter. Core registers only,
// so the file fits every Cortex-M4F part; no vendor headers.
#pragma once

#include <cstdint>

namespace gyrostab::firmware::cortex_m4 {

inline volatile std::uint32_t& reg(std::uintptr_t address) {
  return *reinterpret_cast<volatile std::uint32_t*>(address);
}

// Coprocessor Access Control: CP10/CP11 (the FPU) full access = bits 20-23 set.
inline constexpr std::uintptr_t kCpacr = 0xE000ED88u;
inline constexpr std::uint32_t kCpacrFpuFullAccess = 0xFu << 20;

// SysTick: control/status, reload value, current value.
inline constexpr std::uintptr_t kSysTickCtrl = 0xE000E010u;
inline constexpr std::uintptr_t kSysTickLoad = 0xE000E014u;
inline constexpr std::uintptr_t kSysTickVal = 0xE000E018u;
inline constexpr std::uint32_t kSysTickEnable = 1u << 0;
inline constexpr std::uint32_t kSysTickInterrupt = 1u << 1;
inline constexpr std::uint32_t kSysTickCoreClock = 1u << 2;

// Debug Exception and Monitor Control (TRCENA enables the DWT), DWT control (CYCCNTENA) and cycle counter.
inline constexpr std::uintptr_t kDemcr = 0xE000EDFCu;
inline constexpr std::uint32_t kDemcrTrcena = 1u << 24;
inline constexpr std::uintptr_t kDwtCtrl = 0xE0001000u;
inline constexpr std::uint32_t kDwtCtrlCyccntena = 1u << 0;
inline constexpr std::uintptr_t kDwtCyccnt = 0xE0001004u;

}  // namespace gyrostab::firmware::cortex_m4
