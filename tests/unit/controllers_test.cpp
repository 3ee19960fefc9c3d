// The device controllers of firmware/app/ through their common API (controller_runtime.hpp): for each of the
// ship roll damper (active and passive), monorail, servo gyro and power stabilizer — a good frame gives a
// command with the right fields and values; the header echoes tick, time and sensor tick and counts the
// sequence +1 per frame; a missing or NaN frame is held for one tick and then gives the safe state with the
// reason bit; zero heap allocations over 1e6 steps. Then the runtime's own rules: refused configurations,
// the multi-rate relation base tick / control / drive, start-up, recovery.
// Expected torques are computed here from the book's formulas (the laws' headers), not from the laws.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "firmware/app/monorail_controller.hpp"
#include "firmware/app/power_stabilizer_controller.hpp"
#include "firmware/app/servo_gyro_controller.hpp"
#include "firmware/app/ship_roll_damper_controller.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/msg/fault_bits.hpp"
#include "tests/support/alloc_counter.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab::firmware {
namespace controllers_test {

using msg::ActuatorFrame;
using msg::FaultBit;
using msg::SensorFrame;

constexpr std::int64_t kTickNs = 1'000'000;

template <class Frame>
void set_header(Frame& f, std::uint64_t k) {
  f.tick = k;
  f.time_ns = static_cast<std::int64_t>(k) * kTickNs;
  f.sample_time_ns = f.time_ns;
  f.sequence = static_cast<std::uint32_t>(k + 7);
}

// Every command at its signal table's safe value (for the union fixture: zero torques and voltages, the
// brake on) and the safe-state bit.
template <class Frame>
bool is_safe_command(const Frame& c) {
  const auto specs = msg::specs_of<Frame>();
  for (std::size_t i = 0; i < specs.size(); ++i)
    if (msg::signal_value(c, i) != specs[i].safe) return false;
  return msg::has(c.status, FaultBit::kSafeState);
}
static_assert(msg::specs_of<ActuatorFrame>()[msg::CommandIndex::precession_brake].safe == 1.0);

// ------------------------------------------------------------------------------ one traits type per device
// Each: the controller type, a default Config, and the expected command of a fresh controller on frame f
// (first control run; for the servo gyro the PI integral is still zero then).

// The ship roll damper's frames: a good frame, the precession torque, two frames with a NaN in a signal the law
// reads.
struct ShipFrames {
  using SensorFrame = msg::ship_roll_damper::SensorFrame;
  using ActuatorFrame = msg::ship_roll_damper::ActuatorFrame;
  static SensorFrame frame(std::uint64_t k) {
    const double x = static_cast<double>(k % 100) * 1e-5;
    SensorFrame f{};
    set_header(f, k);
    f.roll_rad = 0.02 + x;
    f.roll_rate_rad_s = 0.01 - x;
    f.precession_angle_rad = 0.03 - x;
    f.precession_rate_rad_s = -0.01 + x;
    return f;
  }
  static double torque(const ActuatorFrame& c) { return c.precession_torque_Nm; }
  static void poison(SensorFrame& f5, SensorFrame& f6) {
    f5.precession_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
    f6.roll_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
  }
};

struct ShipActive : ShipFrames {
  using Controller = ShipRollDamperController;
  static Controller::Config config() { return {}; }
  static void expect_command(const SensorFrame& f, const ActuatorFrame& c) {
    const ActivePrecessionParams p{};
    const double phi_rate = f.roll_rate_rad_s, beta = f.precession_angle_rad;
    const double beta_rate = f.precession_rate_rad_s;
    // Active law inside the soft limit, not braking: k_r cosβ φ' − d_c β' − k_c β.
    const double M2 = p.roll_rate_gain * std::cos(beta) * phi_rate - p.precession_damping * beta_rate -
                      p.centring_stiffness * beta;
    EXPECT_NEAR(c.precession_torque_Nm, M2, 1e-12 * std::abs(M2));
    EXPECT_EQ(c.precession_brake, 0.0);
  }
};

struct ShipPassive : ShipFrames {
  using Controller = ShipRollDamperController;
  static Controller::Config config() {
    Controller::Config c{};
    c.mode = ShipRollDamperMode::kPassiveBrake;
    return c;
  }
  static void expect_command(const SensorFrame& f, const ActuatorFrame& c) {
    const double M2 = -PrecessionBrakeParams{}.d2 * f.precession_rate_rad_s;  // −d2 β'
    EXPECT_DOUBLE_EQ(c.precession_torque_Nm, M2);
    EXPECT_EQ(c.precession_brake, 0.0);
  }
};

struct Monorail {
  using Controller = MonorailController;
  using SensorFrame = msg::monorail::SensorFrame;
  using ActuatorFrame = msg::monorail::ActuatorFrame;
  static Controller::Config config() { return {}; }
  static SensorFrame frame(std::uint64_t k) {
    const double x = static_cast<double>(k % 100) * 1e-5;
    SensorFrame f{};
    set_header(f, k);
    f.tilt_rad = 0.02 + x;
    f.tilt_rate_rad_s = 0.01 - x;
    f.case_angle_rad = 0.03 - x;
    f.case_rate_rad_s = -0.01 + x;
    return f;
  }
  static double torque(const ActuatorFrame& c) { return c.motor_torque_Nm; }
  static void poison(SensorFrame& f5, SensorFrame& f6) {
    f5.case_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
    f6.tilt_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
  }
  static void expect_command(const SensorFrame& f, const ActuatorFrame& c) {
    const MonorailMotorParams p{};
    const double M2 = p.k * f.tilt_rad - p.d * f.case_rate_rad_s;  // (14.2)
    EXPECT_DOUBLE_EQ(c.motor_torque_Nm, M2);
    EXPECT_EQ(c.precession_brake, 0.0);
  }
};

struct ServoGyro {
  using Controller = ServoGyroController;
  using SensorFrame = msg::servo_gyro::SensorFrame;
  using ActuatorFrame = msg::servo_gyro::ActuatorFrame;
  static Controller::Config config() {
    Controller::Config c{};
    c.reference = 0.02;  // Ω [rad/s], small so the first command is not saturated
    return c;
  }
  static SensorFrame frame(std::uint64_t k) {
    const double x = static_cast<double>(k % 100) * 1e-5;
    SensorFrame f{};
    set_header(f, k);
    f.alpha_rad = 0.01 + x;
    f.drive_angle_rad = 0.03 - x;
    f.alpha_rate_rad_s = 0.02 + x;
    f.drive_rate_rad_s = -0.01 + x;
    return f;
  }
  static double torque(const ActuatorFrame& c) { return c.motor_torque_Nm; }
  static void poison(SensorFrame& f5, SensorFrame& f6) {
    f5.drive_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
    f6.alpha_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
  }
  static void expect_command(const SensorFrame& f, const ActuatorFrame& c) {
    const ServoGyroParams p{};
    const double beta = f.drive_angle_rad;
    // First run: k_p (Ω − β') − H cosβ α' (14.43), integral still 0.
    const double M2 = p.rate_kp * (0.02 - f.drive_rate_rad_s) - p.H * std::cos(beta) * f.alpha_rate_rad_s;
    EXPECT_NEAR(c.motor_torque_Nm, M2, 1e-12 * std::abs(M2));
    EXPECT_EQ(c.precession_brake, 0.0);
  }
};

struct PowerStabilizer {
  using Controller = PowerStabilizerController;
  using SensorFrame = msg::power_stabilizer::SensorFrame;
  using ActuatorFrame = msg::power_stabilizer::ActuatorFrame;
  static Controller::Config config() { return {}; }
  static SensorFrame frame(std::uint64_t k) {
    const double x = static_cast<double>(k % 100) * 1e-5;
    SensorFrame f{};
    set_header(f, k);
    f.alpha_rad = 0.01 + x;
    f.beta_rad = 0.03 - x;
    f.alpha_rate_rad_s = 0.02 + x;
    f.beta_rate_rad_s = -0.01 + x;
    f.motor1_current_A = 0.1;
    f.motor2_current_A = -0.1;
    f.rotor_speed_rad_s = 500.0;
    return f;
  }
  static double torque(const ActuatorFrame& c) { return c.motor2_torque_Nm; }
  static void poison(SensorFrame& f5, SensorFrame& f6) {
    f5.beta_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
    f6.alpha_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
  }
  static void expect_command(const SensorFrame& f, const ActuatorFrame& c) {
    const PowerStabilizerConfig p{};
    // (14.19) + rate damping: M1 = −k1 β − d1 α', M2 = k2 α − d2 β'.
    EXPECT_DOUBLE_EQ(c.motor1_torque_Nm, -p.k1 * f.beta_rad - p.d1 * f.alpha_rate_rad_s);
    EXPECT_DOUBLE_EQ(c.motor2_torque_Nm, p.k2 * f.alpha_rad - p.d2 * f.beta_rate_rad_s);
    EXPECT_EQ(c.motor1_voltage_V, 0.0);  // drive disabled by default: torque-mode drives
    EXPECT_EQ(c.motor2_voltage_V, 0.0);
  }
};

template <class T>
class ControllerTest : public ::testing::Test {};
using Devices = ::testing::Types<ShipActive, ShipPassive, Monorail, ServoGyro, PowerStabilizer>;
TYPED_TEST_SUITE(ControllerTest, Devices);

TYPED_TEST(ControllerTest, DefaultConfigIsAccepted) {
  const auto cfg = TypeParam::config();
  const ConfigCheck c = TypeParam::Controller::check(cfg);
  EXPECT_TRUE(c.ok) << c.reason;
  typename TypeParam::Controller ctl(cfg);
  EXPECT_TRUE(ctl.armed());
}

TYPED_TEST(ControllerTest, GoodFrameGivesTheLawsCommandWithTheHeader) {
  typename TypeParam::Controller ctl(TypeParam::config());
  const typename TypeParam::SensorFrame f = TypeParam::frame(0);
  typename TypeParam::ActuatorFrame out{};
  ctl.step(0, &f, out);
  TypeParam::expect_command(f, out);
  EXPECT_EQ(out.tick, 0u);
  EXPECT_EQ(out.sensor_tick, 0u);
  EXPECT_EQ(out.sequence, 0u);
  EXPECT_EQ(out.time_ns, 0);
  EXPECT_EQ(out.status & 0xFFFFu, 0u) << "no fault-monitor bit on a good frame";
  if constexpr (requires { out.motor_voltage_V; }) {
    EXPECT_EQ(out.motor_voltage_V[0], 0.0);  // drive disabled by default: torque-mode drives
    EXPECT_EQ(out.motor_voltage_V[1], 0.0);
  }
}

TYPED_TEST(ControllerTest, HeaderEchoesTheTickAndCountsTheSequence) {
  typename TypeParam::Controller ctl(TypeParam::config());
  typename TypeParam::ActuatorFrame out{};
  for (std::uint64_t k = 0; k < 50; ++k) {
    const typename TypeParam::SensorFrame f = TypeParam::frame(k);
    ctl.step(k, &f, out);
    ASSERT_EQ(out.tick, k);
    ASSERT_EQ(out.sensor_tick, k);
    ASSERT_EQ(out.time_ns, static_cast<std::int64_t>(k) * kTickNs);
    ASSERT_EQ(out.sequence, static_cast<std::uint32_t>(k));
    ASSERT_FALSE(msg::has(out.status, FaultBit::kSafeState));
  }
  EXPECT_EQ(ctl.control_counters().runs, 50u);
  EXPECT_EQ(ctl.fault_counters().good_frames, 50u);
  EXPECT_EQ(ctl.ticks_run(), 50u);
}

// Ticks 0..4 good, then `bad` at ticks 5 and 6: 5 is held (the command from frame 4), 6 is the safe state
// with `reason`; the sequence keeps counting.
template <class Traits>
void expect_hold_then_safe(const typename Traits::SensorFrame* bad5, const typename Traits::SensorFrame* bad6,
                           FaultBit reason) {
  typename Traits::Controller ctl(Traits::config());
  typename Traits::ActuatorFrame out{};
  for (std::uint64_t k = 0; k < 5; ++k) {
    const typename Traits::SensorFrame f = Traits::frame(k);
    ctl.step(k, &f, out);
  }
  const typename Traits::ActuatorFrame before = out;
  ctl.step(5, bad5, out);
  EXPECT_TRUE(msg::has(out.status, FaultBit::kHoldingLastGood));
  EXPECT_TRUE(msg::has(out.status, reason));
  EXPECT_FALSE(msg::has(out.status, FaultBit::kSafeState));
  EXPECT_EQ(out.sensor_tick, 4u) << "computed from the held frame of tick 4";
  EXPECT_EQ(out.tick, 5u);
  EXPECT_EQ(out.sequence, 5u);
  if constexpr (requires { out.precession_brake; }) {
    EXPECT_EQ(out.precession_brake, 0.0);
  }
  EXPECT_TRUE(std::isfinite(Traits::torque(out)));
  if constexpr (!std::is_same_v<Traits, ServoGyro>) {  // static laws: the same frame gives the same torque
    EXPECT_EQ(Traits::torque(out), Traits::torque(before));
  }
  ctl.step(6, bad6, out);
  EXPECT_TRUE(is_safe_command(out));
  EXPECT_TRUE(msg::has(out.status, reason));
  EXPECT_FALSE(msg::has(out.status, FaultBit::kHoldingLastGood));
  EXPECT_EQ(out.sequence, 6u);
  // Latched: good frames do not release it without acknowledge().
  const typename Traits::SensorFrame f7 = Traits::frame(7);
  ctl.step(7, &f7, out);
  EXPECT_TRUE(is_safe_command(out));
  EXPECT_EQ(ctl.fault_counters().trips, 1u);
}

TYPED_TEST(ControllerTest, MissingFrameIsHeldOneTickThenSafeStateWithTheReason) {
  expect_hold_then_safe<TypeParam>(nullptr, nullptr, FaultBit::kSensorMissing);
}

TYPED_TEST(ControllerTest, NaNFrameIsHeldOneTickThenSafeStateWithTheReason) {
  typename TypeParam::SensorFrame f5 = TypeParam::frame(5), f6 = TypeParam::frame(6);
  TypeParam::poison(f5, f6);
  expect_hold_then_safe<TypeParam>(&f5, &f6, FaultBit::kSensorNonFinite);
}

TYPED_TEST(ControllerTest, BeforeTheFirstFrameTheOutputIsTheSafeCommand) {
  typename TypeParam::Controller ctl(TypeParam::config());
  typename TypeParam::ActuatorFrame out{};
  ctl.step(0, nullptr, out);
  EXPECT_TRUE(is_safe_command(out));
  EXPECT_TRUE(msg::has(out.status, FaultBit::kAwaitingFirstFrame));
  const typename TypeParam::SensorFrame f = TypeParam::frame(1);
  ctl.step(1, &f, out);
  EXPECT_FALSE(msg::has(out.status, FaultBit::kSafeState));
  TypeParam::expect_command(f, out);
}

TYPED_TEST(ControllerTest, AcknowledgeThenAGoodFrameRestartsTheLawFromAFreshState) {
  typename TypeParam::Controller ctl(TypeParam::config());
  typename TypeParam::ActuatorFrame out{};
  for (std::uint64_t k = 0; k < 3; ++k) {
    const typename TypeParam::SensorFrame f = TypeParam::frame(k);
    ctl.step(k, &f, out);
  }
  ctl.step(3, nullptr, out);
  ctl.step(4, nullptr, out);
  ASSERT_TRUE(is_safe_command(out));
  ctl.acknowledge();
  const typename TypeParam::SensorFrame f = TypeParam::frame(5);
  ctl.step(5, &f, out);
  EXPECT_FALSE(msg::has(out.status, FaultBit::kSafeState));
  EXPECT_EQ(ctl.fault_counters().recoveries, 1u);
  TypeParam::expect_command(f, out);  // like a fresh controller: the law state was reset in the safe state
}

TYPED_TEST(ControllerTest, ZeroHeapAllocationsOverAMillionSteps) {
  typename TypeParam::Controller ctl(TypeParam::config());
  typename TypeParam::ActuatorFrame out{};
  double sink = 0.0;
  typename TypeParam::SensorFrame f = TypeParam::frame(0);
  testing::AllocationCounter c;
  for (std::uint64_t k = 0; k < 1'000'000; ++k) {
    f = TypeParam::frame(k);
    ctl.step(k, (k % 1000 == 999) ? nullptr : &f, out);  // an occasional missing frame: the holding path too
    sink += TypeParam::torque(out);
  }
  EXPECT_EQ(c.count(), 0u);
  EXPECT_TRUE(std::isfinite(sink));
  EXPECT_EQ(ctl.fault_counters().held_ticks, 1000u);
  EXPECT_EQ(ctl.fault_counters().trips, 0u);
}

// ------------------------------------------------------------------------------------- the runtime's rules

TEST(ControllerRuntime, ARefusedMonorailGainGivesTheBoundsAndOnlyTheSafeCommand) {
  MonorailConfig cfg{};
  cfg.law.k = 1001.0;  // below the window 1112 < k < 14388 (docs/models/monorail.md)
  const ConfigCheck c = MonorailController::check(cfg);
  EXPECT_FALSE(c.ok);
  EXPECT_NEAR(c.lower, 1112.0, 0.5);
  EXPECT_NEAR(c.upper, 14388.0, 0.5);
  MonorailController ctl(cfg);
  EXPECT_FALSE(ctl.armed());
  Monorail::ActuatorFrame out{};
  for (std::uint64_t k = 0; k < 5; ++k) {
    const Monorail::SensorFrame f = Monorail::frame(k);
    ctl.step(k, &f, out);
    ASSERT_TRUE(is_safe_command(out));
    ASSERT_TRUE((out.status & bit(LawStatusBit::kConfigRefused)) != 0u);
    ASSERT_EQ(out.sequence, static_cast<std::uint32_t>(k));
  }
  EXPECT_EQ(ctl.control_counters().runs, 0u);
}

TEST(ControllerRuntime, ARefusedPowerStabilizerGainReportsTheGainMargin) {
  PowerStabilizerControllerConfig cfg{};
  cfg.loops.k1 = cfg.loops.k2 = 40.0;  // above k_max = 28.12 N m/rad for d = 0.5 (S2 case)
  const ConfigCheck c = PowerStabilizerController::check(cfg);
  EXPECT_FALSE(c.ok);
  EXPECT_LT(c.value, 1.0) << "gain margin sigma_max";
  EXPECT_NEAR(c.upper, 28.12, 0.01);
}

TEST(ControllerRuntime, DivisorsMustNestAndThePeriodMustBePositive) {
  MonorailConfig cfg{};
  cfg.runtime.control_divisor = 10;
  cfg.runtime.drive_divisor = 3;
  EXPECT_FALSE(MonorailController::check(cfg).ok);
  cfg.runtime.drive_divisor = 5;
  EXPECT_TRUE(MonorailController::check(cfg).ok);
  cfg.runtime.tick_period_ns = 0;
  EXPECT_FALSE(MonorailController::check(cfg).ok);
}

TEST(ControllerRuntime, FastBaseTickRunsTheLawEveryTenthTickAndTheDriveEveryTick) {
  // Base 100 µs: law at 1 kHz (control_divisor 10), current loops at 10 kHz (drive_divisor 1). The torque
  // changes only on control ticks (k ≡ 0 mod 10, held in between); the voltage is recomputed every tick.
  PowerStabilizerControllerConfig cfg{};
  cfg.runtime.tick_period_ns = 100'000;
  cfg.runtime.control_divisor = 10;
  cfg.runtime.drive_divisor = 1;
  cfg.drive.enabled = true;
  for (TorqueCurrentLoopParams& d : cfg.drive.axis) {
    d.bandwidth_rad_s = 2000.0;           // ω_c T_d = 0.2 ≤ ln(4/3)
    d.torque_constant_Nm_per_A = 1e3;     // i_ref = M/k_t small: no saturation
  }
  ASSERT_TRUE(PowerStabilizerController::check(cfg).ok) << PowerStabilizerController::check(cfg).reason;
  PowerStabilizerController ctl(cfg);
  const PowerStabilizerConfig& p = cfg.loops;
  PowerStabilizer::ActuatorFrame out{};
  double torque_at_last_control = 0.0, last_voltage = 0.0;
  int voltage_changes = 0;
  for (std::uint64_t k = 0; k < 100; ++k) {
    PowerStabilizer::SensorFrame f = PowerStabilizer::frame(k);
    f.time_ns = static_cast<std::int64_t>(k) * 100'000;
    f.alpha_rad = 0.01 + 1e-4 * static_cast<double>(k);               // α changes every tick
    f.motor2_current_A = 1e-3 * static_cast<double>(k % 7);           // and so does the current
    ctl.step(k, &f, out);
    ASSERT_EQ(out.time_ns, static_cast<std::int64_t>(k) * 100'000);
    if (k % 10 == 0) {
      torque_at_last_control = out.motor2_torque_Nm;
      ASSERT_DOUBLE_EQ(torque_at_last_control, p.k2 * f.alpha_rad - p.d2 * f.beta_rate_rad_s);
      ASSERT_EQ(out.sensor_tick, k);
    } else {
      ASSERT_EQ(out.motor2_torque_Nm, torque_at_last_control) << "held between control runs";
      ASSERT_EQ(out.sensor_tick, k - k % 10) << "the frame the held torque came from";
    }
    if (out.motor2_voltage_V != last_voltage) ++voltage_changes;
    last_voltage = out.motor2_voltage_V;
  }
  EXPECT_EQ(ctl.control_counters().runs, 10u);
  EXPECT_TRUE(ctl.has_drive_task());
  EXPECT_EQ(ctl.drive_counters().runs, 100u);
  EXPECT_GT(voltage_changes, 90) << "the current loop acts every base tick";
  EXPECT_FALSE((out.status & bit(LawStatusBit::kDriveVoltageSaturated)) != 0u);
  EXPECT_NE(out.motor2_voltage_V, 0.0);
}

TEST(ControllerRuntime, TheCurrentLoopTurnsTheTorqueIntoAVoltageOfTheSameSign) {
  // Power stabilizer with only axis 1's gimbal deflected: M2 = k2 α > 0, M1 = −d1 α' = 0. The current loop
  // drives i toward M2/k_t with the measured current held at 0 (an open winding): the voltage rises and
  // saturates at +voltage_limit; axis 1's loop has nothing to do.
  PowerStabilizerControllerConfig cfg{};
  cfg.drive.enabled = true;
  for (TorqueCurrentLoopParams& d : cfg.drive.axis) d.bandwidth_rad_s = 200.0;  // ω_c T = 0.2 at 1 ms
  ASSERT_TRUE(PowerStabilizerController::check(cfg).ok) << PowerStabilizerController::check(cfg).reason;
  PowerStabilizerController ctl(cfg);
  PowerStabilizer::ActuatorFrame out{};
  for (std::uint64_t k = 0; k < 200; ++k) {
    PowerStabilizer::SensorFrame f{};
    f.tick = k;
    f.time_ns = static_cast<std::int64_t>(k) * kTickNs;
    f.sequence = static_cast<std::uint32_t>(k);
    f.alpha_rad = 0.05;
    f.rotor_speed_rad_s = 500.0;
    ctl.step(k, &f, out);
  }
  EXPECT_GT(out.motor2_torque_Nm, 0.0);
  EXPECT_EQ(out.motor1_torque_Nm, 0.0);
  EXPECT_EQ(out.motor2_voltage_V, cfg.drive.axis[1].voltage_limit_V);  // channel 1: axis 2
  EXPECT_TRUE((out.status & bit(LawStatusBit::kDriveVoltageSaturated)) != 0u);
  EXPECT_EQ(out.motor1_voltage_V, 0.0) << "no torque demanded on axis 1";
}

TEST(ControllerRuntime, ActiveShipBeyondTheSoftLimitReportsItAndBrakesTowardTheStop) {
  ShipRollDamperController ctl(ShipRollDamperConfig{});
  const ActivePrecessionParams p{};
  ShipActive::ActuatorFrame out{};
  ShipActive::SensorFrame f = ShipActive::frame(0);
  f.precession_angle_rad = p.beta_soft + 0.02;
  f.precession_rate_rad_s = 0.5;  // moving out beyond the limit: braking
  ctl.step(0, &f, out);
  EXPECT_TRUE((out.status & bit(LawStatusBit::kBeyondSoftLimit)) != 0u);
  EXPECT_TRUE((out.status & bit(LawStatusBit::kEndStopBraking)) != 0u);
  EXPECT_LT(out.precession_torque_Nm, 0.0);
  EXPECT_EQ(out.precession_brake, 0.0) << "the law brakes with torque, never with the holding brake";
}

TEST(ControllerRuntime, ServoGyroTorqueDemandBecomesARateReference) {
  // Demand M1 = −0.01 N m on axis 1 ⇒ Ω = −M1/(H cosβ) = 0.01/cos(0.03) rad/s; first command k_p (Ω − β') +
  // ff.
  ServoGyroConfig cfg{};
  cfg.reference_kind = ServoGyroReference::kAxis1Torque;
  cfg.reference = -0.01;
  ServoGyroController ctl(cfg);
  const ServoGyro::SensorFrame f = ServoGyro::frame(0);
  ServoGyro::ActuatorFrame out{};
  ctl.step(0, &f, out);
  const ServoGyroParams p{};
  const double beta = f.drive_angle_rad;
  const double omega = 0.01 / (p.H * std::cos(beta));
  const double M2 = p.rate_kp * (omega - f.drive_rate_rad_s) - p.H * std::cos(beta) * f.alpha_rate_rad_s;
  EXPECT_NEAR(out.motor_torque_Nm, M2, 1e-12);
}

}  // namespace controllers_test
}  // namespace gyrostab::firmware
