// Oracle tests of the rate gyro with an asymmetric rotor (sim/models/u_gyro.hpp) against Magnus §15.4,
// (15.27)-(15.29) (docs/models/u-gyro.md): the torque of the rotor on the held frame against (15.29); the
// output of a spring-restrained frame — its mean against H Ω / c2 (15.4) and its twice-spin component against
// (15.29) through the frame's response, with the rotor's varying inertia to second order (harmonic balance,
// sim/oracles/u_gyro_output.hpp) and without it (first order, tolerance the coupling's size).
//
// Measurement: RK4 from rest with the case turning from t = 0; after the transient has decayed (e^-30 at
// least), β is summed against cos 2γ, sin 2γ over whole twice-spin periods
// sampled 160 times each (discrete Fourier sums, exact for harmonics below 80 × 2γ'). Errors: RK4 at
// h × 2γ' = 0.039 errs by < 1e-8 of β2 (measured by halving the step: 1.1e-6 at 40 steps a period, 7e-8 at
// 80); the harmonic balance's next term, δ⁴ω⁸/(D1 D2² D3), is a few 1e-6 of β2 (measured 3-5e-6). Tolerance
// 1e-5 relative on β2 (coupled).
#include "sim/models/u_gyro.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "sim/dynamics/rk4.hpp"
#include "sim/oracles/u_gyro_output.hpp"

