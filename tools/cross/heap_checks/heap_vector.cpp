// Must NOT link: a host habit, std::vector growth, allocates through operator new.
#include <vector>

extern "C" {
int* volatile g_sink{nullptr};
void SysTick_Handler() {}
[[noreturn]] void firmware_main() {
  static std::vector<int> v;
  v.push_back(1);
  g_sink = v.data();
  for (;;) {
  }
}
}
