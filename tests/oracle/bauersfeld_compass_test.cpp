// Oracle tests of the two-rotor spatial compass of Bauersfeld (sim/models/bauersfeld_compass.hpp) against
// Magnus §13.4, (13.40)-(13.64) (docs/models/bauersfeld-compass.md), on the vehicle generator of
// sim/motion/earth_vehicle.hpp sampled exactly at every RK4 stage:
//   (a) tuned (13.60) and started per (13.64), a1 stays on the geocentric vertical through any manoeuvre; a
//       compass mistuned by 3 % leaves it, and swings about the offset its mistuning predicts;
//   (b) started off the vertical, each tilt component swings with T = 2π sqrt(|R^M|/g) (13.63);
//   (c) fixed to the Earth: a1 down, a3 north, a2 west (right-handed a1, a2, a3 with δ > 0), and
//       sin δ = H ω^E cosφ / (2 f);
//   (d) moving: a3 deviates from north by the speed deviation ψ_F = atan2(−v_N, v_E + ω^E R cosφ) — the
//       azimuth of the horizontal part of the vertical's absolute rate (16.51) — and
//       sin δ = H sqrt(v_N² + (v_E + ω^E R cosφ)²) / (2 f R);
//   (e) the scene's checks: no real δ, `tuned = true` with a mistuned spring.
//
// Error budget of the tuned runs (step_budget() below). The exact solution is a1 = −up(t), and along it the
// right-hand side of (13.57) is a function of time, −up''(t) (the a1-dependent Schuler term acts on the
// deviation only, ω_S² ≈ 1.5e-6 s⁻²): RK4 is then Simpson's rule for the rate, local error h⁵|up⁽⁶⁾|/2880,
// and for the position h⁵|up⁽⁵⁾|/720 a step. In a turn at rate r and speed v, |up⁽ᵏ⁾| ≈ (v/R) r^(k−1) (the
// Earth-rate terms are smaller by ω^E/r); on straight legs and at rest the derivatives are powers of v/R or
// ω^E (< 1e-20 s⁻⁵) and add nothing. The steps of a segment see one segment (corners on steps), so the jumps
// cost nothing. A rate error e turns into a Schuler swing of amplitude e/ω_S, so the tilt's budget is
// Σ n h⁵ (v/R) r⁴/720 + (Σ n h⁵ (v/R) r⁵/2880)/ω_S over the turns (n steps each, no cancellation assumed),
// plus rounding: 1e-13 rad (|a1| = 1 random-walks by ε = 1.1e-16 a step, ~1e-14 over 2e4 steps) and 1e-16
// rad/s. The azimuth's error is the rate's error across a1 over |a1'| ≥ min |ω_IG horizontal|, and sin δ's is
// H/(2f) times the rate's. Fixed to the Earth the derivatives are powers of ω^E: rounding only.
#include "sim/models/bauersfeld_compass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "sim/dynamics/rk4.hpp"
#include "sim/motion/vehicle_motion.hpp"
#include "sim/oracles/bauersfeld_compass.hpp"
#include "tools/commands.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab {
namespace bauersfeld_compass_test {

using dynamics::Vec3;
using Vehicle = motion::VehicleGenerator;
using Support = models::VehicleSupport<Vehicle>;
using Model = models::BauersfeldCompass<Support>;
using State = Model::State;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kR = 6.371e6, kG = 9.81, kW = 7.292115e-5;
constexpr double kH = 5.0, kM = 10.0, kS = 6.5e-4;
constexpr double kRM = kR - kS;  // |R^M|

models::BauersfeldCompassParams compass(double tuning_ratio = 1.0) {
  models::BauersfeldCompassParams p;
  p.H = kH;
  p.m = kM;
  p.s = kS;
  p.gravity = kG;
  p.f = models::bauersfeld_tuned_spring(kH, kM, kS, kRM) / tuning_ratio;
  return p;
}

motion::VehicleMotionParams earth_at(double latitude, double rotation = kW) {
  motion::VehicleMotionParams m;
  m.earth = {kR, kG, rotation};
  m.start.latitude = latitude;
  m.start.longitude = 8.0 * kDeg;
  return m;
}

void add(motion::VehicleMotionParams& m, double duration_s, double turn_deg_s, double accel) {
  m.segments[static_cast<std::size_t>(m.count++)] = {
      static_cast<std::int64_t>(std::llround(duration_s * 1e9)), turn_deg_s * kDeg, accel};
}

// A ship at 50°N: works up to 15 m/s northward, turns east, about to west, to 20 m/s, north, stops (4.3 h).
motion::VehicleMotionParams ship() {
  motion::VehicleMotionParams m = earth_at(50.0 * kDeg);
  add(m, 600, 0, 0);
  add(m, 300, 0, 0.05);
  add(m, 3600, 0, 0);
  add(m, 90, 1.0, 0);
  add(m, 3600, 0, 0);
  add(m, 120, -1.5, 0);
  add(m, 100, 0, 0.05);
  add(m, 3600, 0, 0);
  add(m, 120, 0.75, 0);
  add(m, 200, 0, -0.1);
  return m;
}

// An aircraft at 45°N heading 30°: take-off to 250 m/s, a full turn at 3°/s, S-turns, deceleration (1 h).
motion::VehicleMotionParams aircraft() {
  motion::VehicleMotionParams m = earth_at(45.0 * kDeg);
  m.start.heading = 30.0 * kDeg;
  add(m, 125, 0, 2.0);
  add(m, 600, 0, 0);
  add(m, 120, 3.0, 0);
  add(m, 300, 0, 0);
  add(m, 60, -2.0, 0);
  add(m, 60, 2.0, 0);
  add(m, 900, 0, 0);
  add(m, 100, 0, -1.5);
  add(m, 1335, 0, 0);
  return m;
}

struct Observed {
  double t;
  const State& x;
  const Vec3& a2;
  const motion::EarthVehicleSample& v;
  models::BauersfeldReading reading;
  double sin_delta;
};

// RK4 at step h from the (13.64) start plus a tilt, for T seconds; obs(Observed) at every step's start.
template <class Obs>
void run(const motion::VehicleMotionParams& plan, const models::BauersfeldCompassParams& p, double T,
         double h, double tilt_east, double tilt_north, Obs obs) {
  const Vehicle v = motion::make_vehicle(plan);
  Model model(p, Support{&v});
  dynamics::Rk4<Model> rk(model);
  const motion::EarthVehicleSample s0 = v.sample(0.0);
  State x = Model::start_state(s0.p_I, s0.v_I, s0.geographic.q_IZ, tilt_east, tilt_north);
  Vec3 a2 = s0.geographic.q_IZ * Vec3(-1.0, 0.0, 0.0);
  const auto n = static_cast<std::int64_t>(std::llround(T / h));
  for (std::int64_t k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) * h;
    const motion::EarthVehicleSample s = v.sample(t);
    a2 = Model::azimuth_axis(x, a2);
    obs(Observed{t, x, a2, s, models::bauersfeld_reading(Model::axis(x), a2, s.geographic.q_IZ),
                 model.sin_delta(x)});
    if (k < n) rk.step(t, h, x);
  }
}

