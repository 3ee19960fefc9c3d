// Drive loops (firmware/control/drive_loops.hpp): the current PI's step response on the exact ZOH winding is
// first order at the designed bandwidth; anti-windup (conditional integration) leaves the limit no later than the
// error's sign change (against ~10^4 ticks without it); outputs never leave their limits, NaN-safe;
// the cascade runs on the firmware scheduler at 10 kHz / 1 kHz and tracks a speed step on the sim drive.
// The plants are the sim's DcTorqueMotor (exact ZOH electrics) and an exact-ZOH inertia.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "firmware/control/drive_loops.hpp"
#include "firmware/scheduler/scheduler.hpp"
#include "sim/drives/dc_torque_motor.hpp"
#include "sim/drives/gimbal_drive.hpp"

namespace gyrostab {
namespace drive_loops_test {

using firmware::AntiWindup;
using firmware::PiCoefficients;
using firmware::PiParams;
using firmware::PiState;

firmware::CurrentLoopSpec current_spec() {
  firmware::CurrentLoopSpec s;
  s.resistance = 0.8;
  s.inductance = 4e-4;  // L/R = 0.5 ms
  s.bandwidth = 3000.0;
  s.period = 1e-4;      // 10 kHz: ω_c T = 0.3
  s.voltage_limit = 48.0;
  return s;
}

drives::DcTorqueMotorParams winding(const firmware::CurrentLoopSpec& s) {
  drives::DcTorqueMotorParams p;
  p.R = s.resistance;
  p.L = s.inductance;
  p.voltage_limit = 1e3;  // the controller's limit is the one under test
  p.current_limit = 1e3;
  return p;
}

// i_k = i_ref (1 − e^{−ω_c k T}) on the exact ZOH winding, stalled and spinning (back-EMF fed forward):
// exact to rounding (1e-12 of i_ref over 200 ticks). The gains tend to the continuous L ω_c, R ω_c.
TEST(CurrentLoop, StepResponseIsFirstOrderAtTheDesignedBandwidth) {
  const firmware::CurrentLoopSpec s = current_spec();
  const PiParams<double> gains = firmware::design_current_pi(s);
  ASSERT_EQ(firmware::check_pi(gains), nullptr);
  const PiCoefficients<double> c = firmware::compile_pi(gains);
  const double i_ref = 3.0, k_e = 0.1;
  for (const double omega : {0.0, 50.0}) {
    drives::DcTorqueMotorParams mp = winding(s);
    mp.k_e = k_e;
    drives::DcTorqueMotor motor(mp);
    PiState<double> st;
    double worst = 0.0, t63 = -1.0;
    for (int k = 1; k <= 200; ++k) {
      const auto o = firmware::pi_step(c, st, i_ref, motor.current(), k_e * omega);
      ASSERT_FALSE(o.saturated);
      motor.advance(s.period, o.value, omega);
      const double t = k * s.period;
      worst = std::fmax(worst, std::fabs(motor.current() - i_ref * (1 - std::exp(-s.bandwidth * t))));
      if (t63 < 0 && motor.current() >= i_ref * (1 - std::exp(-1.0))) t63 = t;
    }
    std::printf("omega_m = %g rad/s: max |i - i_ref(1 - e^{-w_c t})| = %.2e A; 63 %% at %.4f ms (1/w_c = %.4f ms)\n",
                omega, worst, t63 * 1e3, 1e3 / s.bandwidth);
    EXPECT_LE(worst, 1e-12 * i_ref);
    // The 63 % point is the first sample at or after 1/ω_c.
    EXPECT_GE(t63, 1.0 / s.bandwidth - 1e-12);
    EXPECT_LT(t63, 1.0 / s.bandwidth + s.period);
  }
  // Continuous limit: T → 0 gives K_p → L ω_c, K_i → R ω_c (first order in ω_c T).
  firmware::CurrentLoopSpec fine = s;
  fine.period = 1e-8;
  const PiParams<double> g0 = firmware::design_current_pi(fine);
  EXPECT_NEAR(g0.kp, s.inductance * s.bandwidth, 1e-4 * s.inductance * s.bandwidth);
  EXPECT_NEAR(g0.ki, s.resistance * s.bandwidth, 1e-4 * s.resistance * s.bandwidth);
}

// The same loop in single precision (the Cortex-M4F build): within 1e-5 of i_ref (float ε = 1.2e-7, the
// gains' rounding moves the pole by ~1e-7).
TEST(CurrentLoop, SinglePrecisionTracksTheSameResponse) {
  const firmware::CurrentLoopSpec s = current_spec();
  const PiCoefficients<float> c = firmware::compile_pi(firmware::narrow<float>(firmware::design_current_pi(s)));
  drives::DcTorqueMotor motor(winding(s));
  PiState<float> st;
  double worst = 0.0;
  for (int k = 1; k <= 200; ++k) {
    const auto o = firmware::pi_step(c, st, 3.0f, static_cast<float>(motor.current()));
    motor.advance(s.period, static_cast<double>(o.value), 0.0);
    worst = std::fmax(worst, std::fabs(motor.current() - 3.0 * (1 - std::exp(-s.bandwidth * k * s.period))));
  }
  EXPECT_LE(worst, 1e-5 * 3.0);
}

// Conditional integration with the integral kept in [u_min − ff, u_max − ff] (header): the output leaves the
// limit no later than the tick at which the error changes sign.
// Case 1, blocked axis: the reference is unreachable for 0.5 s (axis held at 0), then drops to −1 rad/s: the
// error flips and the output leaves the upper limit in that same tick, at K_p e + I_frozen = −1 A (the
// integral froze at 0 when the first tick saturated). Without anti-windup the integral has wound up to
// K_i e t = 12.5 · 20 · 0.5 = 125 A and the output stays on the limit until K_p e + I < u_max, unwinding at
// K_i |e| = 12.5 A/s: (125 − 2 − 1)/12.5 = 9.76 s = 9760 ticks (± 1 tick for the sample at the boundary).
// Case 2, a 20 rad/s step on a free inertia (exact ZOH): saturated acceleration at 100 rad/s²; with
// anti-windup the output leaves the limit at the first tick where K_p e + I_frozen ≤ u_max, before the error
// crosses zero, and overshoots by < 5 %; without, it leaves long after the crossing and overshoots by ~67 %.
TEST(AntiWindup, OutputLeavesTheLimitNoLaterThanTheErrorSignChange) {
  firmware::VelocityLoopSpec vs;
  vs.inertia = 0.01;
  vs.torque_constant = 0.5;
  vs.bandwidth = 50.0;  // K_p = 1 A s/rad, K_i = 12.5 A/rad
  vs.period = 1e-3;
  vs.current_limit = 2.0;
  const double T = vs.period, J = vs.inertia, k_t = vs.torque_constant;

  // Case 1.
  for (const AntiWindup aw : {AntiWindup::kConditionalIntegration, AntiWindup::kNone}) {
    PiParams<double> g = firmware::design_velocity_pi(vs);
    g.anti_windup = aw;
    const PiCoefficients<double> c = firmware::compile_pi(g);
    PiState<double> st;
    const long k_flip = 500;
    long leave = -1;
    double first_value = 0.0;
    for (long k = 0; k < 20000 && leave < 0; ++k) {
      const double ref = k < k_flip ? 20.0 : -1.0;
      const auto o = firmware::pi_step(c, st, ref, 0.0);  // blocked: speed 0
      if (k < k_flip) {
        ASSERT_TRUE(o.saturated);
        ASSERT_EQ(o.value, 2.0);
      }
      if (k >= k_flip && o.value < 2.0) {
        leave = k;
        first_value = o.value;
      }
    }
    std::printf("blocked axis, %s: error flips at tick %ld, output leaves the limit at tick %ld (%.4f A)\n",
                aw == AntiWindup::kNone ? "no anti-windup" : "conditional integration", k_flip, leave, first_value);
    if (aw == AntiWindup::kConditionalIntegration) {
      EXPECT_EQ(leave, k_flip);
      EXPECT_EQ(first_value, -1.0);  // K_p e + 0: the integral did not move while saturated
    } else {
      const double wound = c.ki_T * 20.0 * static_cast<double>(k_flip);  // 125 A
      const double predicted = (wound - c.out_max + c.kp * -1.0) / (c.ki_T * 1.0);
      EXPECT_NEAR(static_cast<double>(leave - k_flip), predicted, 1.0);
    }
  }

  // Case 2.
  double overshoot[2] = {0, 0};
  long after_cross[2] = {0, 0};
  for (const AntiWindup aw : {AntiWindup::kConditionalIntegration, AntiWindup::kNone}) {
    PiParams<double> g = firmware::design_velocity_pi(vs);
    g.anti_windup = aw;
    const PiCoefficients<double> c = firmware::compile_pi(g);
    PiState<double> st;
    const double ref = 20.0;
    double w = 0.0, peak = 0.0;
    long cross = -1, leave = -1, predicted = -1;
    bool was_saturated = false;
    for (long k = 0; k < 3000; ++k) {
      const double e = ref - w;
      if (cross < 0 && e <= 0.0) cross = k;
      // The header's verdict: after saturating, the first tick with K_p e + I ≤ u_max (I frozen).
      if (was_saturated && predicted < 0 && c.kp * e + st.integral <= c.out_max) predicted = k;
      const auto o = firmware::pi_step(c, st, ref, w);
      if (was_saturated && !o.saturated && leave < 0) leave = k;
      if (o.saturated) was_saturated = true;
      w += T * k_t * o.value / J;  // exact ZOH of J ω' = k i
      peak = std::fmax(peak, w);
    }
    const int i = aw == AntiWindup::kNone ? 1 : 0;
    overshoot[i] = peak / ref - 1.0;
    after_cross[i] = leave - cross;
    std::printf("speed step, %s: error crosses zero at tick %ld, output leaves the limit at tick %ld, overshoot %.2f %%\n",
                i ? "no anti-windup" : "conditional integration", cross, leave, 100 * overshoot[i]);
    if (aw == AntiWindup::kConditionalIntegration) {
      EXPECT_EQ(leave, predicted);
      EXPECT_LE(leave, cross);
    }
  }
  EXPECT_GT(after_cross[1], 50);            // without: long after the crossing
  EXPECT_LT(overshoot[0], 0.05);            // with: the linear loop's own small overshoot
  EXPECT_GT(overshoot[1], 10 * overshoot[0]);  // without: the windup overshoot
}

// Outputs stay inside [out_min, out_max] for any input, including ±huge, ±Inf and NaN (then valid = false,
// output 0 clamped into the limits, integral unchanged), with and without anti-windup, and for an
// asymmetric range not containing 0; with anti-windup the integral stays in range. Deterministic inputs
// (fixed LCG).
TEST(PiController, OutputIsAlwaysWithinItsLimits) {
  std::uint64_t lcg = 0x9E3779B97F4A7C15ull;
  auto next = [&lcg]() {
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(lcg >> 11) / 9007199254740992.0;  // [0, 1)
  };
  const double specials[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(), 1e300, -1e300};
  for (const AntiWindup aw : {AntiWindup::kConditionalIntegration, AntiWindup::kNone}) {
    for (const double lo : {-3.0, 0.5}) {
      PiParams<double> g;
      g.kp = 2.0;
      g.ki = 500.0;
      g.period = 1e-4;
      g.out_min = lo;
      g.out_max = 4.0;
      g.anti_windup = aw;
      ASSERT_EQ(firmware::check_pi(g), nullptr);
      const PiCoefficients<double> c = firmware::compile_pi(g);
      PiState<double> st;
      long invalid = 0;
      for (int k = 0; k < 200000; ++k) {
        double r = 20.0 * (next() - 0.5), y = 20.0 * (next() - 0.5);
        if (k % 97 == 0) y = specials[(k / 97) % 5];
        const double before = st.integral;
        const auto o = firmware::pi_step(c, st, r, y);
        ASSERT_GE(o.value, g.out_min) << k;
        ASSERT_LE(o.value, g.out_max) << k;
        // Conditional integration keeps I in [u_min, u_max] (ff = 0), or leaves it untouched (frozen): what
        // makes the output leave the limit at the error's sign change.
        if (aw == AntiWindup::kConditionalIntegration && o.valid) {
          ASSERT_TRUE((st.integral >= lo && st.integral <= 4.0) || st.integral == before) << k;
        }
        if (!o.valid) {
          ++invalid;
          ASSERT_EQ(st.integral, before);
          ASSERT_EQ(o.value, lo > 0 ? lo : 0.0);
        }
        // Reset after a ±1e300 input (whose integral update is legitimately huge) so the run stays varied.
        if (!(std::fabs(st.integral) < 1e6)) st = {};
      }
      EXPECT_GT(invalid, 0);
    }
  }
  PiParams<double> bad;
  bad.out_min = 1.0;
  bad.out_max = 1.0;
  EXPECT_NE(firmware::check_pi(bad), nullptr);
  bad.out_min = -1.0;
  bad.period = 0.0;
  EXPECT_NE(firmware::check_pi(bad), nullptr);
}

// The cascade on the firmware scheduler: 10 kHz ticks, current task every tick, velocity task every 10th,
// velocity first. Plant: GimbalDrive (N = 10) on an inertia, stepped 100 µs per tick. A 10 rad/s step
// saturates the velocity loop at 5 A (the drive's own clamp is 6 A, not reached), then settles:
// within 1e-6 rad/s at 1 s (double pole at −ω_v/2 = −25 1/s: e^{−25}·(1 + 25) ≈ 4e-10 of the step), overshoot
// < 5 % (conditional integration: the loop leaves the limit with a frozen integral and the rest is the linear
// loop's own overshoot, which its PI zero at ω_v/4 causes; without anti-windup it is tens of %), |i| ≤ 5 A + 1 % (the current loop's first-order tracking of a ≤ 5 A reference
// does not overshoot; 1 % for the back-EMF feedforward's one-tick lag), |u| ≤ 24 V. Task run counts exact.
TEST(DriveCascade, RunsOnTheSchedulerAndTracksASpeedStep) {
  drives::GimbalDriveParams dp;
  dp.motor.R = 0.8;
  dp.motor.L = 4e-4;
  dp.motor.k_t = dp.motor.k_e = 0.1;
  dp.motor.J_m = 1e-4;
  dp.motor.voltage_limit = 24.0;
  dp.motor.current_limit = 6.0;
  dp.gear.ratio = 10.0;
  drives::GimbalDrive drive(dp);
  const double J = 0.05 + drive.reflected_inertia(), T = 1e-4, N = 10.0;

  firmware::CurrentLoopSpec cs;
  cs.resistance = dp.motor.R;
  cs.inductance = dp.motor.L;
  cs.bandwidth = 2000.0;
  cs.period = T;
  cs.voltage_limit = 24.0;
  firmware::VelocityLoopSpec vs;
  vs.inertia = J;
  vs.torque_constant = N * dp.motor.k_t;
  vs.bandwidth = 50.0;
  vs.period = 10 * T;
  vs.current_limit = 5.0;
  firmware::DriveCascade<> cascade({firmware::design_velocity_pi(vs), firmware::design_current_pi(cs),
                                    N * dp.motor.k_e});
  firmware::Scheduler<2> sched;
  ASSERT_TRUE((sched.add_member<&firmware::DriveCascade<>::velocity_task>("velocity", 10, 0, 0, cascade).ok()));
  ASSERT_TRUE((sched.add_member<&firmware::DriveCascade<>::current_task>("current", 1, 0, 0, cascade).ok()));

  double w = 0.0, peak = 0.0, i_max = 0.0, u_max = 0.0;
  cascade.in.speed_reference = 10.0;
  const std::uint64_t ticks = 10000;  // 1 s
  for (std::uint64_t k = 0; k < ticks; ++k) {
    cascade.in.speed = w;
    cascade.in.current = drive.current();
    sched.run_tick(k);
    drive.command_voltage(cascade.out.voltage, true);
    const drives::DriveOutput out = drive.step(T, w, {0.0, J});
    if (out.hold) w = 0.0;
    w += T * out.torque / J;  // exact for the held torque on a pure inertia
    peak = std::fmax(peak, w);
    i_max = std::fmax(i_max, std::fabs(drive.current()));
    u_max = std::fmax(u_max, std::fabs(cascade.out.voltage));
  }
  std::printf("speed %.9f rad/s (ref 10), overshoot %.3f %%, max |i| %.4f A, max |u| %.3f V\n", w,
              100 * (peak / 10.0 - 1), i_max, u_max);
  EXPECT_NEAR(w, 10.0, 1e-6);
  EXPECT_LT(peak, 10.5);
  EXPECT_LE(i_max, 5.0 * 1.01);
  EXPECT_LE(u_max, 24.0);
  EXPECT_EQ(sched.counters(0).runs, ticks / 10);
  EXPECT_EQ(sched.counters(1).runs, ticks);
}

// The contract's 32-bit encoder count wraps; differences across the wrap are exact.
TEST(EncoderCountDelta, IsExactAcrossTheWrap) {
  constexpr std::int32_t kMin = std::numeric_limits<std::int32_t>::min();
  constexpr std::int32_t kMax = std::numeric_limits<std::int32_t>::max();
  static_assert(firmware::encoder_count_delta(kMin + 5, kMax - 4) == 10);
  static_assert(firmware::encoder_count_delta(kMax - 4, kMin + 5) == -10);
  static_assert(firmware::encoder_count_delta(7, 3) == 4);
  EXPECT_EQ(firmware::encoder_count_delta(0, -1), 1);
}

}  // namespace drive_loops_test
}  // namespace gyrostab
