// The gyro instruments' firmware: the correction laws of the gyro vertical (12.35), the
// gyrocompass law (13.8) and its tuning formulas (13.12), (13.26), the Schuler loop (16.36)/(16.39), and the
// three controllers through the common runtime API (frame mapping, hold and safe state on bad frames,
// refused configurations, zero allocations). Expected values are computed here from the book's formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "firmware/app/gyro_vertical_controller.hpp"
#include "firmware/app/gyrocompass_controller.hpp"
#include "firmware/app/inertial_platform_controller.hpp"
#include "firmware/control/gyro_vertical_correction.hpp"
#include "firmware/control/gyrocompass_law.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/schuler_loop.hpp"
#include "firmware/msg/fault_bits.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gyrostab::firmware {
namespace gyro_instrument_laws_test {

constexpr double kPi = std::numbers::pi;

GyroVerticalCorrectionParams all_rows() {
  GyroVerticalCorrectionParams p;
  p.H = 0.5;
  p.c1 = 1.0, p.c2 = 2.0;
  p.d1 = 3.0, p.d2 = 4.0;
  p.r1 = 5.0, p.r2 = 6.0;
  p.f1 = 7.0, p.f2 = 8.0;
  p.g1 = 9.0, p.g2 = 10.0;
  p.torque_limit_Nm = 1e6;
  return p;
}

TEST(GyroVerticalCorrection, EachRowOfTable12_35) {
  const GyroVerticalCorrectionParams p = all_rows();
  const CorrectionSignals s{0.1, -0.2, 0.3, -0.4, 0.0};
  const CorrectionTorques r1 = pendulous_row(p, s), r2 = viscous_row(p, s), r3 = coulomb_row(p, s),
                          r4 = linear_correction_row(p, s), r5 = relay_correction_row(p, s);
  EXPECT_DOUBLE_EQ(r1.M1, -1.0 * 0.1);
  EXPECT_DOUBLE_EQ(r1.M2, -2.0 * -0.2);
  EXPECT_DOUBLE_EQ(r2.M1, -3.0 * 0.3);
  EXPECT_DOUBLE_EQ(r2.M2, -4.0 * -0.4);
  EXPECT_DOUBLE_EQ(r3.M1, -5.0);   // −r1 sgn α'
  EXPECT_DOUBLE_EQ(r3.M2, 6.0);    // −r2 sgn β'
  EXPECT_DOUBLE_EQ(r4.M1, -7.0 * -0.2);  // −f1 e2
  EXPECT_DOUBLE_EQ(r4.M2, 8.0 * 0.1);    // +f2 e1
  EXPECT_DOUBLE_EQ(r5.M1, 9.0);    // −g1 sgn e2
  EXPECT_DOUBLE_EQ(r5.M2, 10.0);   // +g2 sgn e1
  const CorrectionTorques sum = gyro_vertical_correction(p, s);
  EXPECT_DOUBLE_EQ(sum.M1, r1.M1 + r2.M1 + r3.M1 + r4.M1 + r5.M1);
  EXPECT_DOUBLE_EQ(sum.M2, r1.M2 + r2.M2 + r3.M2 + r4.M2 + r5.M2);
  EXPECT_FALSE(sum.cut_out);
  EXPECT_FALSE(sum.limited);
}

TEST(GyroVerticalCorrection, DeadBandsCutOutAndLimit) {
  GyroVerticalCorrectionParams p = all_rows();
  p.rate_deadband = 0.5;
  p.tilt_deadband = 0.15;
  const CorrectionSignals s{0.1, -0.2, 0.3, -0.4, 0.0};
  EXPECT_DOUBLE_EQ(coulomb_row(p, s).M1, 0.0);  // |α'| ≤ band
  EXPECT_DOUBLE_EQ(relay_correction_row(p, s).M2, 0.0);  // |e1| ≤ band
  EXPECT_DOUBLE_EQ(relay_correction_row(p, s).M1, 9.0);  // |e2| > band
  EXPECT_DOUBLE_EQ(sgn_deadband(0.0, 0.0), 0.0);
  // Turn cut-out (the book's remedy): above the threshold both torques (or M1 only) are zero.
  p.turn_cutout_rate = 0.01;
  CorrectionSignals turning = s;
  turning.turn_rate = -0.02;
  CorrectionTorques t = gyro_vertical_correction(p, turning);
  EXPECT_TRUE(t.cut_out);
  EXPECT_EQ(t.M1, 0.0);
  EXPECT_EQ(t.M2, 0.0);
  p.cutout = TurnCutout::kAxis1;
  t = gyro_vertical_correction(p, turning);
  EXPECT_EQ(t.M1, 0.0);
  EXPECT_NE(t.M2, 0.0);
  turning.turn_rate = 0.005;  // below: no cut-out
  EXPECT_FALSE(gyro_vertical_correction(p, turning).cut_out);
  // Limit.
  p.torque_limit_Nm = 0.5;
  t = gyro_vertical_correction(p, s);
  EXPECT_TRUE(t.limited);
  EXPECT_LE(std::fabs(t.M1), 0.5);
  EXPECT_LE(std::fabs(t.M2), 0.5);
}

TEST(GyroVerticalCorrection, StartUpCheck) {
  GyroVerticalCorrectionParams p;
  p.f1 = p.f2 = 0.01;
  EXPECT_TRUE(check_gyro_vertical_correction(p, 1e-3).ok);
  GyroVerticalCorrectionParams bad = p;
  bad.f1 = -1.0;
  EXPECT_FALSE(check_gyro_vertical_correction(bad, 1e-3).ok);
  bad = p;
  bad.g2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(check_gyro_vertical_correction(bad, 1e-3).ok);
  bad = p;
  bad.f2 = 0.6 * p.H / 1e-3;  // (c + f) T/H > 0.5
  const ConfigCheck c = check_gyro_vertical_correction(bad, 1e-3);
  EXPECT_FALSE(c.ok);
  EXPECT_DOUBLE_EQ(c.upper, 0.5 * p.H / 1e-3);
  bad = p;
  bad.d1 = bad.d2 = p.H;  // d1 d2/H² = 1
  EXPECT_FALSE(check_gyro_vertical_correction(bad, 1e-3).ok);
  bad = p;
  bad.torque_limit_Nm = 0.0;
  EXPECT_FALSE(check_gyro_vertical_correction(bad, 1e-3).ok);
}

TEST(GyrocompassLaw, TorquesTuningAndChecks) {
  GyrocompassLawParams p{2.0, 0.05, 0.03, 1.0};
  const GyrocompassTorques t = gyrocompass_torques(p, 1e-3);
  EXPECT_DOUBLE_EQ(t.M1, -0.05e-3);  // (13.8) M1 = −f β
  EXPECT_DOUBLE_EQ(t.M2, -0.03e-3);  // electrical pendulosity M2 = −c_e β
  EXPECT_FALSE(t.limited);
  p.torque_limit_Nm = 1e-5;
  EXPECT_TRUE(gyrocompass_torques(p, 1e-3).limited);
  // (13.26) at 50°: c/H = 0.03285 /s (tuning table, docs/models/gyrocompass.md); (13.12) damping for ζ = 0.3
  // gives δ = 7.45e-4 /s.
  const double lat = 50.0 * kPi / 180.0, we = 7.292115e-5;
  const double c = schuler_tuned_pendulosity(2.0, lat, 9.81, 6.371e6, we);
  EXPECT_NEAR(c / 2.0, 0.03285, 5e-6);
  EXPECT_NEAR(gyrocompass_damping_for_ratio(2.0, c, lat, 0.3, we) / 2.0, 7.45e-4, 5e-7);
  p.torque_limit_Nm = 1.0;
  EXPECT_TRUE(check_gyrocompass_law(p, 0.01).ok);
  GyrocompassLawParams bad = p;
  bad.f = 0.6 * p.H / 0.01;
  EXPECT_FALSE(check_gyrocompass_law(bad, 0.01).ok);
  bad = p;
  bad.c_e = -1.0;
  EXPECT_FALSE(check_gyrocompass_law(bad, 0.01).ok);
  bad = p;
  bad.H = 0.0;
  EXPECT_FALSE(check_gyrocompass_law(bad, 0.01).ok);
}

TEST(SchulerLoopLaw, IntegratorTorqueResetAndChecks) {
  SchulerLoopParams p;
  p.radius = 6.371e6;
  p.H = 0.05;
  p.initial_rate[0] = 1e-5;
  p.initial_rate[1] = -2e-5;
  const double T = 5e-3;
  ASSERT_TRUE(check_schuler_loop(p, T).ok);
  SchulerLoop loop(p, T);
  const double theta[2] = {1e-4, -3e-4};
  const SchulerTorques m = loop.step(theta);
  const double w0 = 1e-5 - p.gravity_scale / p.radius * T * 1e-4;  // ω ← ω − (g0/R) θ T (16.36)
  const double w1 = -2e-5 + p.gravity_scale / p.radius * T * 3e-4;
  EXPECT_DOUBLE_EQ(loop.commanded_rate(0), w0);
  EXPECT_DOUBLE_EQ(loop.commanded_rate(1), w1);
  EXPECT_DOUBLE_EQ(m.M[0], -p.H * w0);  // (16.39) M^K = −H ω_cmd
  EXPECT_DOUBLE_EQ(m.M[1], -p.H * w1);
  EXPECT_DOUBLE_EQ(loop.velocity_estimate(0), p.radius * w0);
  loop.reset();  // keeps the navigation state
  EXPECT_DOUBLE_EQ(loop.commanded_rate(0), w0);
  const double nan_theta[2] = {std::numeric_limits<double>::quiet_NaN(), 0.0};
  loop.step(nan_theta);
  EXPECT_DOUBLE_EQ(loop.commanded_rate(0), w0);
  p.enabled[1] = false;
  SchulerLoop one(p, T);
  EXPECT_EQ(one.step(theta).M[1], 0.0);
  SchulerLoopParams bad = p;
  bad.radius = 0.0;
  EXPECT_FALSE(check_schuler_loop(bad, T).ok);
  EXPECT_FALSE(check_schuler_loop(p, 100.0).ok);  // ω_S T = 0.12 > 1e-2
  bad = p;
  bad.initial_rate[0] = 1.0;
  EXPECT_FALSE(check_schuler_loop(bad, T).ok);
}

// The header of a test frame for tick k (1 ms ticks).
template <class Frame>
Frame frame_header(std::uint64_t k) {
  Frame f{};
  f.tick = k;
  f.time_ns = static_cast<std::int64_t>(k) * 1'000'000;
  f.sample_time_ns = f.time_ns;
  f.sequence = static_cast<std::uint32_t>(k);
  return f;
}

msg::gyro_vertical::SensorFrame gyro_vertical_frame(std::uint64_t k) {
  msg::gyro_vertical::SensorFrame f = frame_header<msg::gyro_vertical::SensorFrame>(k);
  f.indicated_bank_rad = 3e-4;
  f.indicated_pitch_rad = -1e-4;
  f.turn_indicator_rad_s = 0.02;
  f.erection_e1_rad = 0.01;
  f.erection_e2_rad = -0.02;
  f.alpha_rate_rad_s = 1e-3;
  f.beta_rate_rad_s = -2e-3;
  return f;
}

msg::gyrocompass::SensorFrame gyrocompass_frame(std::uint64_t k) {
  msg::gyrocompass::SensorFrame f = frame_header<msg::gyrocompass::SensorFrame>(k);
  f.indicated_heading_rad = 0.3;
  f.follow_up_rad = -0.3;
  f.level_rad = -0.02;
  f.azimuth_rate_rad_s = 1e-3;
  f.elevation_rate_rad_s = -2e-3;
  return f;
}

msg::inertial_platform::SensorFrame inertial_platform_frame(std::uint64_t k) {
  msg::inertial_platform::SensorFrame f = frame_header<msg::inertial_platform::SensorFrame>(k);
  f.theta1_rad = 3e-4;
  f.theta2_rad = -1e-4;
  f.gyro_angle1_rad = 0.01;
  f.gyro_angle2_rad = -0.02;
  f.gyro_rate1_rad_s = 1e-3;
  f.gyro_rate2_rad_s = -2e-3;
  return f;
}

// The two torquer commands of a device's actuator frame.
struct Torques {
  double m1, m2;
};
Torques torques(const msg::gyro_vertical::ActuatorFrame& out) { return {out.torquer1_Nm, out.torquer2_Nm}; }
Torques torques(const msg::gyrocompass::ActuatorFrame& out) {
  return {out.vertical_torquer_Nm, out.east_torquer_Nm};
}
Torques torques(const msg::inertial_platform::ActuatorFrame& out) { return {out.torquer1_Nm, out.torquer2_Nm}; }

// A missing frame is held once, then the safe state: zero torque.
template <class Controller, class MakeFrame>
void expect_hold_then_safe(Controller& c, MakeFrame frame_of) {
  typename Controller::ActuatorFrame out{};
  for (std::uint64_t k = 0; k < 5; ++k) c.step(k, nullptr, out);  // awaiting the first frame: safe values
  typename Controller::SensorFrame f = frame_of(5);
  c.step(5, &f, out);
  const double m1 = torques(out).m1;
  c.step(6, nullptr, out);  // held
  EXPECT_TRUE(out.status & msg::bit(msg::FaultBit::kHoldingLastGood));
  EXPECT_EQ(torques(out).m1, m1);
  c.step(7, nullptr, out);  // safe state: zero torque
  EXPECT_TRUE(out.status & msg::bit(msg::FaultBit::kSafeState));
  EXPECT_EQ(torques(out).m1, 0.0);
  EXPECT_EQ(torques(out).m2, 0.0);
}

TEST(GyroInstrumentControllers, GyroVerticalMapsTheFrameOntoTheLaw) {
  GyroVerticalConfig cfg;
  cfg.law.f1 = cfg.law.f2 = 0.01;
  cfg.law.c1 = cfg.law.c2 = 0.002;
  cfg.law.turn_cutout_rate = 0.05;
  GyroVerticalController c(cfg);
  ASSERT_TRUE(c.armed());
  msg::gyro_vertical::SensorFrame f = gyro_vertical_frame(0);
  msg::gyro_vertical::ActuatorFrame out{};
  c.step(0, &f, out);
  EXPECT_DOUBLE_EQ(out.torquer1_Nm, -0.002 * 0.01 - 0.01 * -0.02);  // −c1 e1 − f1 e2
  EXPECT_DOUBLE_EQ(out.torquer2_Nm, -0.002 * -0.02 + 0.01 * 0.01);  // −c2 e2 + f2 e1
  f = gyro_vertical_frame(1);
  f.turn_indicator_rad_s = 0.06;  // turning: cut out
  c.step(1, &f, out);
  EXPECT_EQ(out.torquer1_Nm, 0.0);
  EXPECT_TRUE(out.status & bit(LawStatusBit::kCorrectionCutOut));
  GyroVerticalController h(cfg);
  expect_hold_then_safe(h, gyro_vertical_frame);
  GyroVerticalConfig bad = cfg;
  bad.law.f1 = -1;
  GyroVerticalController r(bad);
  EXPECT_FALSE(r.armed());
  r.step(0, &f, out);
  EXPECT_TRUE(out.status & bit(LawStatusBit::kConfigRefused));
  EXPECT_EQ(out.torquer1_Nm, 0.0);
}

TEST(GyroInstrumentControllers, GyrocompassMapsTheLevelSensor) {
  GyrocompassConfig cfg;
  cfg.runtime.tick_period_ns = 10'000'000;
  cfg.law = {2.0, 0.0015, 0.06, 0.1};
  GyrocompassController c(cfg);
  ASSERT_TRUE(c.armed());
  msg::gyrocompass::SensorFrame f = gyrocompass_frame(0);
  msg::gyrocompass::ActuatorFrame out{};
  c.step(0, &f, out);
  EXPECT_DOUBLE_EQ(out.vertical_torquer_Nm, -0.0015 * -0.02);  // M1 = −f β_lvl
  EXPECT_DOUBLE_EQ(out.east_torquer_Nm, -0.06 * -0.02);        // M2 = −c_e β_lvl
  GyrocompassController h(cfg);
  expect_hold_then_safe(h, gyrocompass_frame);
}

TEST(GyroInstrumentControllers, InertialPlatformRunsTheSchulerLoopOnTheCarrierTilts) {
  InertialPlatformConfig cfg;
  cfg.runtime.tick_period_ns = 5'000'000;
  cfg.law.H = 0.05;
  cfg.law.initial_rate[0] = 1e-5;
  InertialPlatformController c(cfg);
  ASSERT_TRUE(c.armed());
  msg::inertial_platform::SensorFrame f = inertial_platform_frame(0);
  msg::inertial_platform::ActuatorFrame out{};
  c.step(0, &f, out);
  const double g0R = cfg.law.gravity_scale / cfg.law.radius * 5e-3;
  EXPECT_DOUBLE_EQ(out.torquer1_Nm, -0.05 * (1e-5 - g0R * 3e-4));
  EXPECT_DOUBLE_EQ(out.torquer2_Nm, -0.05 * (0.0 - g0R * -1e-4));
  EXPECT_DOUBLE_EQ(c.velocity_estimate(0), cfg.law.radius * (1e-5 - g0R * 3e-4));
  InertialPlatformController h(cfg);
  expect_hold_then_safe(h, inertial_platform_frame);
}

TEST(GyroInstrumentControllers, NoHeapOverAMillionSteps) {
  GyroVerticalConfig gv;
  gv.law.f1 = gv.law.f2 = 0.01;
  GyrocompassConfig gc;
  gc.law = {2.0, 0.0015, 0.06, 0.1};
  InertialPlatformConfig ip;
  GyroVerticalController a(gv);
  GyrocompassController b(gc);
  InertialPlatformController c(ip);
  msg::gyro_vertical::ActuatorFrame out_gv{};
  msg::gyrocompass::ActuatorFrame out_gc{};
  msg::inertial_platform::ActuatorFrame out_ip{};
  const std::uint64_t before = testing::allocations_so_far();
  for (std::uint64_t k = 0; k < 1'000'000; ++k) {
    msg::gyro_vertical::SensorFrame f_gv = gyro_vertical_frame(k);
    msg::gyrocompass::SensorFrame f_gc = gyrocompass_frame(k);
    msg::inertial_platform::SensorFrame f_ip = inertial_platform_frame(k);
    const bool drop = (k % 1000) == 999;
    a.step(k, drop ? nullptr : &f_gv, out_gv);
    b.step(k, drop ? nullptr : &f_gc, out_gc);
    c.step(k, drop ? nullptr : &f_ip, out_ip);
  }
  EXPECT_EQ(testing::allocations_so_far() - before, 0u);
}

}  // namespace gyro_instrument_laws_test
}  // namespace gyrostab::firmware
