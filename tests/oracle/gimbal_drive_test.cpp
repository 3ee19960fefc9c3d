// Gimbal drive oracles (sim/drives/): exact-ZOH motor electrics at a step 1000× longer than L/R, the held-speed
// error bound, unloaded speed V/k_e (with friction), stall torque and current clamp, reflected inertia
// through the GimbalGyro scene-builder rule, Karnopp stick-slip (stuck exactly below breakaway, finite-time
// stop at J v0/τ_c without sign changes, Magnus §11.2b Coulomb nutation decay at a 1 ms step), the explicit
// coupling's first-order speed error, encoder quantization on the motor shaft, enable/fault/watchdog.
// Tolerances: "exact" results are asserted to 1e-12 relative (a few hundred ulps: the recursions and
// exponentials round at 1e-16 per step, over ≤ 1e4 steps), everything else states its own bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include "firmware/msg/fault_bits.hpp"
#include "sim/drives/gimbal_drive.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/models/gimbal_gyro.hpp"

namespace gyrostab {
namespace gimbal_drive_test {

using drives::AxisLoad;
using drives::DcTorqueMotor;
using drives::DcTorqueMotorParams;
using drives::DriveOutput;
using drives::GimbalDrive;
using drives::GimbalDriveParams;
constexpr double kPi = std::numbers::pi;

// A rigid axis: J θ'' = load + drive torque. The drive's inertia is part of J (reflected).
struct InertiaAxis {
  static constexpr int kStateSize = 2;
  using State = Eigen::Matrix<double, kStateSize, 1>;
  double J{1.0};       // [kg m²]
  double load{0.0};    // external torque [N m]
  double torque{0.0};  // drive torque, held over the step [N m]
  void derivative(double /*t*/, const State& x, State& dx) const {
    dx[0] = x[1];
    dx[1] = (load + torque) / J;
  }
  void project(State& /*x*/) const {}
};

// Drive + axis, coupled as gimbal_drive.hpp prescribes. Not copyable (the integrator holds the axis).
struct Rig {
  explicit Rig(const GimbalDriveParams& p, double J_load) : drive(p) {
    EXPECT_EQ(GimbalDrive::check(p), nullptr);
    axis.J = J_load + drive.reflected_inertia();
  }
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  DriveOutput step(double h) {
    const DriveOutput out = drive.step(h, x[1], AxisLoad{axis.load, axis.J});
    if (out.hold) x[1] = 0.0;
    axis.torque = out.torque;
    integ.step(t, h, x);
    t += h;
    return out;
  }

