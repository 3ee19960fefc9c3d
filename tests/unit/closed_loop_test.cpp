// The in-process loop's timing contract: the command computed from the sensor frame of tick k is applied by
// the plant at exactly tick k + latency (docs/architecture.md, the loop), for latency 0, 1 and 3; before that
// the device's initial command holds.
#include "tools/loop/closed_loop.hpp"

#include "tests/support/test_ports.hpp"
#include "tests/support/union_frames.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace gyrostab {
namespace closed_loop_test {

// The controller echoes the sensor frame's tick in its torque; the plant logs what it is given each tick.
struct EchoController {
  void step(std::uint64_t tick, const msg::SensorFrame* f, msg::ActuatorFrame& out) {
    out = msg::ActuatorFrame{};
    out.tick = tick;
    out.sensor_tick = f->tick;
    out.gimbal_torque_Nm[0] = static_cast<double>(f->tick);
  }
};

struct LoggingDevice {
  using SensorFrame = msg::SensorFrame;  // the union fixture's frames (tests/support/union_frames.hpp)
  using ActuatorFrame = msg::ActuatorFrame;
  std::vector<double> applied_at;  // per tick: the torque the plant integrated with
  double current{-1.0};
  void sense(std::int64_t tick, msg::SensorFrame& f) {
    f = msg::SensorFrame{};
    f.tick = static_cast<std::uint64_t>(tick);
  }
  void actuate(const msg::ActuatorFrame& a) { current = a.gimbal_torque_Nm[0]; }
  void advance(std::int64_t) { applied_at.push_back(current); }
  bool finite() const { return true; }
  msg::ActuatorFrame initial_command() const {
    msg::ActuatorFrame a{};
    a.gimbal_torque_Nm[0] = -1.0;
    return a;
  }
};

TEST(ClosedLoop, CommandFromFrameKIsAppliedAtTickKPlusLatency) {
  for (const int latency : {0, 1, 3}) {
    tools::PlantPortOf<LoggingDevice> plant;
    testing::LawPort<EchoController> controller;
    const LoggingDevice& d = plant.binding();
    tools::LoopConfig cfg;
    cfg.duration_s = 0.02;
    cfg.tick_ns = 1'000'000;
    cfg.latency_ticks = latency;
    const auto out = tools::run_closed_loop(plant, controller, cfg, nullptr);
    ASSERT_EQ(out.ticks_run, 20);
    ASSERT_EQ(d.applied_at.size(), 20u);
    for (int k = 0; k < 20; ++k) {
      const double expected = k < latency ? -1.0 : static_cast<double>(k - latency);
      EXPECT_EQ(d.applied_at[static_cast<size_t>(k)], expected) << "latency " << latency << " tick " << k;
    }
  }
}

struct DivergingDevice : LoggingDevice {
  bool finite() const { return applied_at.size() < 7; }
};

TEST(ClosedLoop, StopsAtTheFirstNonFiniteStateAndSaysWhere) {
  tools::PlantPortOf<DivergingDevice> plant;
  testing::LawPort<EchoController> controller;
  tools::LoopConfig cfg;
  cfg.duration_s = 1.0;
  const auto out = tools::run_closed_loop(plant, controller, cfg, nullptr);
  EXPECT_TRUE(out.diverged);
  EXPECT_EQ(out.diverged_tick, 6);
  EXPECT_EQ(out.ticks_run, 7);
}

}  // namespace closed_loop_test
}  // namespace gyrostab