// The tuned runs' error budget at step h (the file's header): tilt [rad] and the rate of a1 [rad/s].
struct Budget {
  double tilt{1e-13}, rate{1e-16};
};
Budget step_budget(const motion::VehicleMotionParams& plan, double h) {
  const Vehicle v = motion::make_vehicle(plan);
  Budget b;
  double position = 0.0, rate = 0.0;
  for (int k = 0; k < plan.count; ++k) {
    const motion::ManoeuvreSegment& g = plan.segments[static_cast<std::size_t>(k)];
    if (g.turn_rate == 0.0) continue;
    const double w = v.sample_ns(motion::segment_start_ns(plan, k)).speed / kR, r = std::fabs(g.turn_rate);
    const double n = 1e-9 * static_cast<double>(g.duration_ns) / h, h5 = std::pow(h, 5);
    position += n * h5 * w * std::pow(r, 4) / 720.0;
    rate += n * h5 * w * std::pow(r, 5) / 2880.0;
  }
  b.rate += rate;
  b.tilt += position + rate / std::sqrt(kG / kRM);
  return b;
}

struct Errors {
  double tilt{0.0}, azimuth{0.0}, azimuth_speed_form{0.0}, sin_delta{0.0}, speed_max{0.0}, rate_min{1e300};
};

