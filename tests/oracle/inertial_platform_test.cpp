// Oracle tests of the inertial platforms (sim/models/inertial_platform.hpp) with the firmware Schuler loop
// (firmware/control/schuler_loop.hpp, sampled at its control period with one tick of latency, as in the
// closed loop) against Magnus ch. 16 (docs/models/inertial-platform.md):
//   servo offsets (16.2) and the stability bound k < Hd/B (16.5);
//   Schuler period 84.4 min of the platform loop (16.38)/(16.44) and the tuned error curves for an initial
//   tilt (16.46)-(16.47) — velocity amplitude α0 sqrt(gR), position error up to 2Rα0 (book: 2.2 km for
//   0.01°) — and for a gyro drift (16.49);
//   level under vehicle acceleration when tuned (16.34): the single-axis platform on an accelerating great
//   circle, and the three-axis platform in turns and accelerations over the rotating Earth (vehicle
//   generator sim/motion/earth_vehicle.hpp), against a mistuned loop that is not.
// Steps: the servo modes (≈ 50 rad/s, −k/H = −6 /s) at RK4 h = 2.5 ms (h|λ| = 0.12, local error ~2e-7 of a
// mode that decays in 0.2 s); the Schuler mode 1.24e-3 rad/s is what is measured. The sampled loop
// (T = 5 ms, Δv accelerometer averaged over the tick + 1 tick of latency) lags by ≈ 1.5 T: its period error
// is O((ω_S T)²) ≈ 4e-11
// and it grows the Schuler amplitude by ω_S² 1.5T/2 ≈ 6e-9 per second, 3e-5 over 5000 s. The servo lag
// (platform follows the commanded rate with the time constant H/k = 1/6 s) shifts the period by O((ω_S H/k)²)
// ≈ 4e-8. Tolerances: period 1e-4 relative (the extrema, sampled every 10 s, locate peaks to ~1e-3 s),
// amplitudes 1e-3 relative.
#include "sim/models/inertial_platform.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "firmware/control/schuler_loop.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/motion/earth_vehicle.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab {
namespace inertial_platform_test {

using models::PlatformAxisParams;
using models::SingleAxisPlatform;
using models::ThreeAxisPlatform;
constexpr double kPi = std::numbers::pi;
constexpr double kR = 6.371e6, kG = 9.81;
const double kWs = std::sqrt(kG / kR);
const double kTs = 2 * kPi / kWs;

TEST(InertialPlatformOracle, ServoOffsets16_2) {
  PlatformAxisParams a;
  a.disturbance = 2e-3;
  SingleAxisPlatform p({a, 0.0});
  const double M_K = -a.H * 1e-4;  // commands 1e-4 rad/s (16.2): α0' = −M^K/H
  p.inputs.torquer = M_K;
  p.inputs.frame.hold({});
  dynamics::Rk4<SingleAxisPlatform> integ(p);
  SingleAxisPlatform::State x = SingleAxisPlatform::State::Zero();
  for (int k = 0; k < 20000; ++k) integ.step(k * 2.5e-3, 2.5e-3, x);  // 50 s: e^-300 of the slowest servo root
  EXPECT_NEAR(x[2], a.disturbance / a.k, 1e-12);
  EXPECT_NEAR(x[1], -M_K / a.H, 1e-15);
  EXPECT_NEAR(x[3], 0.0, 1e-15);
}

TEST(InertialPlatformOracle, StabilityBound16_5) {
  // Eigenvalues of the single-axis servo (J B λ³ + J d λ² + H² λ + H k, × λ for the angle) across k_max.
  PlatformAxisParams a;
  const double kmax = a.H * a.d / a.B;
  EXPECT_DOUBLE_EQ(a.k_max(), kmax);
  for (const double f : {0.9, 1.1}) {
    PlatformAxisParams b = a;
    b.k = f * kmax;
    SingleAxisPlatform p({b, 0.0});
    p.inputs.frame.hold({});
    Eigen::Matrix4d J;
    dynamics::finite_difference_jacobian(p, 0.0, SingleAxisPlatform::State::Zero(), J);
    const dynamics::EigenvaluesOf<4> ev = dynamics::eigenvalues<4>(J);
    double re_max = -1e9;
    for (int i = 0; i < 4; ++i) {
      if (std::abs(ev[i]) > 1e-6) re_max = std::max(re_max, ev[i].real());
    }
    if (f < 1.0) {
      EXPECT_LT(re_max, 0.0);
      EXPECT_EQ(b.invalid_reason(), nullptr);
    } else {
      EXPECT_GT(re_max, 0.0);
      EXPECT_NE(b.invalid_reason(), nullptr);
    }
  }
}

// The single-axis platform over a non-rotating Earth with the sampled Schuler loop: vehicle speed profile
// v(t) along a great circle (Ω = v/R about the platform axis, f = (v', 0, g − v²/R) in T axes).
struct SingleAxisRun {
  double T{5e-3};
  int substeps{2};
  double e0{0.0};         // initial tilt [rad]
  double drift{0.0};      // gyro drift [rad/s]
  double R_loop{kR};      // the loop's radius
  double accel{0.0}, t_accel0{0.0}, t_accel1{0.0};  // v' = accel on [t0, t1)
  double duration{3.0 * kTs};
  // Outputs
  analysis::ExtremaMeter<64> extrema;
  double tilt_max{0.0}, v_err_max{0.0}, pos_err_max{0.0};

