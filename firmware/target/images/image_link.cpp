// What every controller image shares: the SysTick interrupt that extends the profile clock
// (instruction_clock.hpp) to 64 bits.
#include <cstdint>

extern "C" {
volatile std::uint32_t g_systicks{0};

void SysTick_Handler() { g_systicks = g_systicks + 1u; }
}
