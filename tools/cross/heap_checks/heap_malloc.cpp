// Must NOT link: a reachable malloc.
#include <cstdlib>

extern "C" {
void* volatile g_sink{nullptr};
void SysTick_Handler() {}
[[noreturn]] void firmware_main() {
  g_sink = std::malloc(16);
  for (;;) {
  }
}
}
