// The closed loop's runtime guard: a device that names its plant state lets the loop say, when the state
// becomes non-finite, WHICH component went first, its value and its last finite value (the value at the end of
// the previous tick), beside the tick. Optional part of the Device concept (closed_loop.hpp):
//   static constexpr int kGuardedStates;      // number of named state components (≤ kMaxGuardedStates)
//   static const char* state_name(int i);     // a static string, e.g. "beta_rate_rad_s"
//   double state_value(int i) const;          // component i now
// Cost when present: kGuardedStates copies per tick into a fixed array (no allocation); a device without it
// compiles to the bare `finite()` check.
#pragma once

#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <string>

namespace gyrostab::tools {

inline constexpr int kMaxGuardedStates = 32;

template <class Device>
concept NamesItsState = requires(const Device& d, int i) {
  { Device::kGuardedStates } -> std::convertible_to<int>;
  { Device::state_name(i) } -> std::convertible_to<const char*>;
  { d.state_value(i) } -> std::convertible_to<double>;
};

// Where the state went non-finite (component -1: the device does not name its state, or its finite() saw
// something outside the named components).
struct NonFiniteState {
  int component{-1};
  const char* name{nullptr};
  double value{0.0};        // the non-finite value
  double last_finite{0.0};  // its value at the end of the previous tick (the initial state at tick 0)
};

template <class Device>
class StateGuard {
 public:
  // Before the tick's advance: remember the (finite) state.
  void remember(const Device& d) {
    if constexpr (NamesItsState<Device>) {
      static_assert(Device::kGuardedStates <= kMaxGuardedStates, "raise kMaxGuardedStates");
      for (int i = 0; i < Device::kGuardedStates; ++i) last_[static_cast<std::size_t>(i)] = d.state_value(i);
    } else {
      (void)d;
    }
  }
  // After finite() failed: the first non-finite named component.
  NonFiniteState locate(const Device& d) const {
    NonFiniteState s;
    if constexpr (NamesItsState<Device>) {
      for (int i = 0; i < Device::kGuardedStates; ++i) {
        const double v = d.state_value(i);
        if (!std::isfinite(v)) {
          s.component = i;
          s.name = Device::state_name(i);
          s.value = v;
          s.last_finite = last_[static_cast<std::size_t>(i)];
          break;
        }
      }
    } else {
      (void)d;
    }
    return s;
  }

 private:
  std::array<double, NamesItsState<Device> ? kMaxGuardedStates : 1> last_{};
};

// The message of a run stopped by the guard (not on the hot path).
inline std::string describe_non_finite(const std::string& scene, std::int64_t tick, const NonFiniteState& s) {
  char buf[512];
  if (s.name != nullptr) {
    std::snprintf(buf, sizeof buf,
                  "%s: the plant state became non-finite at tick %lld: %s = %g (state component %d), last finite "
                  "value %.17g at the end of tick %lld",
                  scene.c_str(), static_cast<long long>(tick), s.name, s.value, s.component, s.last_finite,
                  static_cast<long long>(tick - 1));
  } else {
    std::snprintf(buf, sizeof buf, "%s: the plant state became non-finite at tick %lld", scene.c_str(),
                  static_cast<long long>(tick));
  }
  return buf;
}

}  // namespace gyrostab::tools