// The tuned closed forms along a run: tilt from the vertical, azimuth against ψ_F (both forms), sin δ.
Errors tuned_errors(const motion::VehicleMotionParams& plan, const models::BauersfeldCompassParams& p,
                    double T, double h) {
  Errors e;
  run(plan, p, T, h, 0.0, 0.0, [&](const Observed& o) {
    const Vec3& w = o.v.geographic.w_IZ_Z;
    e.tilt = std::fmax(e.tilt, o.reading.tilt);
    e.azimuth = std::fmax(e.azimuth, std::fabs(std::remainder(
                                         o.reading.azimuth - oracles::bauersfeld_azimuth_book(w), 2 * kPi)));
    const double psi_f = oracles::bauersfeld_speed_deviation(o.v.v_north, o.v.v_east, o.v.latitude, kR,
                                                             plan.earth.rotation_rate);
    e.azimuth_speed_form =
        std::fmax(e.azimuth_speed_form, std::fabs(std::remainder(o.reading.azimuth - psi_f, 2 * kPi)));
    const double sd =
        p.H * std::hypot(o.v.v_north, o.v.v_east + plan.earth.rotation_rate * kR * std::cos(o.v.latitude)) /
        (2.0 * p.f * kR);
    e.sin_delta = std::fmax(e.sin_delta, std::fabs(o.sin_delta - sd));
    e.speed_max = std::fmax(e.speed_max, o.v.speed);
    e.rate_min = std::fmin(e.rate_min, std::hypot(w.x(), w.y()));
  });
  return e;
}

// --- (a) motion independence ------------------------------------------------------------------------------

TEST(BauersfeldTuned, StaysOnTheVerticalThroughAnyManoeuvre) {
  for (const auto& [name, plan, T] :
       {std::tuple{"ship", ship(), 15000.0}, std::tuple{"aircraft", aircraft(), 3600.0}}) {
    const Errors e1 = tuned_errors(plan, compass(), T, 1.0);
    const Errors e2 = tuned_errors(plan, compass(), T, 0.5);
    const Budget b1 = step_budget(plan, 1.0), b2 = step_budget(plan, 0.5);
    std::printf(
        "  %-8s (v up to %.0f m/s): tilt max %.2e rad (budget %.2e) at h = 1 s, %.2e (%.2e) at h = 0.5 s\n",
        name, e1.speed_max, e1.tilt, b1.tilt, e2.tilt, b2.tilt);
    EXPECT_LT(e1.tilt, b1.tilt) << name;
    EXPECT_LT(e2.tilt, b2.tilt) << name;
  }
}

TEST(BauersfeldTuned, MistunedByThreePercentLeavesTheVertical) {
  for (const double ratio : {0.97, 1.03}) {
    const Errors e = tuned_errors(ship(), compass(ratio), 15000.0, 1.0);
    std::printf("  tuning ratio %.2f: tilt max %.3e rad, azimuth off ψ_F by %.3e rad\n", ratio, e.tilt,
                e.azimuth);
    // At least 3 % of the steady offset κ ω^E² R sinφ cosφ / g (1.7e-3 rad at 50°) at rest alone: 5e-5 rad.
    EXPECT_GT(e.tilt, 1e4 * 1e-9);
    EXPECT_GT(e.azimuth, 1e-6);
  }
}

