// The gyro pendulum's monitor-only controller (firmware/app/gyro_pendulum_controller.hpp): zero torque from
// a good frame, the runtime's header, hold-then-safe-state on missing frames, a refused tick period.
#include "firmware/app/gyro_pendulum_controller.hpp"

#include <gtest/gtest.h>

#include "firmware/msg/fault_bits.hpp"

namespace gyrostab {
namespace gyro_pendulum_controller_test {

using SensorFrame = msg::gyro_pendulum::SensorFrame;
using ActuatorFrame = msg::gyro_pendulum::ActuatorFrame;

SensorFrame frame(std::uint64_t tick) {
  SensorFrame f;
  f.tick = tick;
  f.time_ns = static_cast<std::int64_t>(tick) * 20'000'000;
  f.sample_time_ns = f.time_ns;
  f.sequence = static_cast<std::uint32_t>(tick);
  f.alpha_rad = 0.03;  // the velocity error of a tuned instrument: not corrected
  f.beta_rad = -0.01;
  return f;
}

TEST(GyroPendulumController, CommandsZeroTorqueFromAGoodFrame) {
  firmware::GyroPendulumConfig c;
  c.runtime.tick_period_ns = 20'000'000;
  ASSERT_TRUE(firmware::GyroPendulumController::check(c).ok);
  firmware::GyroPendulumController ctl(c);
  ActuatorFrame out;
  for (std::uint64_t k = 0; k < 5; ++k) {
    const SensorFrame f = frame(k);
    ctl.step(k, &f, out);
    EXPECT_EQ(out.tick, k);
    EXPECT_EQ(out.time_ns, static_cast<std::int64_t>(k) * 20'000'000);
    EXPECT_EQ(out.torque_F1_Nm, 0.0);
    EXPECT_EQ(out.torque_F2_Nm, 0.0);
    EXPECT_EQ(out.status & msg::bit(msg::FaultBit::kSafeState), 0u);
  }
}

TEST(GyroPendulumController, MissingFramesGiveTheSafeState) {
  firmware::GyroPendulumConfig c;
  firmware::GyroPendulumController ctl(c);
  ActuatorFrame out;
  const SensorFrame f = frame(0);
  ctl.step(0, &f, out);
  ctl.step(1, nullptr, out);
  EXPECT_NE(out.status & msg::bit(msg::FaultBit::kHoldingLastGood), 0u);
  ctl.step(2, nullptr, out);
  EXPECT_NE(out.status & msg::bit(msg::FaultBit::kSafeState), 0u);
  EXPECT_EQ(out.torque_F1_Nm, 0.0);
  EXPECT_EQ(out.torque_F2_Nm, 0.0);
}

TEST(GyroPendulumController, RefusesANonPositiveTick) {
  firmware::GyroPendulumConfig c;
  c.runtime.tick_period_ns = 0;
  EXPECT_FALSE(firmware::GyroPendulumController::check(c).ok);
  firmware::GyroPendulumController ctl(c);
  EXPECT_FALSE(ctl.armed());
}

}  // namespace gyro_pendulum_controller_test
}  // namespace gyrostab