  InertiaAxis axis;
  GimbalDrive drive;
  InertiaAxis::State x{InertiaAxis::State::Zero()};
  dynamics::Rk4<InertiaAxis> integ{axis};
  double t{0.0};
};

GimbalDriveParams frictionless_drive() {
  GimbalDriveParams p;
  p.motor.R = 2.0;
  p.motor.L = 2e-6;  // L/R = 1 µs: 1000× shorter than the 1 ms step
  p.motor.k_t = 0.1;
  p.motor.k_e = 0.1;
  p.motor.J_m = 1e-4;
  p.motor.voltage_limit = 24.0;
  p.motor.current_limit = 100.0;
  return p;
}

// ------------------------------------------------------------------------------------------ motor electrics

// i(t) = (V/R)(1 − e^{−tR/L}) at every step end and its exact mean over each step, for h/τ = 1000, 1, 0.1.
// An explicit scheme at h = 1000 τ would multiply the error by |1 − h/τ| = 999 per step.
TEST(DcTorqueMotor, CurrentRiseIsExactAtAStepThousandTimesLOverR) {
  DcTorqueMotorParams p = frictionless_drive().motor;
  const double V = 12.0, tau = p.L / p.R, i_inf = V / p.R;
  for (const double ratio : {1000.0, 1.0, 0.1}) {
    DcTorqueMotor m(p);
    const double h = ratio * tau;
    double worst_end = 0.0, worst_mean = 0.0;
    for (int k = 0; k < 60; ++k) {
      const DcTorqueMotor::Interval iv = m.advance(h, V, 0.0);
      const double t0 = k * h, t1 = (k + 1) * h;
      const double i_exact = i_inf * (1.0 - std::exp(-t1 / tau));
      const double mean_exact = i_inf * (1.0 - (tau / h) * (std::exp(-t0 / tau) - std::exp(-t1 / tau)));
      worst_end = std::fmax(worst_end, std::fabs(iv.current_end - i_exact));
      worst_mean = std::fmax(worst_mean, std::fabs(iv.current_mean - mean_exact));
      ASSERT_EQ(iv.voltage_mean, V);  // unclipped, no clamp
    }
    std::printf("h = %g L/R: max |i - exact| = %.2e A, max |mean - exact| = %.2e A (V/R = %g A)\n", ratio,
                worst_end, worst_mean, i_inf);
    EXPECT_LE(worst_end, 1e-12 * i_inf) << "h/tau = " << ratio;
    EXPECT_LE(worst_mean, 1e-12 * i_inf) << "h/tau = " << ratio;
  }
  // One step of 1000 τ and 1000 steps of τ end at the same current (the discretization is exact).
  DcTorqueMotor a(p), b(p);
  a.advance(1000 * tau, V, 3.0);
  for (int k = 0; k < 1000; ++k) b.advance(tau, V, 3.0);
  EXPECT_NEAR(a.current(), b.current(), 1e-12 * i_inf);
}

// The held-speed bound of dc_torque_motor.hpp, |i_held − i_true| ≤ k_e α h/R, on a speed ramp ω = α t whose
// exact current is i(t) = (V − k_e α (t − τ))/R − ((V + k_e α τ)/R) e^{−t/τ}. For h ≫ τ the bound is attained
// (error → k_e α (h − τ)/R); for h ≪ τ the error is about half of it.
TEST(DcTorqueMotor, HeldSpeedErrorIsBoundedByKeAlphaHOverR) {
  DcTorqueMotorParams p = frictionless_drive().motor;
  const double V = 12.0, alpha = 100.0, tau = p.L / p.R;
  for (const double ratio : {1000.0, 1.0, 0.01}) {
    const double h = ratio * tau;
    const double bound = p.k_e * alpha * h / p.R;
    DcTorqueMotor m(p);
    double worst = 0.0, late = 0.0;
    const int n = 2000;
    for (int k = 0; k < n; ++k) {
      m.advance(h, V, alpha * k * h);  // speed held at the step start
      const double t = (k + 1) * h;
      const double exact = (V - p.k_e * alpha * (t - tau)) / p.R - (V + p.k_e * alpha * tau) / p.R * std::exp(-t / tau);
      const double err = std::fabs(m.current() - exact);
      worst = std::fmax(worst, err);
      if (k == n - 1) late = err;
    }
    std::printf("h = %g L/R: max error %.4e A, bound k_e a h/R = %.4e A, ratio %.4f\n", ratio, worst, bound,
                worst / bound);
    EXPECT_LE(worst, bound * (1 + 1e-9)) << "h/tau = " << ratio;
    // Not vacuous: at h ≫ τ the error reaches k_e α (h − τ)/R; at h ≪ τ the ramp's mean lag h/2 shows.
    const double expected_late = ratio >= 1000 ? bound * (1 - 1 / ratio) : 0.0;
    if (ratio >= 1000) {
      EXPECT_NEAR(late, expected_late, 1e-9 * bound);
    }
    if (ratio <= 0.01) {
      EXPECT_GE(late, 0.45 * bound);
    }
  }
}

// Stall (ω = 0, joint held by a large breakaway): torque k_t V/R, or k_t I_max once V/R exceeds the clamp;
// with the clamp the current reaches I_max at s* = τ ln(i∞/(i∞ − I_max)) and the first step's mean current
// is the exact piecewise integral. Gear: η N k_t i on the axis while motoring.
TEST(GimbalDrive, StallTorqueIsKtVOverRClippedByTheCurrentLimit) {
  GimbalDriveParams p = frictionless_drive();
  p.motor.R = 1.0;
  p.motor.L = 2e-4;  // τ = 0.2 ms: the clamp engages inside the first 1 ms step
  p.motor.current_limit = 10.0;
  p.gear.ratio = 10.0;
  p.gear.efficiency = 0.8;
  p.friction.breakaway = 1e3;  // stuck: the motor stalls
  const double h = 1e-3, tau = 2e-4;
  for (const double V : {5.0, 24.0}) {
    Rig rig(p, 1.0);
    rig.drive.command_voltage(V, true);
    const double i_inf = V / p.motor.R;
    // A creeping rate inside the Karnopp dead band: the joint is held, and there is no back-EMF (else the
    // stall current would be short by k_e N v, 5e-5 of it here).
    rig.x[1] = 0.5 * p.friction.stick_velocity;
    const DriveOutput first = rig.step(h);
    EXPECT_TRUE(first.hold);
    EXPECT_EQ(rig.x[1], 0.0);
    if (i_inf <= p.motor.current_limit) {
      EXPECT_NEAR(rig.drive.current(), i_inf * (1 - std::exp(-h / tau)), 1e-12 * i_inf);
    } else {
      const double I = p.motor.current_limit;
      const double s_hit = tau * std::log(i_inf / (i_inf - I));
      const double q = i_inf * s_hit - i_inf * tau * (1 - std::exp(-s_hit / tau)) + I * (h - s_hit);
      EXPECT_NEAR(rig.drive.last_interval().current_mean, q / h, 1e-12 * I);
      // The axis gets the step's impulse: the MEAN current's torque, not the end current's (which is I).
      EXPECT_NEAR(rig.drive.gear_torque(), 0.8 * 10.0 * p.motor.k_t * q / h, 1e-12 * 10.0);
      // The override lowers the voltage to R I once clamped: mean (V s* + R I (h − s*))/h.
      EXPECT_NEAR(rig.drive.last_interval().voltage_mean, (V * s_hit + p.motor.R * I * (h - s_hit)) / h, 1e-12 * V);
    }
    for (int k = 0; k < 20; ++k) rig.step(h);
    const double i_stall = std::fmin(i_inf, p.motor.current_limit);
    std::printf("V = %g V: stall current %.15g A, axis torque %.15g N m\n", V, rig.drive.current(),
                rig.drive.gear_torque());
    EXPECT_NEAR(rig.drive.current(), i_stall, 1e-12 * i_stall);
    EXPECT_NEAR(rig.drive.gear_torque(), 0.8 * 10.0 * p.motor.k_t * i_stall, 1e-12 * 10.0);
    EXPECT_EQ(rig.x[1], 0.0);  // held: the joint did not move at all
    EXPECT_EQ(rig.x[0], 0.0);
  }
}

// ------------------------------------------------------------------------------------------ speed, inertia

// Unloaded steady speed: N η k_t (V − k_e N ω)/R = τ_c + b ω, i.e. V/(N k_e) without friction. The fixed
// point of the held-speed coupling is the exact steady state (i = i∞ there), so after 40 τ_em the speed is
// exact to rounding: 1e-9 relative. Gear efficiency 1 (the formula has η = 1).
TEST(GimbalDrive, UnloadedSpeedIsVOverKeMinusFriction) {
  const double V = 12.0, h = 1e-3;
  for (const double N : {1.0, 5.0}) {
    for (const bool with_friction : {false, true}) {
      GimbalDriveParams p = frictionless_drive();
      p.gear.ratio = N;
      if (with_friction) {
        p.friction.coulomb = 0.01 * N;
        p.friction.breakaway = 0.015 * N;
        p.friction.viscous = 1e-4 * N * N;
      }
      Rig rig(p, 1e-3 * N * N);
      const double b_e = rig.drive.electrical_damping();
      const double tau_em = rig.axis.J / (b_e + p.friction.viscous);
      ASSERT_LT(h, 0.05 * tau_em);
      rig.drive.command_voltage(V, true);
      const long n = static_cast<long>(40 * tau_em / h);
      for (long k = 0; k < n; ++k) rig.step(h);
      const double m = p.motor.k_t / p.motor.R;
      const double expected = (N * m * V - p.friction.coulomb) / (N * N * m * p.motor.k_e + p.friction.viscous);
      std::printf("N = %g, friction %d: axis speed %.12f rad/s, expected %.12f (V/(N k_e) = %g)\n", N,
                  with_friction, rig.x[1], expected, V / (N * p.motor.k_e));
      EXPECT_NEAR(rig.x[1], expected, 1e-9 * expected);
    }
  }
}

// The explicit coupling's error (gimbal_drive.hpp): for h ≫ L/R the speed obeys ω_{k+1} = ω_k + r(ω_ss − ω_k),
// r = h/τ_em, instead of e^{−r}; the step response is off by max_k |(1 − r)^k − e^{−rk}| ≤ r/(2e)(1 + r)
// of ω_ss: first order in h. Checked at r = 0.005 and 0.05 against the exact first-order response (τ_e/τ_em
// = 5e-6 changes it by less than 1e-5 of ω_ss; the allowance below).
TEST(GimbalDrive, HeldSpeedCouplingErrorIsFirstOrderInHOverTauEm) {
  const GimbalDriveParams p = frictionless_drive();
  const double V = 12.0, w_ss = V / p.motor.k_e;
  double previous = 0.0;
  for (const double r : {0.005, 0.05}) {
    Rig rig(p, 0.0);
    const double tau_em = rig.axis.J / rig.drive.electrical_damping();
    const double h = r * tau_em;
    ASSERT_LT(h, rig.drive.max_stable_step(rig.axis.J));
    rig.drive.command_voltage(V, true);
    double worst = 0.0, predicted = 0.0;
    for (int k = 1; k <= static_cast<int>(10 / r); ++k) {
      rig.step(h);
      worst = std::fmax(worst, std::fabs(rig.x[1] - w_ss * (1 - std::exp(-k * r))) / w_ss);
      predicted = std::fmax(predicted, std::fabs(std::pow(1 - r, k) - std::exp(-k * r)));
    }
    const double bound = r / (2 * std::numbers::e) * (1 + r);
    std::printf("h/tau_em = %g: max speed error %.4e of w_ss, discrete prediction %.4e, bound %.4e\n", r, worst,
                predicted, bound);
    EXPECT_LE(worst, bound + 1e-5);
    EXPECT_NEAR(worst, predicted, 0.01 * predicted + 1e-5);  // the recursion above is what happens
    if (previous > 0) {
      EXPECT_NEAR(worst / previous, 10.0, 0.5);  // first order: 10× the step, 10× the error
    }
    previous = worst;
  }
}

// Reflected inertia through the scene-builder rule for GimbalGyro axis 2 (BJ += N² J_m): a clamped current is a
// torque step N k_t I_max on the axis, and β'' = N k_t I_max/(B + N² J_m). The rotor does not spin (H = 0),
// so axis 2 decouples: the acceleration is constant after the clamp engages in the first step, exact to
// rounding. probe_axis_load must see the same inertia.
TEST(GimbalDrive, ReflectedInertiaSetsTheGearedAxisAcceleration) {
  GimbalDriveParams dp = frictionless_drive();
  dp.motor.R = 1.0;
  dp.motor.k_t = dp.motor.k_e = 0.05;
  dp.motor.J_m = 2e-4;
  dp.motor.current_limit = 2.0;
  dp.gear.ratio = 20.0;
  GimbalDrive drive(dp);
  ASSERT_EQ(GimbalDrive::check(dp), nullptr);
  models::GimbalGyroParams gp;
  gp.AR = 0.07;
  gp.BJ = 0.05;  // B = BJ + AR = 0.12 (the load)
  gp.AA = 0.3;
  const double J_load = gp.BJ + gp.AR;
  gp.BJ += drive.reflected_inertia();  // 0.08: the rule of gimbal_drive.hpp
  using Gyro = models::GimbalGyro<models::FixedBase>;
  Gyro gyro(gp);
  dynamics::Rk4<Gyro> integ(gyro);
  Gyro::State x = Gyro::make_state(0, 0, 0, 0, 0);
  const double h = 1e-3, tau_axis = 20.0 * 0.05 * 2.0;  // N k_t I_max = 2 N m
  const double expected = tau_axis / (J_load + 20.0 * 20.0 * 2e-4);
  drive.command_voltage(24.0, true);
  double w_first = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const AxisLoad load = drives::probe_axis_load(gyro, gyro.torques.M2, k * h, x, 3, drive.peak_torque());
    if (k == 0) {
      EXPECT_NEAR(load.inertia, J_load + drive.reflected_inertia(), 1e-12);
      EXPECT_NEAR(load.torque, 0.0, 1e-12);
    }
    const DriveOutput out = drive.step(h, x[3], load);
    if (out.hold) x[3] = 0.0;
    gyro.torques.M2 = out.torque;
    integ.step(k * h, h, x);
    if (k == 0) w_first = x[3];
    // Back-EMF headroom: the clamp holds while R I + k_e N ω ≤ U_max.
    ASSERT_LE(dp.motor.R * 2.0 + dp.motor.k_e * 20.0 * x[3], 24.0);
  }
  const double measured = (x[3] - w_first) / (999 * h);
  std::printf("beta'' = %.15f rad/s^2, tau N/(J_load + N^2 J_m) = %.15f, without reflection %.6f\n", measured,
              expected, tau_axis / J_load);
  EXPECT_NEAR(measured, expected, 1e-12 * expected);
  EXPECT_EQ(x[0], 0.0);  // axis 1 untouched
  EXPECT_EQ(x[2], 0.0);
}

// Gear efficiency by power direction: motoring η N τ_m, back-driven N τ_m/η (the loss adds to the braking),
// so |P_axis| = η |P_motor| when motoring and |P_motor| = η |P_axis| when back-driven.
TEST(GearTrain, EfficiencyFollowsThePowerDirection) {
  const drives::GearTrain g({-8.0, 0.75, 1e-6});
  const double tm = 0.3;
  EXPECT_DOUBLE_EQ(g.axis_torque(tm, -2.0), 0.75 * -8.0 * tm);  // ω_m = 16 > 0, τ_m > 0: motoring
  EXPECT_DOUBLE_EQ(g.axis_torque(tm, 2.0), -8.0 * tm / 0.75);   // ω_m < 0: back-driven
  EXPECT_DOUBLE_EQ(g.axis_torque(tm, 0.0), 0.75 * -8.0 * tm);   // standstill: motoring
  EXPECT_DOUBLE_EQ(g.reflected_inertia(1e-5), 64.0 * (1e-5 + 1e-6));
  EXPECT_NE(drives::GearTrain::check({0.0, 1.0, 0.0}), nullptr);
  EXPECT_NE(drives::GearTrain::check({2.0, 1.5, 0.0}), nullptr);
}

// ------------------------------------------------------------------------------------------ stick-slip

// A voltage ramp at stall, on top of a constant external load τ_L of the same sign, raises the net axis
// torque τ_L + N k_t V/R through the breakaway τ_s. Below it the joint is held EXACTLY (rate and angle
// bit-equal to zero: no creep, which needs the hold torque to cancel the load exactly, not up to rounding),
// above it slips at once, in the direction of the torque, without a sign change. Breakaway at
// V = (τ_s − |τ_L|) R/(N k_t) within one step of the ramp (the mean current lags the ZOH voltage by
// (τ/h) ΔV/R, 1e-3 of a step's voltage increment).
TEST(BearingFriction, RampBelowBreakawayStaysExactlyStuckThenSlips) {
  for (const double sign : {1.0, -1.0}) {
    GimbalDriveParams p = frictionless_drive();
    p.motor.R = 1.0;
    p.motor.L = 1e-6;
    p.friction.coulomb = 0.2;
    p.friction.breakaway = 0.3;
    p.friction.viscous = 0.01;
    Rig rig(p, 0.1);
    rig.axis.load = sign * 0.0734567;  // [N m]
    const double h = 1e-3, ramp = 1.0;  // V/s
    const double t_break = (p.friction.breakaway - 0.0734567) * p.motor.R / (p.motor.k_t * ramp);
    long first_slip = -1;
    int sign_changes = 0;
    double prev = 0.0;
    for (long k = 0; k < 4000; ++k) {
      rig.drive.command_voltage(sign * ramp * static_cast<double>(k) * h, true);
      const DriveOutput out = rig.step(h);
      if (first_slip < 0) {
        if (out.hold) {
          ASSERT_EQ(rig.x[1], 0.0) << "creep at k = " << k;
          ASSERT_EQ(rig.x[0], 0.0) << "creep at k = " << k;
          ASSERT_LE(std::fabs(rig.drive.gear_torque() + rig.axis.load), p.friction.breakaway);
        } else {
          first_slip = k;
        }
      }
      if (prev * rig.x[1] < 0) ++sign_changes;
      prev = rig.x[1];
    }
    const double t_slip = static_cast<double>(first_slip) * h;
    std::printf("sign %+g: slip starts at %.4f s (breakaway torque reached at %.4f s), final rate %.4f rad/s\n", sign,
                t_slip, t_break, rig.x[1]);
    EXPECT_NEAR(t_slip, t_break, 1.01 * h);
    EXPECT_GT(sign * rig.x[1], 0.0);
    EXPECT_EQ(sign_changes, 0);
  }
}

// Coulomb-only decay of a free axis (drive disabled): v = v0 − (τ_c/J) t until t* = J v0/τ_c, then rest at
// θ* = J v0²/(2 τ_c) (the mean motion (11.10)). Before t* the deceleration is constant and RK4 is exact (1e-12);
// the last step lands on zero, costing at most ½ a h² of angle (a = τ_c/J). From the step after t* the
// rate is exactly 0 and the angle frozen. Sign changes are counted outside the dead band (|v| ≥ v_st:
// inside it the joint is at rest by definition; the landing leaves |v| ~ 1e-19).
TEST(BearingFriction, CoulombDecayStopsInFiniteTimeWithoutChatter) {
  GimbalDriveParams p = frictionless_drive();
  p.friction.coulomb = 0.05;
  p.friction.breakaway = 0.08;
  Rig rig(p, 0.1);  // never commanded: bridge disabled
  const double J = rig.axis.J, v0 = 2.0003, a = p.friction.coulomb / J, h = 1e-3;
  const double t_stop = v0 / a, theta_stop = J * v0 * v0 / (2 * p.friction.coulomb);
  rig.x[1] = v0;
  int sign_changes = 0;
  double prev = v0, worst_before = 0.0;
  long rest_from = -1;
  for (long k = 1; k <= 8000; ++k) {
    rig.step(h);
    const double t = static_cast<double>(k) * h, v = rig.x[1];
    if (t < t_stop) worst_before = std::fmax(worst_before, std::fabs(v - (v0 - a * t)));
    if (std::fabs(v) >= p.friction.stick_velocity) {
      if (prev * v < 0) ++sign_changes;
      prev = v;
    }
    if (v != 0.0) rest_from = -1;
    else if (rest_from < 0) rest_from = k;
  }
  std::printf("stop: exact rest from t = %.4f s (t* = %.4f s), angle %.9f rad (J v0^2/(2 tau_c) = %.9f)\n",
              static_cast<double>(rest_from) * h, t_stop, rig.x[0], theta_stop);
  EXPECT_LE(worst_before, 1e-12 * v0);
  EXPECT_EQ(sign_changes, 0);
  ASSERT_GT(rest_from, 0);
  EXPECT_LE(static_cast<double>(rest_from) * h, t_stop + 2 * h);  // lands in the step holding t*, held at the next
  EXPECT_GE(static_cast<double>(rest_from) * h, t_stop);
  EXPECT_NEAR(rig.x[0], theta_stop, 0.5 * a * h * h);
  EXPECT_EQ(rig.x[1], 0.0);
}

// Reversal inside a step: a slow forward slip under a large opposing load |τ_L| > τ_s stops and slides back.
// The step that holds the stop splits the friction at s* = J v/(τ_c − τ_L) (−τ_c before, +τ_c after), which is
// the exact impulse for a pure inertia: the rate after every step equals the piecewise-exact solution
//   v(t) = v0 + (τ_L − τ_c) t / J  for t ≤ s*,   (τ_L + τ_c)(t − s*)/J after
// to rounding (1e-12 of the rate scale). Without the split the crossing step would be off by 2 τ_c (h − s*)/J.
TEST(BearingFriction, ReversalWithinAStepKeepsTheExactImpulse) {
  GimbalDriveParams p = frictionless_drive();
  p.friction.coulomb = 0.05;
  p.friction.breakaway = 0.08;
  const double h = 1e-3;
  for (const double v0 : {0.00137, 0.0042, 0.01}) {
    Rig rig(p, 0.1);
    rig.axis.load = -0.5;
    rig.x[1] = v0;
    const double J = rig.axis.J, s_stop = J * v0 / (p.friction.coulomb - rig.axis.load);
    double worst = 0.0;
    for (int k = 1; k <= 40; ++k) {
      rig.step(h);
      const double t = k * h;
      const double exact = t <= s_stop ? v0 + (rig.axis.load - p.friction.coulomb) * t / J
                                       : (rig.axis.load + p.friction.coulomb) * (t - s_stop) / J;
      worst = std::fmax(worst, std::fabs(rig.x[1] - exact));
    }
    std::printf("v0 = %g rad/s (stop at %.4f ms): max rate error %.2e rad/s\n", v0, s_stop * 1e3, worst);
    EXPECT_LE(worst, 1e-12 * 0.2);
  }
}

// Magnus §11.2.2 with the drives' Karnopp friction on both gimbal bearings of a GimbalGyro at a 1 ms step
// (the regularised friction of the model needs 20 µs): the normalised nutation rate amplitude ρ falls
// linearly, dρ/dt = −(2/π)(r1 + r2 √(A/B))/√(AB) (reference F1, docs/models/gimbal-gyro.md: 0.7478, 0.4958,
// 0.2440 at 2, 4, 6 s), and the motion stops in finite time near t_stop = ρ0 √(AB) π/(2(r1 + r2
// √(A/B))) = 7.94 s, deflected (11.10), at exact rest after. Tolerances: ρ ±3e-3 (within a quarter cycle ρ
// moves by (r1 + r2 √(A/B))/H = 2.8e-3, as in gimbal_gyro_test); stop within one nutation period
// 2π√(AB)/H = 0.12 s + 0.03 s of the law (its last cycles are stick-slip).
TEST(BearingFriction, CoulombNutationDecaysLinearlyAndStopsAtAOneMillisecondStep) {
  using Gyro = models::GimbalGyro<models::FixedBase>;
  models::GimbalGyroParams gp;
  gp.AR = 0.6;
  gp.AA = 0.4;  // A = 1, B = 0.6
  gp.CR = 1.0;
  const Gyro gyro_model(gp);
  Gyro gyro = gyro_model;
  GimbalDriveParams p1, p2;
  p1.motor.J_m = p2.motor.J_m = 0.0;
  p1.friction.coulomb = p1.friction.breakaway = 0.05;  // r1
  p2.friction.coulomb = p2.friction.breakaway = 0.08;  // r2
  GimbalDrive d1(p1), d2(p2);
  const double A = 1.0, B = 0.6, H = 40.0, r1 = 0.05, r2 = 0.08, h = 1e-3;
  const double slope = 2.0 / kPi * (r1 + r2 * std::sqrt(A / B)) / std::sqrt(A * B);
  const double t_law = std::sqrt(A * B) * kPi / (2 * (r1 + r2 * std::sqrt(A / B)));
  Gyro::State x = Gyro::make_state(0, 0, 0, 1.0, H);
  dynamics::Rk4<Gyro> integ(gyro);
  long rest_from = -1;
  Gyro::State at_rest = x;
  for (long k = 0; k < 12000; ++k) {
    const double t = static_cast<double>(k) * h;
    const AxisLoad l1 = drives::probe_axis_load(gyro, gyro.torques.M1, t, x, 2);
    const DriveOutput o1 = d1.step(h, x[2], l1);
    if (o1.hold) x[2] = 0.0;
    const AxisLoad l2 = drives::probe_axis_load(gyro, gyro.torques.M2, t, x, 3);
    const DriveOutput o2 = d2.step(h, x[3], l2);
    if (o2.hold) x[3] = 0.0;
    gyro.torques.M1 = o1.torque;
    gyro.torques.M2 = o2.torque;
    integ.step(t, h, x);
    const long n = k + 1;
    if (n == 2000 || n == 4000 || n == 6000) {
      const double tc = static_cast<double>(n) * h, rho = std::hypot(x[2] * std::sqrt(A / B), x[3]);
      std::printf("t = %g s: rho = %.5f, linear law %.5f\n", tc, rho, 1.0 - slope * tc);
      EXPECT_NEAR(rho, 1.0 - slope * tc, 3e-3) << "t = " << tc;
    }
    if (x[2] != 0.0 || x[3] != 0.0) {
      rest_from = -1;
    } else if (rest_from < 0) {
      rest_from = n;
      at_rest = x;
    }
  }
  ASSERT_GT(rest_from, 0) << "never came to rest";
  const double t_rest = static_cast<double>(rest_from) * h;
  std::printf("exact rest from t = %.3f s (law %.3f s), deflected to alpha = %.5f, beta = %.5f rad\n", t_rest, t_law,
              x[0], x[1]);
  EXPECT_NEAR(t_rest, t_law, 2 * kPi * std::sqrt(A * B) / H + 0.03);
  EXPECT_EQ(x, at_rest);  // frozen: no creep, no chatter after the stop
  EXPECT_NE(x[0], 0.0);   // the axis ends deflected (§11.2b)
}

// ------------------------------------------------------------------------------------------ sensors, faults

// Motor-shaft encoder: count = ⌊N θ CPR/2π⌋ (Encoder, kFloor), so the axis angle is read to LSB/N with the
// error in [0, 2π/(CPR N)); the count wraps to int32 as the contract carries it.
TEST(GimbalDrive, EncoderQuantizesTheMotorShaftAngle) {
  GimbalDriveParams p;
  p.gear.ratio = 10.0;
  p.encoder.counts_per_rev = 4096;
  const GimbalDrive drive(p);
  const sensors::Encoder bare(p.encoder);
  const double lsb_axis = 2 * kPi / (4096 * 10.0);
  for (int j = -20000; j <= 20000; ++j) {
    const double theta = 0.37 * lsb_axis * j;
    const std::int32_t c = drive.encoder_count(theta);
    ASSERT_EQ(c, bare.counts(10.0 * theta));
    const double err = theta - c * lsb_axis;
    ASSERT_GE(err, -1e-15);
    ASSERT_LT(err, lsb_axis * (1 + 1e-9));
  }
  // 2^31 + 5 motor counts wrap to −2^31 + 5.
  const double theta_wrap = (2147483648.0 + 5.5) * lsb_axis;
  EXPECT_EQ(drive.encoder_count(theta_wrap), static_cast<std::int32_t>(-2147483648LL + 5));
  const drives::DriveReadings r = drive.readings(theta_wrap);
  EXPECT_EQ(r.encoder_count, static_cast<std::int32_t>(-2147483648LL + 5));
  EXPECT_FALSE(r.fault);
}

// Disabled, safe state in the actuator frame, or a watchdog timeout: bridge open, zero current and torque
// at once; the watchdog fault latches (and is reported as kDriveFault) until cleared.
TEST(GimbalDrive, DisabledFaultedOrSafeStateGivesZeroTorque) {
  GimbalDriveParams p = frictionless_drive();
  p.command_timeout = 2.5e-3;
  Rig rig(p, 1.0);
  const double h = 1e-3;
  const double volts = 12.0, torque = 0.0;  // a voltage-mode drive takes the voltage, ignores the torque
  std::uint32_t status = 0;
  rig.drive.command(volts, torque, status);
  rig.step(h);
  EXPECT_GT(rig.drive.current(), 1.0);
  status = msg::bit(msg::FaultBit::kSafeState);
  rig.drive.command(volts, torque, status);
  DriveOutput out = rig.step(h);
  EXPECT_EQ(rig.drive.current(), 0.0);
  EXPECT_EQ(rig.drive.gear_torque(), 0.0);
  EXPECT_EQ(out.torque, 0.0);  // frictionless
  status = 0;
  rig.drive.command(volts, torque, status);
  rig.step(h);  // 1 ms since the command
  EXPECT_GT(rig.drive.current(), 1.0);
  // No further command (one missing frame): 2 ms ≤ 2.5 ms, still running.
  rig.step(h);
  EXPECT_EQ(rig.drive.fault(), drives::DriveFault::kNone);
  EXPECT_GT(rig.drive.current(), 1.0);
  out = rig.step(h);  // 3 ms > 2.5 ms: two missing actuator frames
  EXPECT_EQ(rig.drive.fault(), drives::DriveFault::kCommandTimeout);
  EXPECT_EQ(out.torque, 0.0);
  EXPECT_TRUE(rig.drive.readings(rig.x[0]).fault);  // a plant reports it as kDriveFault
  rig.drive.command(volts, torque, status);  // a command alone does not clear a latched fault
  rig.step(h);
  EXPECT_EQ(rig.drive.current(), 0.0);
  rig.drive.clear_fault();
  rig.drive.command(volts, torque, status);
  rig.step(h);
  EXPECT_GT(rig.drive.current(), 1.0);
}

// Current-regulated (torque) mode: i_ref = τ/(N k_t) is reached exactly within the step (bus-limited rise
// L Δi/(U_max − k_e ω) ≪ h) and held; the mean current falls short by the rise, ½ L i²/(U_max h) per step.
TEST(GimbalDrive, TorqueModeRegulatesTheCurrentToTheCommand) {
  GimbalDriveParams p = frictionless_drive();
  p.command = GimbalDriveParams::Command::kTorque;
  p.motor.L = 1e-4;
  p.gear.ratio = 10.0;
  Rig rig(p, 5.0);
  rig.drive.command(99.0, 2.0, 0u);  // i_ref = 2/(10 · 0.1) = 2 A; a torque-mode drive ignores the voltage
  const double h = 1e-3;
  rig.step(h);
  EXPECT_NEAR(rig.drive.current(), 2.0, 1e-12);
  // Rise at full bus: s_r = τ ln(i∞/(i∞ − 2)), i∞ = U_max/R; mean = (∫ rise + 2 (h − s_r))/h.
  const double tau = p.motor.L / p.motor.R, i_inf = 24.0 / p.motor.R;
  const double s_r = tau * std::log(i_inf / (i_inf - 2.0));
  const double q = i_inf * s_r - i_inf * tau * (1 - std::exp(-s_r / tau)) + 2.0 * (h - s_r);
  EXPECT_NEAR(rig.drive.last_interval().current_mean, q / h, 1e-12);
  for (int k = 0; k < 100; ++k) rig.step(h);
  EXPECT_NEAR(rig.drive.current(), 2.0, 1e-12);  // held against the rising back-EMF
  EXPECT_NEAR(rig.drive.gear_torque(), 2.0, 1e-12);
}

}  // namespace gimbal_drive_test
}  // namespace gyrostab