// Mistuned at rest, started per (13.64): the sphere swings about the steady offset toward north
//   ε_N = κ (R − s) (R^A'' horizontal)/g,  κ = K/(m s R) − 1,  R^A'' horizontal = ω^E² R sinφ cosφ (north),
// (K = H²/f + m s²; the deviation obeys R ε'' + g ε R/(R − s) = κ (R − s) R^A''⊥ in the linearization).
// Started on the vertical, the north tilt reaches 2 ε_N half a Schuler period later. Neglected: the Earth's
// rotation of the swing (Foucault, ω^E sinφ × T/2 = 0.14 rad: cos 0.14 = 0.99) and the start's rate mismatch
// ω^E ε (a cross swing of (ω^E/ω_S) ε = 6 % of ε, east); tolerance 3 % on the peak.
TEST(BauersfeldTuned, MistunedSwingsAboutItsPredictedOffset) {
  for (const double ratio : {0.95, 1.05}) {
    const models::BauersfeldCompassParams p = compass(ratio);
    const double kappa = p.effective_inertia() / (kM * kS * kR) - 1.0;
    const double phi = 50.0 * kDeg;
    const double offset = kappa * kRM * kW * kW * std::sin(phi) * std::cos(phi) / kG;
    double peak = 0.0;
    run(earth_at(phi), p, 0.5 * oracles::bauersfeld_period(kRM, kG) * 1.2, 1.0, 0.0, 0.0,
        [&](const Observed& o) {
          peak = std::fabs(o.reading.tilt_north) > std::fabs(peak) ? o.reading.tilt_north : peak;
        });
    std::printf("  ratio %.2f: κ = %+.4f, offset ε_N = %+.4e rad, north tilt peak %+.4e = %.4f × 2 ε_N\n",
                ratio, kappa, offset, peak, peak / (2 * offset));
    EXPECT_NEAR(peak / (2.0 * offset), 1.0, 0.03);
  }
}

// --- (b) the perturbed compass swings with (13.63) ---------------------------------------------------------

struct Periods {
  double east{0.0}, north{0.0};
  int crossings_east{0}, crossings_north{0};
};

// Mean period between upward zero crossings (linear interpolation between steps) of each tilt component.
Periods swing_periods(const motion::VehicleMotionParams& plan, double tilt, double T) {
  struct Crossings {
    double prev_t{0.0}, prev_y{0.0}, first{0.0}, last{0.0};
    int n{0};
    void add(double t, double y) {
      if (t > 0.0 && prev_y < 0.0 && y >= 0.0) {
        const double tc = prev_t + (t - prev_t) * (-prev_y / (y - prev_y));
        if (n == 0) first = tc;
        last = tc;
        ++n;
      }
      prev_t = t;
      prev_y = y;
    }
    double period() const { return n < 2 ? 0.0 : (last - first) / (n - 1); }
  } east, north;
  run(plan, compass(), T, 1.0, tilt, tilt, [&](const Observed& o) {
    east.add(o.t, o.reading.tilt_east);
    north.add(o.t, o.reading.tilt_north);
  });
  return {east.period(), north.period(), east.n, north.n};
}

