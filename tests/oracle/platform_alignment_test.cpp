// Oracle tests of platform alignment (sim/models/platform_alignment.hpp, sim/plants/platform_alignment_plant.hpp,
// firmware/control/platform_alignment_loops.hpp) against Magnus §16.5, (16.52) and the closed forms of the
// linearised loop (tools/devices/platform_alignment/platform_alignment_closed_forms.hpp, docs/models/platform-alignment.md):
//   (a) (16.52): the Earth rate on the east axis of a level platform with heading error ψ is −ω^E cosφ sinψ,
//       exactly for the exact kinematics (4.7e-8 rad/s for 1 mrad at 50°), and a platform not torqued about
//       its east axis tilts at that rate;
//   (b) levelling: the sampled closed loop against θ0 e^{−σt}(cos ω_d t − (σ/ω_d) sin ω_d t);
//   (c) azimuth: the heading error's decay against the cubic's slow root; the sampled check's bound against
//       the simulated loop (decays just inside, grows just outside); the continuous Hurwitz bound;
//   (d) residuals: θ_E = −b_N/g, θ_N = b_E/g, ψ = −ε_E/(ω^E cosφ) − θ_N tanφ − (ε_U + Ω_N θ_E)/(k_a Ω_N);
//   (e) the alignment time against the loop's prediction and its 1/cosφ growth near the latitude limit; the
//       limit itself (aligned in time just inside it, not just outside) and the scene check's refusal.
// The loop as a scene runs it: the plant sampled at each tick's start, the command of frame k applied over
// tick k + 1 (one tick of latency), T = 10 ms, RK4 with one sub-step (the platform integrates held rates: its
// local error is O((ωT)⁵) of rates ≲ 1e-3 rad/s, < 1e-20 rad a tick). No noise, no base motion.
#include "sim/models/platform_alignment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "firmware/control/platform_alignment_loops.hpp"
#include "sim/dynamics/rk4.hpp"
#include "tools/devices/platform_alignment/platform_alignment_closed_forms.hpp"
#include "sim/plants/platform_alignment_plant.hpp"
#include "tools/commands.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab {
namespace platform_alignment_test {

using firmware::PlatformAlignmentLoopParams;
using firmware::PlatformAlignmentLoops;
using models::PlatformAlignment;
using models::PlatformMisalignment;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kWe = 7.292115e-5;
constexpr double kT = 0.01;
constexpr double kDegH = kDeg / 3600.0;

// The closed loop: plant + loops, one tick of latency.
struct Loop {
  plants::PlatformAlignmentPlantParams plant{};
  PlatformAlignmentLoopParams law{};
  plants::PlatformAlignmentPlant* p{nullptr};

  Loop() {
    law.levelling_min_s = 120.0;
    law.settle_tilt_rad = 0.0;
    plant.gravity = 9.81;
  }
  void at(double latitude) {
    plant.platform.latitude = latitude;
    law.latitude = latitude;
  }