  double speed(double t) const {
    return accel * (std::clamp(t, t_accel0, t_accel1) - t_accel0);
  }
  // Left limit at a ramp corner when `left` (the end of a step), right limit otherwise.
  models::FrameSample frame(double t, bool left = false) const {
    const bool on = left ? (t > t_accel0 && t <= t_accel1) : (t >= t_accel0 && t < t_accel1);
    const double v = speed(t), a = on ? accel : 0.0;
    return {dynamics::Vec3(0, v / kR, 0), dynamics::Vec3(0, a / kR, 0), dynamics::Vec3(a, 0, kG - v * v / kR)};
  }

  void run() {
    PlatformAxisParams a;
    a.drift = drift;
    SingleAxisPlatform p({a, 0.0});
    firmware::SchulerLoopParams lp;
    lp.radius = R_loop;
    lp.gravity_scale = models::kStandardGravity;
    lp.H = a.H;
    lp.initial_rate[0] = 0.0;
    lp.enabled[1] = false;
    lp.torque_limit_Nm = 1.0;
    ASSERT_TRUE(firmware::check_schuler_loop(lp, T).ok);
    firmware::SchulerLoop loop(lp, T);
    dynamics::Rk4<SingleAxisPlatform> integ(p);
    SingleAxisPlatform::State x;
    x << e0, 0.0, 0.0, 0.0;
    double held = 0.0, pos = 0.0;  // torque applied this tick (1 tick of latency)
    const long n = std::lround(duration / T);
    const double h = T / substeps;
    // Integrating (Δv) accelerometer, as the scene's: the mean apparent tilt over the previous tick.
    p.inputs.frame.hold(frame(0.0));
    double theta_mean = p.apparent_tilt(0.0, x);
    for (long k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) * T;
      p.inputs.frame.t0 = t;
      p.inputs.frame.h = T;
      p.inputs.frame.s0 = frame(t);
      p.inputs.frame.s1 = frame(t + T, true);
      const double theta[2] = {theta_mean, 0.0};
      const firmware::SchulerTorques m = loop.step(theta);
      p.inputs.torquer = held;
      held = m.M[0];
      const double theta0 = p.apparent_tilt(t, x);
      for (int j = 0; j < substeps; ++j) integ.step(t + j * h, h, x);
      theta_mean = 0.5 * (theta0 + p.apparent_tilt(t + T, x));
      tilt_max = std::max(tilt_max, std::fabs(x[0]));
      const double v_err = loop.velocity_estimate(0) - speed(t + T) * R_loop / kR;
      v_err_max = std::max(v_err_max, std::fabs(v_err));
      pos += v_err * T;
      pos_err_max = std::max(pos_err_max, std::fabs(pos));
      if ((k + 1) % 2000 == 0) extrema.add(t + T, x[0]);
    }
  }
};

