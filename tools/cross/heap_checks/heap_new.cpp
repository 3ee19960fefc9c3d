// Must NOT link: a reachable operator new (the pointer escapes to a volatile, so it cannot be elided).
extern "C" {
int* volatile g_sink{nullptr};
void SysTick_Handler() {}
[[noreturn]] void firmware_main() {
  g_sink = new int(42);
  for (;;) {
  }
}
}
