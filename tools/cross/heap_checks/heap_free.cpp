// Must NOT link: a reachable free (e.g. a C library helper that releases memory).
#include <cstdlib>

extern "C" {
void* volatile g_sink{nullptr};
void SysTick_Handler() {}
[[noreturn]] void firmware_main() {
  std::free(g_sink);
  for (;;) {
  }
}
}