TEST(InertialPlatformOracle, SchulerPeriodAndErrorCurvesForAnInitialTilt16_38_16_47) {
  SingleAxisRun r;
  r.e0 = 0.01 * kPi / 180.0;  // the book's example
  r.run();
  ASSERT_GE(r.extrema.count(), 4);
  std::printf("Schuler period %.3f s = %.4f min (book 2 pi sqrt(R/g) = %.4f min)\n", r.extrema.period(),
              r.extrema.period() / 60, kTs / 60);
  EXPECT_NEAR(r.extrema.period() / kTs, 1.0, 1e-4);
  EXPECT_NEAR(kTs / 60.0, 84.39, 0.01);
  // (16.46)-(16.47): α = α0 cos ω_S t; v error amplitude α0 sqrt(gR); position error up to 2 R α0.
  std::printf("tilt max %.4e (e0 %.4e), v error max %.4f m/s (book %.4f), position error max %.1f m (book %.1f)\n",
              r.tilt_max, r.e0, r.v_err_max, r.e0 * std::sqrt(kG * kR), r.pos_err_max, 2 * kR * r.e0);
  EXPECT_NEAR(r.tilt_max / r.e0, 1.0, 1e-3);
  EXPECT_NEAR(r.v_err_max / (r.e0 * std::sqrt(kG * kR)), 1.0, 1e-3);
  EXPECT_NEAR(r.pos_err_max / (2 * kR * r.e0), 1.0, 1e-3);
  EXPECT_NEAR(2 * kR * r.e0, 2224.0, 1.0);  // 2Rα0 recomputed: 2.224 km (book, §16.4.3: 2.2 km)
  // A loop tuned to 4R swings with twice the period (2π sqrt(R_loop/g)).
  SingleAxisRun m;
  m.e0 = r.e0;
  m.R_loop = 4 * kR;
  m.duration = 2.2 * kTs;
  m.run();
  ASSERT_GE(m.extrema.count(), 2);
  EXPECT_NEAR(m.extrema.period() / (2 * kTs), 1.0, 1e-4);
}

TEST(InertialPlatformOracle, GyroDriftErrorCurve16_49) {
  SingleAxisRun r;
  r.drift = 0.01 * kPi / 180.0 / 3600.0;  // 0.01 °/h
  r.duration = 1.0 * kTs;
  r.run();
  std::printf("drift: tilt max %.4e rad (book eps/omega_S %.4e)\n", r.tilt_max, r.drift / kWs);
  EXPECT_NEAR(r.tilt_max / (r.drift / kWs), 1.0, 1e-3);  // (16.49) α = (α0'/ω_S) sin ω_S t
}

TEST(InertialPlatformOracle, LevelUnderVehicleAccelerationWhenTuned16_34) {
  // 0 → 250 m/s in 100 s and cruise, started level: tuned, only the servo lag (v'/R)(H/k) ≈ 6.5e-8 rad and
  // the sampling lag remain; a loop tuned to 1.1 R errs by ≈ (v/R)(0.1/1.1)/ω_S at the speed change.
  SingleAxisRun tuned;
  tuned.accel = 2.5;
  tuned.t_accel0 = 600.0;
  tuned.t_accel1 = 700.0;
  tuned.duration = 2.0 * kTs;
  tuned.run();
  SingleAxisRun mistuned = tuned;
  mistuned.R_loop = 1.1 * kR;
  mistuned.extrema = analysis::ExtremaMeter<64>();
  mistuned.tilt_max = 0.0;
  mistuned.run();
  const double predicted_mistuned = 250.0 / kR * (0.1 / 1.1) / kWs;
  std::printf("level under acceleration: tuned max tilt %.3e rad, mistuned %.3e rad (predicted %.3e)\n",
              tuned.tilt_max, mistuned.tilt_max, predicted_mistuned);
  // Bound: the digital loop's lag — the Δv mean (T/2) plus one tick of latency — turns the platform late by
  // 1.5 T Δv/R = 2.9e-7 rad for Δv = 250 m/s; the servo lag adds ≲ 1e-8.
  EXPECT_LT(tuned.tilt_max, 1.5 * 5e-3 * 250.0 / kR + 5e-8);
  EXPECT_NEAR(mistuned.tilt_max / predicted_mistuned, 1.0, 0.1);  // the period also changes: ±10 %
}