// Tolerance 1e-6 relative (5 ms): the swing's nonlinearity at 1e-4 rad is θ²/16 ≈ 6e-10, the crossings'
// interpolation error ~ (ω_S h)² h/12 ≈ 1e-7 s, RK4's phase error (ω_S h)⁴/120 ≈ 2e-14.
TEST(BauersfeldPerturbed, EachTiltComponentSwingsWithTheSchulerPeriod) {
  const double T_book = oracles::bauersfeld_period(kRM, kG);  // (13.63)
  {
    // A non-rotating Earth: the book's inertial derivation holds as it stands, at any latitude.
    const Periods p = swing_periods(earth_at(50.0 * kDeg, 0.0), 1e-4, 8.0 * T_book);
    std::printf("  non-rotating, 50°: T east %.4f s, north %.4f s, book %.4f s (%.2f min)\n", p.east, p.north,
                T_book, T_book / 60.0);
    ASSERT_GE(p.crossings_east, 7);
    ASSERT_GE(p.crossings_north, 7);
    EXPECT_NEAR(p.east / T_book, 1.0, 1e-6);
    EXPECT_NEAR(p.north / T_book, 1.0, 1e-6);
  }
  {
    // The rotating Earth, at rest on the Equator: north (along the Earth's axis) exactly (13.63); east
    // lengthened by the Earth's rotation to 2π/sqrt(g/|R^M| − ω^E²) — 0.17 % — which (13.62) leaves out.
    const double T_east = oracles::bauersfeld_equator_east_period(kRM, kG, kW);
    const Periods p = swing_periods(earth_at(0.0), 1e-4, 8.0 * T_book);
    std::printf("  rotating, Equator: T east %.4f s (closed form %.4f s), north %.4f s (book %.4f s)\n",
                p.east, T_east, p.north, T_book);
    ASSERT_GE(p.crossings_east, 7);
    ASSERT_GE(p.crossings_north, 7);
    EXPECT_NEAR(p.north / T_book, 1.0, 1e-6);
    EXPECT_NEAR(p.east / T_east, 1.0, 1e-6);
    EXPECT_GT(p.east / T_book - 1.0, 1e-3);  // the Earth's rotation is seen: (ω^E/ω_S)²/2 = 1.7e-3
    EXPECT_LT(p.east / T_book - 1.0, 2e-3);
  }
}

// --- (c) fixed to the Earth ------------------------------------------------------------------------------

TEST(BauersfeldFixed, DownWestNorthAndTheSwingOfTheEarthRate) {
  for (const double lat : {0.0, 30.0, 50.0, 70.0, -40.0}) {
    const double phi = lat * kDeg;
    const models::BauersfeldCompassParams p = compass();
    const double sd_book = kH * kW * std::cos(phi) / (2.0 * p.f);
    double down = 0.0, west = 0.0, north = 0.0, sd = 0.0;
    run(earth_at(phi), p, 21600.0, 1.0, 0.0, 0.0, [&](const Observed& o) {
      const dynamics::Quat& q = o.v.geographic.q_IZ;
      const Vec3 a1 = Model::axis(o.x), a3 = a1.cross(o.a2);
      const auto angle = [](const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); };
      down = std::fmax(down, angle(a1, q * Vec3(0, 0, -1)));
      west = std::fmax(west, angle(o.a2, q * Vec3(-1, 0, 0)));
      north = std::fmax(north, angle(a3, q * Vec3(0, 1, 0)));
      sd = std::fmax(sd, std::fabs(o.sin_delta - sd_book));
    });
    std::printf(
        "  φ = %+5.1f°: a1 from down %.1e, a2 from west %.1e, a3 from north %.1e rad; δ = %.4f° "
        "(sin δ off H ω^E cosφ/(2f) by %.1e)\n",
        lat, down, west, north, std::asin(sd_book) / kDeg, sd);
    // Rounding only (header): 1e-13 rad on a1, and on a2, a3 the rate's rounding over |a1'| = ω^E cosφ ≥
    // 2.5e-5 rad/s (φ ≤ 70°) — 1e-16 / 2.5e-5 = 4e-12; tolerance 1e-11 rad, and 1e-12 on sin δ (H/(2f)
    // 1e-16).
    EXPECT_LT(down, 1e-11);
    EXPECT_LT(west, 1e-11);
    EXPECT_LT(north, 1e-11);
    EXPECT_LT(sd, 1e-12);
  }
}

// --- (d) moving: the speed deviation -----------------------------------------------------------------------