namespace gyrostab {
namespace u_gyro_test {

using models::UGyro;
using models::UGyroParams;
constexpr double kPi = std::numbers::pi;

TEST(UGyroHeldFrame, TorqueOnTheFrameIs15_29) {
  UGyroParams p;
  for (const double eps : {-0.9, -0.3, 0.0, 0.3, 0.9}) {
    p.AR = 0.5 * p.CR * (1.0 + eps);
    p.BR = 0.5 * p.CR * (1.0 - eps);
    UGyro g(p);
    g.inputs.Omega = 0.7;
    double worst = 0.0, c2 = 0.0, s2 = 0.0;
    const int n = 3600;
    for (int k = 0; k < n; ++k) {
      const double gamma = 2.0 * kPi * k / n;
      const double m = g.gyro_torque_on_frame(UGyro::make_state(0.0, 0.0, gamma));
      worst = std::fmax(worst, std::fabs(m - oracles::u_gyro_output_torque(p, 0.7, gamma)));
      c2 += m * std::cos(2.0 * gamma);
      s2 += m * std::sin(2.0 * gamma);
    }
    const double HOm = p.H() * 0.7;
    // The relative amplitude of the twice-spin part: −(A^R − B^R)/C^R (a cosine of 2γ with negative sign).
    const double rel = 2.0 / n * c2 / HOm;
    std::printf("  ε = %+.1f: max |M2 − (15.29)| %.1e N m, twice-spin amplitude / HΩ = %+.15f\n", eps, worst, rel);
    EXPECT_LT(worst, 1e-15 * 10.0 * HOm);  // the same algebra in two roundings
    EXPECT_NEAR(rel, -p.asymmetry(), 1e-14);
    EXPECT_NEAR(2.0 / n * s2 / HOm, 0.0, 1e-14);
  }
}

struct Output {
  double mean{0.0}, twice{0.0};
};

Output simulate(const UGyroParams& p, double Omega, int steps_per_period, double settle_s, int periods) {
  UGyro g(p);
  g.inputs.Omega = Omega;
  dynamics::Rk4<UGyro> rk4(g);
  auto x = UGyro::make_state(0.0, 0.0, 0.0);
  const double period = kPi / p.spin;  // of 2γ
  const double h = period / steps_per_period;
  const auto settle = static_cast<long>(std::ceil(settle_s / period)) * steps_per_period;
  for (long k = 0; k < settle; ++k) rk4.step(static_cast<double>(k) * h, h, x);
  double sum = 0.0, c2 = 0.0, s2 = 0.0;
  const long n = static_cast<long>(periods) * steps_per_period;
  for (long k = 0; k < n; ++k) {
    sum += x[UGyro::kBeta];
    const double gamma = p.spin * static_cast<double>(settle + k) * h;  // γ's exact value at this step
    c2 += x[UGyro::kBeta] * std::cos(2.0 * gamma);
    s2 += x[UGyro::kBeta] * std::sin(2.0 * gamma);
    rk4.step(static_cast<double>(settle + k) * h, h, x);
  }
  return {sum / static_cast<double>(n), 2.0 / static_cast<double>(n) * std::hypot(c2, s2)};
}

TEST(UGyroSpringFrame, TwiceSpinOutputMatches15_29ThroughTheFrame) {
  // The scene's gyro: 6000 rpm, ε = 0.3, frame tuned to twice the spin (sqrt(c2/B̄) = 2γ'), ζ = 0.05; and the
  // same rotor on a frame far below twice the spin (10 Hz, a P-gyro's) and one between twice and four times
  // the spin (a frame tuned near 4γ' would resonate with the 4γ harmonic and break the series).
  for (const double c2 : {600.0, 15.0, 1350.0}) {
    UGyroParams p;
    p.c2 = c2;
    const double B = p.mean_output_inertia();
    p.d2 = 0.1 * std::sqrt(c2 * B);  // ζ = 0.05
    const double decay = p.d2 / (2.0 * (B + 0.5 * (p.AR - p.BR)));
    const double settle = 30.0 / decay;
    const Output o = simulate(p, 0.5, 160, settle, 200);
    const double mean_book = oracles::u_gyro_mean_output(p, 0.5);
    const double first = oracles::u_gyro_twice_spin_output(p, 0.5);
    const double coupled = oracles::u_gyro_twice_spin_output_coupled(p, 0.5);
    const double coupling = oracles::u_gyro_inertia_coupling(p);
    std::printf("  c2 = %6.1f: mean rel err %+.2e; β2 %.6e rad, vs first order %+.2e (coupling %.1e), "
                "vs coupled %+.2e\n",
                c2, (o.mean - mean_book) / mean_book, o.twice, (o.twice - first) / first, coupling,
                (o.twice - coupled) / coupled);
    // (15.4) is linear in β: the exact mean carries cos β0 (relative β0²/2) and the Ω² stiffness of rotor and
    // frame inertias, Ω²|C^R − (A^R + B^R)/2 + C^J − A^J| / c2; both together stay below β0² + 1e-7 here.
    EXPECT_NEAR(o.mean / mean_book, 1.0, mean_book * mean_book + 1e-7);
    EXPECT_NEAR(o.twice / coupled, 1.0, 1e-5);
    // Without the coupling: off by at most its size (the correction term over D1), plus the coupled residual.
    EXPECT_NEAR(o.twice / first, 1.0, coupling * (1.0 + coupling) + 1e-5);
  }
}

TEST(UGyroSpringFrame, TwiceSpinOutputConvergesWithTheStep) {
  UGyroParams p;  // the scene's tuned frame
  const double settle = 0.5;
  const Output coarse = simulate(p, 0.5, 40, settle, 200), fine = simulate(p, 0.5, 80, settle, 200);
  const double coupled = oracles::u_gyro_twice_spin_output_coupled(p, 0.5);
  std::printf("  40 steps/period: %+.3e, 80: %+.3e (relative to the coupled prediction)\n",
              coarse.twice / coupled - 1.0, fine.twice / coupled - 1.0);
  // RK4's error falls 16× per halving: Richardson's |coarse − fine| / 15 is the finer run's step error, which
  // must be far below the 1e-5 tolerance of the coupled oracle (the rest there is the series' δ⁴ term).
  const double step_error_80 = std::fabs(coarse.twice - fine.twice) / 15.0 / coupled;
  std::printf("  step error at 80 steps/period (h × 2γ' = 0.079, the scene's): %.1e\n", step_error_80);
  EXPECT_LT(step_error_80, 1e-7);
}

}  // namespace u_gyro_test
}  // namespace gyrostab
