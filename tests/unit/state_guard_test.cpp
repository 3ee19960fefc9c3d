// The closed loop's runtime guard (tools/loop/state_guard.hpp): a run whose plant state goes non-finite stops at
// that tick and names the component that went first with its last finite value; a device that does not name
// its state still stops at the tick.
#include "tools/loop/closed_loop.hpp"

#include "tests/support/test_ports.hpp"
#include "tests/support/union_frames.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace gyrostab {
namespace state_guard_test {

struct NullController {
  void step(std::uint64_t, const msg::SensorFrame*, msg::ActuatorFrame& out) { out = msg::ActuatorFrame{}; }
};

// x = [alpha, beta, beta_rate]: alpha grows linearly, beta_rate doubles each tick and is forced to +inf at
// tick 6 (beta_rate was 2^6 = 64 at the end of tick 5), beta goes NaN one tick later (never reached).
struct BlowingUpDevice {
  using SensorFrame = msg::SensorFrame;  // the union fixture's frames (tests/support/union_frames.hpp)
  using ActuatorFrame = msg::ActuatorFrame;
  static constexpr int kGuardedStates = 3;
  static const char* state_name(int i) {
    static const char* const names[] = {"alpha_rad", "beta_rad", "beta_rate_rad_s"};
    return names[i];
  }
  double state_value(int i) const { return x[static_cast<std::size_t>(i)]; }

  std::array<double, 3> x{0.0, 0.5, 1.0};
  void sense(std::int64_t, msg::SensorFrame& f) { f = msg::SensorFrame{}; }
  void actuate(const msg::ActuatorFrame&) {}
  void advance(std::int64_t k) {
    x[0] += 0.25;
    x[2] = k == 6 ? std::numeric_limits<double>::infinity() : 2.0 * x[2];
    if (k == 7) x[1] = std::nan("");
  }
  bool finite() const { return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]); }
  msg::ActuatorFrame initial_command() const { return {}; }
};

TEST(StateGuard, NamesTheFirstNonFiniteComponentAndItsLastFiniteValue) {
  tools::PlantPortOf<BlowingUpDevice> plant;
  testing::LawPort<NullController> controller;
  tools::LoopConfig cfg;
  cfg.duration_s = 1.0;
  const tools::LoopOutcome out = tools::run_closed_loop(plant, controller, cfg, nullptr);
  ASSERT_TRUE(out.diverged);
  EXPECT_EQ(out.diverged_tick, 6);
  EXPECT_EQ(out.ticks_run, 7);
  ASSERT_NE(out.diverged_state.name, nullptr);
  EXPECT_STREQ(out.diverged_state.name, "beta_rate_rad_s");
  EXPECT_EQ(out.diverged_state.component, 2);
  EXPECT_EQ(out.diverged_state.last_finite, 64.0);  // 2^6 after ticks 0..5
  EXPECT_TRUE(std::isinf(out.diverged_state.value));

  const std::string msg = tools::describe_non_finite("blow-up", out.diverged_tick, out.diverged_state);
  EXPECT_NE(msg.find("tick 6"), std::string::npos) << msg;
  EXPECT_NE(msg.find("beta_rate_rad_s = inf"), std::string::npos) << msg;
  EXPECT_NE(msg.find("last finite value 64"), std::string::npos) << msg;
}

// Without the optional part of the concept the guard still stops at the tick and says so.
struct AnonymousDevice {
  using SensorFrame = msg::SensorFrame;  // the union fixture's frames (tests/support/union_frames.hpp)
  using ActuatorFrame = msg::ActuatorFrame;
  int ticks{0};
  void sense(std::int64_t, msg::SensorFrame& f) { f = msg::SensorFrame{}; }
  void actuate(const msg::ActuatorFrame&) {}
  void advance(std::int64_t) { ++ticks; }
  bool finite() const { return ticks < 4; }
  msg::ActuatorFrame initial_command() const { return {}; }
};

TEST(StateGuard, ADeviceThatDoesNotNameItsStateStillStopsAtTheTick) {
  static_assert(!tools::NamesItsState<AnonymousDevice>);
  static_assert(tools::NamesItsState<BlowingUpDevice>);
  tools::PlantPortOf<AnonymousDevice> plant;
  testing::LawPort<NullController> controller;
  tools::LoopConfig cfg;
  cfg.duration_s = 1.0;
  const tools::LoopOutcome out = tools::run_closed_loop(plant, controller, cfg, nullptr);
  ASSERT_TRUE(out.diverged);
  EXPECT_EQ(out.diverged_tick, 3);
  EXPECT_EQ(out.diverged_state.name, nullptr);
  EXPECT_EQ(tools::describe_non_finite("s", 3, out.diverged_state), "s: the plant state became non-finite at tick 3");
}

}  // namespace state_guard_test
}  // namespace gyrostab
