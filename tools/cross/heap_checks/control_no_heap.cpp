// Control case of the no-heap check: the same program shape as the heap_* cases, without an allocation.
// It must link; if it does not, a heap_* failure would prove nothing.
#include <cstdint>

extern "C" {
volatile std::uint32_t g_sink{0};
void SysTick_Handler() {}
[[noreturn]] void firmware_main() {
  static std::uint32_t buffer[4]{};
  for (;;) g_sink = buffer[g_sink & 3u]++;
}
}