TEST(BauersfeldMoving, AzimuthIsTheSpeedDeviationAndDeltaFollowsTheVerticalsRate) {
  for (const auto& [name, plan, T] :
       {std::tuple{"ship", ship(), 15000.0}, std::tuple{"aircraft", aircraft(), 3600.0}}) {
    const models::BauersfeldCompassParams p = compass();
    const Errors e = tuned_errors(plan, p, T, 1.0);
    const Errors e2 = tuned_errors(plan, p, T, 0.5);
    const Budget b = step_budget(plan, 1.0);
    const double az_tol = (b.rate + std::sqrt(kG / kRM) * b.tilt) / e.rate_min;
    const double sd_tol = p.H * b.rate / (2.0 * p.f);
    std::printf(
        "  %-8s: azimuth − atan2(ω1, ω2) %.2e (budget %.2e; h = 0.5 s: %.2e), − atan2(−v_N, v_E + ω^E R "
        "cosφ) %.2e rad; sin δ %.2e (budget %.2e; h = 0.5 s: %.2e); |ω_IG,h| down to %.2e rad/s\n",
        name, e.azimuth, az_tol, e2.azimuth, e.azimuth_speed_form, e.sin_delta, sd_tol, e2.sin_delta,
        e.rate_min);
    EXPECT_LT(e.azimuth, az_tol) << name;
    EXPECT_LT(e.azimuth_speed_form, az_tol) << name;
    EXPECT_LT(e.sin_delta, sd_tol) << name;
    if (e.azimuth > 1e3 * 1e-16 / e.rate_min) {  // well above rounding: the error is RK4's, fourth order
      EXPECT_NEAR(e.azimuth / e2.azimuth, 16.0, 4.0) << name;
    }
  }
  // The deviation is large where it should be: northbound at 15 m/s at 50°N, ψ_F = −atan(15/(ω^E R cos 50°)).
  double psi_north = 0.0, lat = 0.0;
  run(ship(), compass(), 4000.0, 1.0, 0.0, 0.0, [&](const Observed& o) {
    psi_north = o.reading.azimuth;
    lat = o.v.latitude;
  });
  const double book = -std::atan(15.0 / (kW * kR * std::cos(lat)));
  std::printf("  northbound at 15 m/s, %.3f°N: azimuth %.6f°, −atan(v/(ω^E R cosφ)) %.6f°\n", lat / kDeg,
              psi_north / kDeg, book / kDeg);
  EXPECT_NEAR(psi_north, book, 1e-9);
  EXPECT_LT(psi_north, -2.8 * kDeg);
}

// --- (e) the scene's checks -----------------------------------------------------------------------------

std::string scene(const std::string& compass_keys) {
  return "[scene]\nname = \"t\"\ndevice = \"bauersfeld_compass\"\nduration_s = 100.0\n"
         "[loop]\ntick_us = 1000000\n[vehicle]\nlatitude_deg = 50.0\n[compass]\n" +
         compass_keys;
}

bool accepted(const std::string& text, std::string& first_error) {
  tools::SceneReader r;
  EXPECT_TRUE(r.parse(text, "t.toml"));
  const auto s = tools::read_device_scene(r);
  first_error = r.errors().empty() ? "" : r.errors().front();
  return s != nullptr;
}

TEST(BauersfeldScene, RefusesNoRealSwingAndAMistunedSpringAskedToBeTuned) {
  std::string why;
  EXPECT_TRUE(accepted(scene("H_Nms = 5.0\nm_kg = 10.0\ns_m = 6.5e-4\ntuned = true\n"), why)) << why;
  // Tuned with H = 0.1: sin δ = m s |R^M| ω^E cosφ / (2 H) = 9.7 at rest.
  EXPECT_FALSE(accepted(scene("H_Nms = 0.1\nm_kg = 10.0\ns_m = 6.5e-4\n"), why));
  EXPECT_NE(why.find("no real swing"), std::string::npos) << why;
  // f 1 % off: refused only when asked for tuned = true.
  const double f = 1.01 * models::bauersfeld_tuned_spring(5.0, 10.0, 6.5e-4, kRM);
  const std::string keys = "H_Nms = 5.0\nm_kg = 10.0\ns_m = 6.5e-4\nf_Nm = " + std::to_string(f) + "\n";
  EXPECT_TRUE(accepted(scene(keys), why)) << why;
  EXPECT_FALSE(accepted(scene(keys + "tuned = true\n"), why));
  EXPECT_NE(why.find("tuned = true"), std::string::npos) << why;
  EXPECT_FALSE(accepted(scene(keys + "tuning_ratio = 0.95\n"), why));
}

}  // namespace bauersfeld_compass_test
}  // namespace gyrostab