  // Runs `seconds`; fn(t, misalignment, loops) after every tick.
  template <class Fn>
  void run(double seconds, Fn&& fn) {
    law.H = plant.H;
    law.azimuth_torquer_scale = plant.azimuth_torquer_scale;
    law.earth_rate = plant.platform.earth_rate;
    plants::PlatformAlignmentPlant plant_obj(plant, {10'000'000, 1, 7});
    p = &plant_obj;
    PlatformAlignmentLoops loops(law, kT);
    const firmware::PlatformAlignmentGains g = loops.gains();
    plants::PlatformAlignmentPlant::ActuatorFrame applied{};
    applied.north_torquer_Nm = -plant.H * g.Omega_N;
    applied.zenith_torquer_V = g.Omega_U / plant.azimuth_torquer_scale;
    const auto n = static_cast<std::int64_t>(std::llround(seconds / kT));
    for (std::int64_t k = 0; k < n; ++k) {
      plants::PlatformAlignmentPlant::SensorFrame f;
      plant_obj.sense(k, f);
      const firmware::PlatformAlignmentCommand c = loops.step(f.theta_east_rad, f.theta_north_rad);
      plant_obj.actuate(applied);
      plant_obj.advance(k);
      applied = plants::PlatformAlignmentPlant::ActuatorFrame{};
      applied.east_torquer_Nm = c.M_east;
      applied.north_torquer_Nm = c.M_north;
      applied.zenith_torquer_V = c.u_zenith;
      if (!fn(static_cast<double>(k + 1) * kT, plant_obj.misalignment(), loops)) break;
    }
    p = nullptr;
  }
};

// --- (a) ---------------------------------------------------------------------------------------------------

TEST(PlatformAlignmentOracle, EastAxisEarthRate16_52) {
  const double phi = 50.0 * kDeg;
  models::PlatformAlignmentParams mp;
  mp.latitude = phi;
  PlatformAlignment m(mp);
  // Exact kinematics: rounding only (|ω^E| × a few ulp).
  for (const double psi : {1e-3, 0.1, 1.0, 2.5, -3.0}) {
    const PlatformAlignment::State x = PlatformAlignment::state_of(models::attitude_of({0.0, 0.0, psi}));
    EXPECT_NEAR(m.earth_rate_on_platform(x).x(), -kWe * std::cos(phi) * std::sin(psi), 1e-20) << psi;
  }
  // The book's number: 1 mrad at 50° gives 4.7e-8 rad/s (two digits).
  const PlatformAlignment::State x1 = PlatformAlignment::state_of(models::attitude_of({0.0, 0.0, 1e-3}));
  EXPECT_NEAR(std::fabs(m.earth_rate_on_platform(x1).x()), 4.7e-8, 0.05e-8);

  // A platform held at the command that keeps it fixed in G, except none about its east axis, tilts about
  // east at +Ω_N sinψ (θ_E' = ω_cE + Ω_N sinψ). Over t the held command no longer matches the Earth rate on
  // the moved axes: θ_E' and ψ' pick up Ω_U θ_N and −Ω_N θ_E, which bend the tilt by −(ω^E t)²/6 relative
  // (8.86e-6 over 100 s; the next term (ω^E t)⁴/120 ~ 2e-11, the angles' own second order θ_E ψ ~ 5e-9; RK4
  // at 0.1 s is exact to 1e-15 here). Against the corrected value, tolerance 1e-7 relative; the uncorrected
  // (16.52) rate holds to 2e-5.
  const double psi = 1e-3, t_end = 100.0;
  PlatformAlignment::State x = x1;
  m.inputs.rate_command = m.earth_rate_on_platform(x);
  m.inputs.rate_command.x() = 0.0;
  dynamics::Rk4<PlatformAlignment> rk(m);
  for (int k = 0; k < 1000; ++k) rk.step(k * 0.1, 0.1, x);
  const double expected = kWe * std::cos(phi) * std::sin(psi) * t_end;
  std::printf("(16.52) tilt after %.0f s: %.9e rad, Omega_N sin(psi) t = %.9e rad (rel %.2e)\n", t_end,
              PlatformAlignment::misalignment(x).tilt_east, expected,
              PlatformAlignment::misalignment(x).tilt_east / expected - 1.0);
  EXPECT_NEAR(PlatformAlignment::misalignment(x).tilt_east, expected, 2e-5 * expected);
  const double corrected = expected * (1.0 - std::pow(kWe * t_end, 2) / 6.0);
  EXPECT_NEAR(PlatformAlignment::misalignment(x).tilt_east, corrected, 1e-7 * expected);
}

TEST(PlatformAlignmentOracle, MisalignmentRoundTripIsExact) {
  for (const PlatformMisalignment a : {PlatformMisalignment{0.01, -0.02, 0.3}, PlatformMisalignment{-0.1, 0.05, -2.9},
                                       PlatformMisalignment{0.2, 0.15, 1.6}}) {
    const PlatformMisalignment b = models::misalignment_of(models::attitude_of(a));
    EXPECT_NEAR(b.tilt_east, a.tilt_east, 1e-14);
    EXPECT_NEAR(b.tilt_north, a.tilt_north, 1e-14);
    EXPECT_NEAR(b.heading_error, a.heading_error, 1e-14);
  }
}

// --- (b) ---------------------------------------------------------------------------------------------------

// The north channel from θ_N(0) = 1°, everything else aligned. Neglected: the one-tick latency plus the
// forward-Euler integrator delay the loop by ≈ 1.5 T, which perturbs the response by ≲ 1.5 ω_L T θ0 ×
// (peak sensitivity ≈ 2) = 5e-5 rad; the gain g/g0 = 1.00035 and sin θ (θ0²/6 = 5e-5 relative) add < 1e-5 rad;
// the Ω_U coupling through θ_E (driven at Ω_U θ_N ~ 1e-6 rad/s) < 1e-8 rad. Tolerance 6e-5 rad (3.4e-3 θ0).
TEST(PlatformAlignmentOracle, LevellingIsTheSecondOrderLoop) {
  Loop L;
  L.at(50.0 * kDeg);
  L.law.levelling_min_s = 1e6;  // levelling only
  const double theta0 = 1.0 * kDeg;
  L.plant.initial = {0.0, theta0, 0.0};
  double worst = 0.0, worst_e = 0.0;
  L.run(120.0, [&](double t, const PlatformMisalignment& m, const PlatformAlignmentLoops&) {
    const double cf = oracles::levelling_response(theta0, L.law.levelling_bandwidth, L.law.levelling_damping, t);
    worst = std::fmax(worst, std::fabs(m.tilt_north - cf));
    worst_e = std::fmax(worst_e, std::fabs(m.tilt_east));
    return true;
  });
  std::printf("levelling: max |θ_N − closed form| = %.3e rad (θ0 = %.3e), max |θ_E| = %.3e\n", worst, theta0,
              worst_e);
  EXPECT_LT(worst, 6e-5);
  EXPECT_LT(worst_e, 1e-5);  // the cross-coupling through Ω_U only
}

// --- (c) ---------------------------------------------------------------------------------------------------

// The decay of tan(|ψ|/2) (exact for the quasi-static loop ψ' = s_A sinψ) fitted by least squares on
// [t_s + 100 s, t_s + 100 s + 3τ]: the levelling roots are down to e^{−ζω_L 100} = 1e-3 of their small
// share (≈ a/ω_L) at the start. The sampled loop's slow root differs from the continuous one by O(1.5 T ω_L
// × a/ω_L) = O(1.5 T a) ≲ 2.5e-4 relative (a ≤ 0.017 /s at the equator); the quasi-static model's neglected
// levelling lag by O((a/ω_L)² ψ²) < 1e-5. Tolerance 5e-4 relative, at three latitudes.
TEST(PlatformAlignmentOracle, AzimuthDecayIsTheSlowRoot) {
  for (const double lat : {0.0, 50.0, 75.0}) {
    Loop L;
    L.at(lat * kDeg);
    L.plant.initial = {0.0, 0.0, 2.0 * kDeg};
    const double sA = oracles::azimuth_slow_root(oracles::gains_at(L.law, lat * kDeg));
    const double t0 = L.law.levelling_min_s + 100.0, t1 = t0 + 3.0 / std::fabs(sA);
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    L.run(t1, [&](double t, const PlatformMisalignment& m, const PlatformAlignmentLoops&) {
      if (t >= t0) {
        const double y = std::log(std::tan(0.5 * std::fabs(m.heading_error)));
        n += 1, sx += t, sy += y, sxx += t * t, sxy += t * y;
      }
      return true;
    });
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    std::printf("azimuth at %g deg: fitted rate %.6e /s, slow root %.6e /s (rel %.2e), k_a Omega_N %.6e\n", lat,
                slope, sA, slope / sA - 1.0, oracles::gains_at(L.law, lat * kDeg).k_a * kWe * std::cos(lat * kDeg));
    EXPECT_NEAR(slope / sA, 1.0, 5e-4) << lat;
  }
}

// The check's sampled bound on the levelling bandwidth (T = 10 ms, one period of latency) against the loop
// itself: at 0.9× the bound the tilt decays, at 1.1× it grows. The continuous Hurwitz bound on τ_A0 likewise.
TEST(PlatformAlignmentOracle, SampledCheckBoundsTheLoop) {
  PlatformAlignmentLoopParams p;
  double lo = 0.1, hi = 1000.0;  // accepted, refused
  p.levelling_bandwidth = hi;
  ASSERT_FALSE(firmware::check_platform_alignment_loops(p, kT).ok);
  for (int i = 0; i < 60; ++i) {
    p.levelling_bandwidth = std::sqrt(lo * hi);
    (firmware::check_platform_alignment_loops(p, kT).ok ? lo : hi) = p.levelling_bandwidth;
  }
  std::printf("sampled levelling bound: omega_L T = %.4f\n", lo * kT);
  for (const double f : {0.9, 1.1}) {
    Loop L;
    L.at(50.0 * kDeg);
    L.law.levelling_min_s = 1e6;
    L.law.levelling_bandwidth = f * lo;
    L.law.torque_limit_Nm = 1e9;  // linear: no clipping
    L.plant.initial = {0.0, 1e-9, 0.0};
    double early = 0.0, late = 0.0;
    L.run(8.0, [&](double t, const PlatformMisalignment& m, const PlatformAlignmentLoops&) {
      if (t > 1.0 && t <= 2.0) early = std::fmax(early, std::fabs(m.tilt_north));
      if (t > 7.0) late = std::fmax(late, std::fabs(m.tilt_north));
      return true;
    });
    std::printf("  %.1f x bound: max |theta| over [1, 2] s %.3e, over [7, 8] s %.3e\n", f, early, late);
    if (f < 1.0) {
      EXPECT_LT(late, 0.1 * early);
    } else {
      EXPECT_GT(late, 10.0 * early);
    }
  }
  // Continuous azimuth loop: refused once k_a ≥ K1 (K2 + Ω_N²)/(K2 Ω_N).
  PlatformAlignmentLoopParams q;
  const firmware::PlatformAlignmentGains g = firmware::platform_alignment_gains(q);
  const double tau_min = g.K2 * g.Omega_N / (kWe * g.K1 * (g.K2 + g.Omega_N * g.Omega_N));
  q.azimuth_time_constant_equator = 1.01 * tau_min;
  EXPECT_TRUE(firmware::check_platform_alignment_loops(q, 1e-4).ok) << firmware::check_platform_alignment_loops(q, 1e-4).reason;
  q.azimuth_time_constant_equator = 0.99 * tau_min;
  EXPECT_FALSE(firmware::check_platform_alignment_loops(q, 1e-4).ok);
  // At the scenes' T = 10 ms the sampled azimuth polynomial agrees with the continuous bound to O(ω T).
  q.azimuth_time_constant_equator = 1.05 * tau_min;
  EXPECT_TRUE(firmware::check_platform_alignment_loops(q, kT).ok) << firmware::check_platform_alignment_loops(q, kT).reason;
}

// --- (d) ---------------------------------------------------------------------------------------------------

// Constant biases and drifts, 20 slow time constants after the switch (the start's share e^-20 = 2e-9 of
// ψ0 = 0.5°: < 2e-11 rad). The steady state of the sampled loop is the continuous one exactly (constant
// held commands); what the closed form neglects is second order in the small angles: |θ|, |ψ| ≲ 2e-3, i.e.
// relative errors of the order of the angles themselves on ψ (its terms θ_N Ω_U, ψ Ω_N are exact to
// O(angle²): ≲ 1e-3 × 5e-2 ~ 5e-5) and O(θ²) ~ 1e-8 on the tilts. Tolerances: tilts 1e-6 relative, heading
// error 1e-4 relative.
TEST(PlatformAlignmentOracle, ResidualsOfBiasesAndDrifts) {
  for (const double lat : {30.0, 50.0, 70.0}) {
    Loop L;
    L.at(lat * kDeg);
    L.plant.initial = {0.3 * kDeg, -0.2 * kDeg, 0.5 * kDeg};
    L.plant.platform.accel_bias = {5e-4, -3e-4, 1e-3};
    L.plant.platform.drift = {0.005 * kDegH, -0.004 * kDegH, 0.006 * kDegH};
    const firmware::PlatformAlignmentGains g = oracles::gains_at(L.law, lat * kDeg);
    const double tau = 1.0 / std::fabs(oracles::azimuth_slow_root(g));
    PlatformMisalignment end{};
    L.run(L.law.levelling_min_s + 20.0 * tau, [&](double, const PlatformMisalignment& m, const PlatformAlignmentLoops&) {
      end = m;
      return true;
    });
    const PlatformMisalignment ss = oracles::steady_misalignment(g, L.plant.platform, L.plant.gravity);
    const double drift_term = -L.plant.platform.drift.x() / (kWe * std::cos(lat * kDeg));
    std::printf("residuals at %g deg: theta_E %.10e (%.10e), theta_N %.10e (%.10e), psi %.8e (%.8e; -eps_E/(wE cos) "
                "%.6e)\n",
                lat, end.tilt_east, ss.tilt_east, end.tilt_north, ss.tilt_north, end.heading_error, ss.heading_error,
                drift_term);
    EXPECT_NEAR(end.tilt_east, -(-3e-4) / 9.81, 1e-6 * std::fabs(ss.tilt_east));
    EXPECT_NEAR(end.tilt_north, 5e-4 / 9.81, 1e-6 * std::fabs(ss.tilt_north));
    EXPECT_NEAR(end.heading_error, ss.heading_error, 1e-4 * std::fabs(ss.heading_error));
    // The drift term dominates; the north tilt adds (b_E/g) tanφ.
    EXPECT_NEAR(ss.heading_error, drift_term - ss.tilt_north * std::tan(lat * kDeg),
                0.02 * std::fabs(drift_term));
  }
}

// --- (e) ---------------------------------------------------------------------------------------------------

// Time from the switch until |ψ| ≤ 1 mrad from ψ0 = 5° (no drifts, no biases), (1) against the closed form
// (quasi-static decay of tan(ψ/2) at the cubic's slow root; neglected: the levelling roots' share ≈ a/ω_L of
// the start, worth ≲ (a/ω_L)/(ζω_L) of time ≈ 10 s of 300 s at the equator, less near the limit; tolerance
// 1 %), and (2) against the 1/cosφ law relative to 70°. The slow root of s³ + K1 s² + K2' s + c is
// −(c/K2')(1 + ε + 2ε² + …) − s³/K2' with ε = K1 c/K2'² ≈ 2ζ k_a ω^E cosφ/ω_L, so t(φ) cosφ/(t(70°) cos70°)
// = 1 + ε(70°) − ε(φ) + O(2ε², s²/K2): measured against that first-order law with tolerance
// 3 max(ε², s²/K2) + 0.5 % (near the limit ε → 0: the pure 1/cosφ law).
TEST(PlatformAlignmentOracle, AlignmentTimeGrowsAsOneOverCosLatitude) {
  const auto time_at = [](double lat) {
    Loop L;
    L.at(lat * kDeg);
    L.plant.initial = {0.0, 0.0, 5.0 * kDeg};
    double last_out = 0.0;
    L.run(L.law.levelling_min_s + 30.0 * 95.0 / std::cos(lat * kDeg),
          [&](double t, const PlatformMisalignment& m, const PlatformAlignmentLoops&) {
            if (std::fabs(m.heading_error) > 1e-3) last_out = t;
            return t < last_out + 200.0;
          });
    return last_out - L.law.levelling_min_s;
  };
  PlatformAlignmentLoopParams lp;
  const auto eps = [&](double lat) {
    const firmware::PlatformAlignmentGains g = oracles::gains_at(lp, lat * kDeg);
    return g.K1 * g.k_a * g.Omega_N / g.K2;
  };
  const auto cubic = [&](double lat) {  // s²/K2 at the slow root
    const double s = oracles::azimuth_slow_root(oracles::gains_at(lp, lat * kDeg));
    return s * s / oracles::gains_at(lp, lat * kDeg).K2;
  };
  const double ref = time_at(70.0) * std::cos(70.0 * kDeg);
  for (const double lat : {0.0, 50.0, 70.0, 75.0, 78.0, 80.0}) {
    const double t = time_at(lat);
    oracles::AlignmentTimeInputs in;
    in.loop = lp;
    in.heading_error0 = 5.0 * kDeg;
    in.heading_tolerance = 1e-3;
    const double cf = oracles::alignment_time(in, lat * kDeg);
    const double law = t * std::cos(lat * kDeg) / ref;
    const double second = 3.0 * std::fmax(std::fmax(eps(lat) * eps(lat), eps(70.0) * eps(70.0)),
                                          std::fmax(cubic(lat), cubic(70.0)));
    const double tol = second + 0.005;
    std::printf("lat %4.0f: azimuth time %.1f s, closed form %.1f s (rel %.2e), t cos(lat) / ref %.4f "
                "(1 + eps(70) - eps = %.4f, tolerance %.4f)\n",
                lat, t, cf, t / cf - 1.0, law, 1.0 + eps(70.0) - eps(lat), tol);
    EXPECT_NEAR(t / cf, 1.0, 0.01) << lat;
    EXPECT_NEAR(law, 1.0 + eps(70.0) - eps(lat), tol) << lat;
  }
}

// The latitude limit for a maximum time. Time-limited (no drift): the closed form's time equals the maximum
// at the limit, and the simulated platform is within the tolerance at the maximum time 1° inside the limit
// and not 1° outside (the time grows by ≈ tanφ · 1° ≈ 9 % per degree there, far beyond the 1 % of the
// closed form). Drift-limited: beyond the limit the residual ε_E/(ω^E cosφ) itself exceeds the tolerance —
// after 20 slow time constants the platform ends inside the band 1° inside the limit and outside 1° beyond.
TEST(PlatformAlignmentOracle, LatitudeLimitIsReal) {
  oracles::AlignmentTimeInputs in;
  in.heading_error0 = 8.0 * kDeg;
  in.heading_tolerance = 1e-3;
  in.switch_time = in.loop.levelling_min_s;
  const double max_time = 1500.0;
  const double limit = oracles::latitude_limit(in, max_time);
  std::printf("time-limited: latitude limit %.3f deg for %.0f s\n", limit / kDeg, max_time);
  ASSERT_GT(limit, 0.0);
  EXPECT_NEAR(oracles::alignment_time(in, limit), max_time, 1e-6 * max_time);
  for (const double d : {-1.0, 1.0}) {
    Loop L;
    L.at(limit + d * kDeg);
    L.plant.initial = {0.0, 0.0, in.heading_error0};
    double psi_end = 0.0;
    L.run(max_time, [&](double, const PlatformMisalignment& m, const PlatformAlignmentLoops&) {
      psi_end = m.heading_error;
      return true;
    });
    EXPECT_EQ(std::fabs(psi_end) <= in.heading_tolerance, d < 0.0) << d << " " << psi_end;
  }

  in.platform.drift = {0.003 * kDegH, 0.0, 0.0};
  const double drift_limit = oracles::latitude_limit(in, 1e9);
  const double cos_bound = 0.003 * kDegH / (kWe * in.heading_tolerance);  // |ε_E|/(ω^E tol), k_a term aside
  std::printf("drift-limited: latitude limit %.3f deg (acos(|eps_E|/(wE tol)) = %.3f deg)\n", drift_limit / kDeg,
              std::acos(cos_bound) / kDeg);
  EXPECT_NEAR(std::cos(drift_limit), cos_bound, 0.01 * cos_bound);
  for (const double d : {-1.0, 1.0}) {
    Loop L;
    L.at(drift_limit + d * kDeg);
    L.plant.initial = {0.0, 0.0, in.heading_error0};
    L.plant.platform.drift = in.platform.drift;
    const double tau = 1.0 / std::fabs(oracles::azimuth_slow_root(oracles::gains_at(L.law, drift_limit + d * kDeg)));
    double psi_end = 0.0;
    L.run(L.law.levelling_min_s + 20.0 * tau, [&](double, const PlatformMisalignment& m, const PlatformAlignmentLoops&) {
      psi_end = m.heading_error;
      return true;
    });
    EXPECT_EQ(std::fabs(psi_end) <= in.heading_tolerance, d < 0.0) << d << " " << psi_end;
  }
}

TEST(PlatformAlignmentOracle, SceneRefusesLatitudesBeyondTheLimit) {
  const std::string base = std::string(GYROSTAB_SOURCE_DIR) + "/sim/scenes/platform-alignment-high-latitude.toml";
  tools::SceneReader ok;
  ASSERT_TRUE(ok.open(base));
  EXPECT_NE(tools::read_device_scene(ok), nullptr) << (ok.errors().empty() ? "" : ok.errors().front());

  const std::string text = R"(
[scene]
name = "too-far-north"
device = "platform_alignment"
duration_s = 3000.0
[loop]
tick_us = 10000
[site]
latitude_deg = 83.0
[platform]
heading_error0_deg = 8.0
[gyros]
drift_east_deg_h = 0.003
[alignment]
max_time_s = 2700.0
heading_tolerance_deg = 0.0859
)";
  tools::SceneReader r;
  ASSERT_TRUE(r.parse(text, "too-far-north.toml"));
  EXPECT_EQ(tools::read_device_scene(r), nullptr);
  bool named = false;
  for (const std::string& e : r.errors()) named = named || e.find("latitude limit") != std::string::npos;
  EXPECT_TRUE(named) << (r.errors().empty() ? "" : r.errors().front());
}

}  // namespace platform_alignment_test
}  // namespace gyrostab
