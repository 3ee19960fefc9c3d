// The gyro pendulum on a pivot moving over the Earth in Magnus's small-angle form (12.55)-(12.58)
// (sim/models/gyro_pendulum_magnus.hpp), stepped by the gyroscopic exponential integrator (nutation carried
// exactly), against the book's closed forms: the roots (12.61), the tuned offset (12.66)-(12.67), the
// 84.39-min precession period (12.68), the velocity-dependent steady error −Hw/(kR) (12.65); and the
// physical pendulum (H = 0, RK4) against (12.59)-(12.60).
// Reference instrument (docs/models/gyro-pendulum.md, constructed): m = 5 kg, A = 0.02, C = 0.025 kg m²,
// H = 5 N m s.
#include "sim/models/gyro_pendulum_magnus.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>

#include "sim/analysis/zero_crossing_meter.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/motion/earth_vehicle.hpp"
#include "sim/oracles/schuler_tuning.hpp"

namespace gyrostab {
namespace gyro_pendulum_magnus_test {

using C = std::complex<double>;
using Vehicle = motion::EarthVehicle<8>;
using Ref = motion::EarthReference<Vehicle>;
constexpr std::int64_t kS = 1'000'000'000;
constexpr double kPi = std::numbers::pi;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Pivot at rest on a non-rotating Earth: f = g up, no frame rates.
struct AtRest {
  double g{9.81};
  motion::SuspensionSample operator()(double) const {
    motion::SuspensionSample s;
    s.f_Z = dynamics::Vec3(0.0, 0.0, g);
    s.f_I = s.f_Z;
    return s;
  }
};

models::GyroPendulumMagnusParams tuned(double s_factor = 1.0) {
  models::GyroPendulumMagnusParams p;
  p.A = 0.02;
  p.C = 0.025;
  p.H = 5.0;
  p.m = 5.0;
  p.s = s_factor * oracles::tuned_gyro_pendulum_offset(p.m, p.A, p.C, p.H, p.g, p.R);
  return p;
}

TEST(GyroPendulumMagnus, TunedOffsetIsThe1266RootAndNear1267) {
  const auto p = tuned();
  // Reference instrument: s = 1.264922e-4 m (quadratic), (12.67) 1.264916e-4 m, k = 6.2044e-3 N m/rad.
  EXPECT_NEAR(p.s, 1.264922e-4, 1e-10);
  EXPECT_NEAR(oracles::tuned_gyro_pendulum_offset_approx(p.m, p.H, p.g, p.R), 1.264916e-4, 1e-10);
  EXPECT_NEAR(p.k(), 6.2044e-3, 1e-7);
  const auto roots = oracles::gyro_pendulum_roots(p.A, p.H, p.k());
  EXPECT_NEAR(roots.nutation, 250.0, 0.05);  // reference: 250.0; exact 250.00124 = H/A (1 + Ak/H² …)
  EXPECT_NEAR(roots.precession, -1.24088e-3, 1e-8);
  // The tuning condition itself: m s − A/R + H/(R ω^P) = 0 with ω^P ≈ −k/H (12.66).
  EXPECT_NEAR(p.m * p.s - p.A / p.R - p.H * p.H / (p.R * p.k()), 0.0, 1e-15);
}

TEST(GyroPendulumMagnus, PrecessionPeriodIs8439MinutesAndNutationIsHOverA) {
  // Pure precession mode z = z0 e^(iω^P t) (z'(0) = iω^P z0): upward zero crossings of α over 6 h (4 periods).
  // The exponential integrator carries the nutation exactly and the slow stiffness −kz as a midpoint-held
  // forcing: precession-rate error O((h ω^P)²) ~ 1e-10 at h = 0.01 s. Tolerance: 1e-5 against (12.61), and
  // the 0.1 % against the book's 84.39 min (12.68).
  const auto p = tuned();
  using Model = models::GyroPendulumMagnus<AtRest>;
  const Model model(p, AtRest{p.g});
  dynamics::GyroscopicExponential<Model> integ(model);
  const auto roots = oracles::gyro_pendulum_roots(p.A, p.H, p.k());
  const C z0(1e-3, 0.0), dz0 = C(0.0, roots.precession) * z0;
  Model::State x = Model::make_state(z0.real(), z0.imag(), dz0.real(), dz0.imag());
  analysis::ZeroCrossingMeter meter;
  const double h = 0.01;
  double nutation_ripple = 0.0;
  for (long i = 0; i < std::lround(6.0 * 3600.0 / h); ++i) {
    integ.step(static_cast<double>(i) * h, h, x);
    const double t = static_cast<double>(i + 1) * h;
    meter.add(t, x[0], x[2]);
    nutation_ripple = std::max(nutation_ripple, std::abs(std::abs(C(x[0], x[1])) - 1e-3));
  }
  const double T = 2.0 * kPi / meter.angular_frequency();
  RecordProperty("precession_period_min", num(T / 60.0));
  RecordProperty("precession_period_book_min", num(2.0 * kPi / std::abs(roots.precession) / 60.0));
  EXPECT_NEAR(T * std::abs(roots.precession) / (2.0 * kPi), 1.0, 1e-5);
  EXPECT_NEAR(T / 60.0 / 84.39, 1.0, 1e-3);
  EXPECT_LT(nutation_ripple, 1e-9);  // a pure mode stays pure: |z| constant

  // Nutation: pure nutation mode z'(0) = iω^N z0 for 1 s at h = 1e-4 s; frequency from crossings (Hermite).
  Model::State y = Model::make_state(1e-6, 0.0, 0.0, roots.nutation * 1e-6);
  analysis::ZeroCrossingMeter nut;
  for (int i = 0; i < 10000; ++i) {
    integ.step(i * 1e-4, 1e-4, y);
    nut.add((i + 1) * 1e-4, y[0], y[2]);
  }
  // The exponential flow turns at H/A; the stiffness k, held at midpoints, adds the Ak/H² = 5e-6 of ω^N.
  EXPECT_NEAR(nut.angular_frequency() / roots.nutation, 1.0, 1e-6);
}

TEST(GyroPendulumMagnus, TunedInstrumentSitsOnTheVelocityErrorAfterAManoeuvre) {
  // Non-rotating Earth, 0.2 m/s² × 50 s northward (the reference manoeuvre): afterwards z = −Hw/(kR) (12.65)
  // plus the nutation-mode terms of (12.65), amplitude ≤ Σ_corners m s |Δw'|/(A ω^N
  // (ω^N − ω^P)) = 2 × 1.0e-7 rad, plus the precession-mode residual of tuning with the approximate ω^P of
  // (12.66) (~1e-9). Tolerance 3e-7 rad over the remaining 3 h. Mistuned (s × 3) the precession mode is
  // excited: residual ~3.4e-3 rad.
  motion::EarthParams e;
  e.rotation_rate = 0.0;
  const motion::ManoeuvreSegment seg[] = {{600 * kS, 0.0, 0.0}, {50 * kS, 0.0, 0.2}};
  const Vehicle veh(e, motion::VehicleStart{0.5, 0.0, 0.0, 0.0}, seg, 2);
  auto residual = [&](double s_factor) {
    const auto p = tuned(s_factor);
    using Model = models::GyroPendulumMagnus<Ref>;
    Model model(p, Ref{&veh, motion::ReferenceTrihedron::kAzimuthFree});
    dynamics::GyroscopicExponential<Model> integ(model);
    Model::State x = Model::make_state(0.0, 0.0);
    const double h = 0.01;
    double worst = 0.0;
    for (long i = 0; i < std::lround(3.0 * 3600.0 / h); ++i) {
      const double t = static_cast<double>(i) * h;
      model.reference().begin_step(t);
      integ.step(t, h, x);
      if (t > 700.0 && i % 50 == 0) {
        const motion::SuspensionSample z = model.reference()(t + h);
        const C w(z.v_Z.x(), z.v_Z.y());
        worst = std::max(worst, std::abs(C(x[0], x[1]) - oracles::velocity_error(p.H, p.k(), p.R, w)));
      }
    }
    return worst;
  };
  const double tuned_residual = residual(1.0), mistuned_residual = residual(3.0);
  RecordProperty("tuned_residual_rad", num(tuned_residual));
  RecordProperty("mistuned_residual_rad", num(mistuned_residual));
  EXPECT_LT(tuned_residual, 3e-7);
  EXPECT_NEAR(mistuned_residual, 3.4e-3, 0.1e-3);
  // The error itself: −H w/(k R) = −1.265e-3 rad for 10 m/s north (β, about F2 = north).
  const auto p = tuned();
  EXPECT_NEAR(oracles::velocity_error(p.H, p.k(), p.R, C(0.0, 10.0)).imag(), -1.265e-3, 1e-6);
}

TEST(GyroPendulumMagnus, PhysicalPendulumPeriodIs1260) {
  // H = 0, s = A/(mR) (12.59): A z'' + k z = 0 with k of (12.57) → T = 2π sqrt(R/g) sqrt(A/(4A − 3C)).
  // RK4 at h = 5 s: phase error (ωh)⁴/120 ~ 1e-13. Tolerance 1e-6.
  for (double C_over_A : {0.0, 1.0, 0.5}) {
    models::GyroPendulumMagnusParams p;
    p.A = 1.0;
    p.C = C_over_A;
    p.H = 0.0;
    p.m = 1.0;
    p.s = p.A / (p.m * p.R);
    using Model = models::GyroPendulumMagnus<AtRest>;
    const Model model(p, AtRest{p.g});
    dynamics::Rk4<Model> rk4(model);
    Model::State x = Model::make_state(1e-4, 0.0);
    analysis::ZeroCrossingMeter meter;
    for (int i = 0; i < 6000; ++i) {
      rk4.step(i * 5.0, 5.0, x);
      meter.add((i + 1) * 5.0, x[0], x[2]);
    }
    const double T = 2.0 * kPi / meter.angular_frequency();
    EXPECT_NEAR(T / oracles::tuned_pendulum_period(p.A, p.C, p.g, p.R), 1.0, 1e-6) << C_over_A;
  }
}

}  // namespace gyro_pendulum_magnus_test
}  // namespace gyrostab