// The three-axis platform in the azimuth-free frame of the vehicle generator over the rotating Earth, the
// Schuler loops on both level channels sampled at T. Returns the max level tilt and the extrema of e1.
struct ThreeAxisResult {
  double tilt_max{0.0};
  double azimuth_max{0.0};
  analysis::ExtremaMeter<64> extrema;
};

ThreeAxisResult run_three_axis(double e10, double R_loop, double duration) {
  using Gen = motion::EarthVehicle<8>;
  const motion::EarthParams earth{kR, kG, 7.292115e-5};
  const motion::VehicleStart start{45.0 * kPi / 180, 0.3, 60.0 * kPi / 180, 0.0};
  const motion::ManoeuvreSegment segs[] = {{600'000'000'000, 0.0, 0.0},
                                           {100'000'000'000, 0.0, 2.5},
                                           {1800'000'000'000, 0.0, 0.0},
                                           {30'000'000'000, 3.0 * kPi / 180, 0.0},
                                           {1000'000'000'000, 0.0, 0.0},
                                           {120'000'000'000, -1.5 * kPi / 180, 0.0},
                                           {600'000'000'000, 0.0, 0.0},
                                           {100'000'000'000, 0.0, -2.5}};
  EXPECT_EQ(Gen::check(earth, start, segs, 8), nullptr);
  const Gen gen(earth, start, segs, 8);
  ThreeAxisPlatform p;
  const double T = 5e-3;
  firmware::SchulerLoopParams lp;
  lp.radius = R_loop;
  lp.H = p.params().axis[0].H;
  const motion::EarthVehicleSample s0 = gen.sample(0.0);
  lp.initial_rate[0] = s0.azimuth_free.w_IZ_Z.x();
  lp.initial_rate[1] = s0.azimuth_free.w_IZ_Z.y();
  lp.torque_limit_Nm = 1.0;
  EXPECT_TRUE(firmware::check_schuler_loop(lp, T).ok);
  firmware::SchulerLoop loop(lp, T);
  // The step [t, t + T] sees the left limit at its end (the accelerations jump at the corners), the next
  // step starts from the right limit (earth_vehicle.hpp).
  auto frame_of = [](const motion::EarthVehicleSample& m) {
    const motion::Trihedron& F = m.azimuth_free;
    return models::FrameSample{F.w_IZ_Z, F.dw_IZ_Z, F.f_Z};
  };
  auto frame = [&](std::int64_t t_ns) { return frame_of(gen.sample_ns(t_ns)); };
  ThreeAxisPlatform::State x = ThreeAxisPlatform::State::Zero();
  models::FrameSample w0 = frame(0);
  x[0] = e10;
  x.segment<3>(3) = w0.Omega + w0.Omega.cross(x.segment<3>(0));
  dynamics::Rk4<ThreeAxisPlatform> integ(p);
  double held[2] = {-lp.H * lp.initial_rate[0], -lp.H * lp.initial_rate[1]};
  // Integrating (Δv) accelerometers: the loop reads the mean apparent tilt over the previous tick.
  p.inputs.frame.hold(w0);
  double theta0[2], theta_mean[2];
  p.apparent_tilts(0.0, x, theta0[0], theta0[1]);
  theta_mean[0] = theta0[0];
  theta_mean[1] = theta0[1];
  ThreeAxisResult r;
  const long n = std::lround(duration / T);
  for (long k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * T;
    const std::int64_t t1_ns = (k + 1) * 5'000'000;
    const models::FrameSample w1 = frame_of(gen.sample_left_ns(t1_ns));
    p.inputs.frame.t0 = t;
    p.inputs.frame.h = T;
    p.inputs.frame.s0 = w0;
    p.inputs.frame.s1 = w1;
    const firmware::SchulerTorques m = loop.step(theta_mean);
    p.inputs.torquer[0] = held[0];
    p.inputs.torquer[1] = held[1];
    held[0] = m.M[0];
    held[1] = m.M[1];
    integ.step(t, 0.5 * T, x);
    integ.step(t + 0.5 * T, 0.5 * T, x);
    double theta1[2];
    p.apparent_tilts(t + T, x, theta1[0], theta1[1]);  // left limit at the step's end
    for (int i = 0; i < 2; ++i) theta_mean[i] = 0.5 * (theta0[i] + theta1[i]);
    w0 = frame(t1_ns);
    p.inputs.frame.hold(w0);
    p.apparent_tilts(t + T, x, theta0[0], theta0[1]);  // right limit: the next step's start
    r.tilt_max = std::max(r.tilt_max, std::hypot(x[0], x[1]));
    r.azimuth_max = std::max(r.azimuth_max, std::fabs(x[2]));
    if ((k + 1) % 2000 == 0) r.extrema.add(t + T, x[0]);
  }
  return r;
}

TEST(InertialPlatformOracle, ThreeAxisLevelInTurnsAndAccelerationsOverTheRotatingEarth) {
  const double duration = 4400.0;  // ground, take-off to 250 m/s, turns, cruise, stop
  const ThreeAxisResult tuned = run_three_axis(0.0, kR, duration);
  const ThreeAxisResult mistuned = run_three_axis(0.0, 1.05 * kR, duration);
  std::printf("three-axis: tuned max tilt %.3e rad (azimuth %.3e), loop at 1.05 R: %.3e rad\n", tuned.tilt_max,
              tuned.azimuth_max, mistuned.tilt_max);
  // Tuned: each manoeuvre leaves the platform late by the digital loop's lag, 1.5 T |Δv|/R (the Δv mean's
  // T/2 plus one tick of latency) — Σ|Δv| = 250 + 354 (90° turn) + 500 (180° turn) + 250 m/s gives a bound
  // of 1.6e-6 rad if all add up (they add as vectors with the Schuler phase between them); the servo lag
  // (J d/(H k)) Δ(ω') is ≲ 1e-11. Without the Δv (mean) accelerometer the rectangle rule alone would err by
  // (T/2)|Δf| in velocity across every turn: 5.7e-6 rad of Schuler swing after the 90° turn.
  const double bound = 1.5 * 5e-3 * (250.0 + 250.0 * std::sqrt(2.0) + 500.0 + 250.0) / kR;
  EXPECT_LT(tuned.tilt_max, bound);
  EXPECT_LT(tuned.azimuth_max, bound);
  // Mistuned by 5 %: the Earth's own rate (ω^E R cos φ = 329 m/s of absolute velocity) is already enough.
  EXPECT_GT(mistuned.tilt_max, 100.0 * tuned.tilt_max);
}

TEST(InertialPlatformOracle, ThreeAxisSchulerPeriodOnTheLevelChannels) {
  const ThreeAxisResult r = run_three_axis(1e-4, kR, 1.6 * kTs);
  ASSERT_GE(r.extrema.count(), 3);
  std::printf("three-axis channel 1: period %.3f s (book %.3f s)\n", r.extrema.period(), kTs);
  // The level channels couple through the azimuth error and the Earth's horizontal rate Ω_h (e3' = q0 e1 −
  // p0 e2 feeds back as −q0 e3'), and the vertical specific force at rest is g − Ω_E² R cos²φ: the
  // frequencies move by relative O(Ω_h²/ω_S²) = 1.7e-3 at 45° — the book's 84.4 min is the single-axis,
  // non-rotating idealization (16.4.2). Tolerance 2e-3.
  EXPECT_NEAR(r.extrema.period() / kTs, 1.0, 2e-3);
  EXPECT_LE(r.tilt_max, 1.02e-4);
}

}  // namespace inertial_platform_test
}  // namespace gyrostab
