// Bare-metal start-up for a Cortex-M4F (the cross-build proof, tools/cross/build-firmware-arm): the vector
// table, a reset handler that enables the FPU, copies .data from flash, zeroes .bss, runs the C++ static
// constructors and calls firmware_main(), and default handlers that stop in a loop. Symbols come from
// tools/cross/cortex_m4.ld. No C runtime start files (-nostartfiles): nothing here may allocate.
#include <cstdint>

#include "firmware/target/cortex_m4_registers.hpp"

extern "C" {
// From the linker script.
extern std::uint32_t _estack;                  // top of the stack
extern std::uint32_t _sidata, _sdata, _edata;  // .data load address (flash), run addresses (RAM)
extern std::uint32_t _sbss, _ebss;             // .bss
extern void (*__init_array_start[])();         // static constructors
extern void (*__init_array_end[])();

[[noreturn]] void firmware_main();  // the program (main_cortex_m4.cpp)
[[noreturn]] void Reset_Handler();
void Default_Handler();
void SysTick_Handler();  // the program defines it
}

extern "C" [[noreturn]] void Reset_Handler() {
  namespace m4 = gyrostab::firmware::cortex_m4;
  // The FPU first: code compiled with -mfloat-abi=hard may touch s-registers anywhere after this.
  m4::reg(m4::kCpacr) = m4::reg(m4::kCpacr) | m4::kCpacrFpuFullAccess;
  __asm__ volatile("dsb\n\tisb" ::: "memory");

  for (std::uint32_t *src = &_sidata, *dst = &_sdata; dst < &_edata;) *dst++ = *src++;
  for (std::uint32_t* dst = &_sbss; dst < &_ebss;) *dst++ = 0;
  for (void (**ctor)() = __init_array_start; ctor < __init_array_end; ++ctor) (*ctor)();

  firmware_main();
}

extern "C" void Default_Handler() {
  for (;;) {
  }
}

// Core exceptions 0-15 (ARMv7-M B1.5.2); device interrupts are not used by the proof program.
using Vector = void (*)();
extern "C" __attribute__((section(".isr_vector"), used)) const Vector g_vector_table[16] = {
    reinterpret_cast<Vector>(&_estack),  // 0  initial stack pointer
    Reset_Handler,                       // 1  reset
    Default_Handler,                     // 2  NMI
    Default_Handler,                     // 3  HardFault
    Default_Handler,                     // 4  MemManage
    Default_Handler,                     // 5  BusFault
    Default_Handler,                     // 6  UsageFault
    nullptr,                             // 7  reserved
    nullptr,                             // 8  reserved
    nullptr,                             // 9  reserved
    nullptr,                             // 10 reserved
    Default_Handler,                     // 11 SVCall
    Default_Handler,                     // 12 DebugMonitor
    nullptr,                             // 13 reserved
    Default_Handler,                     // 14 PendSV
    SysTick_Handler,                     // 15 SysTick
};
