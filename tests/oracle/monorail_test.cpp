// Oracle tests of the gyro-stabilized monorail car (sim/models/monorail.hpp) against Magnus §14.1
// (docs/models/monorail.md): the gain window d(c + Aω_P²)/H < k < d(c + Aω_N²)/H of the Hurwitz conditions
// (14.5), with growth rates and frequencies measured from the simulated car and compared with the roots of
// the characteristic equation (14.3); curve running (14.6)-(14.7); and energy conservation of the
// large-angle terms.
//
// Measurement: for the linearisation x' = M x of (14.6) (Ω3 = 0: (14.2)), a left eigenvector w of M with
// eigenvalue λ makes η(t) = wᴴ x(t) = η(0) e^{λt} exactly, whatever the other modes do. The simulated state
// is projected on w; Re λ = ln|η(T)/η(0)|/T and Im λ = (unwrapped arg increment)/T. The projection is an
// independent reading of the simulation: a model that differs from (14.6) leaks other modes into η and
// its rate differs.
// Integrator: RK4 at h = 1 ms; |λ|max ≈ 9.5 s⁻¹, so each mode's per-step error is ≤ (h|λ|)⁵/120 ≈ 6e-13
// relative and its rate errs by ≤ |λ|(h|λ|)⁴/120 ≈ 6e-10 s⁻¹. Amplitudes stay ≤ 1e-4 rad, so the
// large-angle terms shift the rates by ≲ |λ|·1e-8 ≈ 1e-7 s⁻¹. Rate tolerance: 1e-6 s⁻¹ (0.06 % of the
// smallest |Re λ| tested, 1.7e-3 s⁻¹).
#include "sim/models/monorail.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

#include "sim/dynamics/rk4.hpp"
#include "tests/support/alloc_counter.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab {
namespace monorail_test {

using models::Monorail;
using models::MonorailParams;
using Rk4 = dynamics::Rk4<Monorail>;
using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// ---- the book's linear theory

// Roots of (14.3) with c → c − HΩ3, q → q − HΩ3 (14.6), from the companion matrix of the quartic.
Eigen::Vector4cd characteristic_roots(const MonorailParams& p, double Omega3) {
  const double c = p.c - p.H * Omega3, q = p.q - p.H * Omega3;
  const double a4 = p.A * p.B, a3 = p.A * p.d, a2 = p.H * p.H - q * p.A - c * p.B, a1 = p.k * p.H - c * p.d,
               a0 = c * q;
  Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
  C(1, 0) = C(2, 1) = C(3, 2) = 1.0;
  C(0, 3) = -a0 / a4;
  C(1, 3) = -a1 / a4;
  C(2, 3) = -a2 / a4;
  C(3, 3) = -a3 / a4;
  return dynamics::eigenvalues<4>(C);
}

// State matrix of (14.6) for x = [φ, β, φ', β'].
Eigen::Matrix4d state_matrix(const MonorailParams& p, double Omega3) {
  const double c = p.c - p.H * Omega3, q = p.q - p.H * Omega3;
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  M(0, 2) = M(1, 3) = 1.0;
  M(2, 0) = c / p.A;
  M(2, 3) = -p.H / p.A;
  M(3, 0) = p.k / p.B;
  M(3, 1) = q / p.B;
  M(3, 2) = p.H / p.B;
  M(3, 3) = -p.d / p.B;
  return M;
}

// Undamped frequencies ω_P < ω_N: roots of AB Ω⁴ − (H² − qA − cB) Ω² + cq = 0 (docs/models/monorail.md).
void undamped_frequencies(const MonorailParams& p, double& wP, double& wN) {
  const double b = p.H * p.H - p.q * p.A - p.c * p.B, r = std::sqrt(b * b - 4.0 * p.A * p.B * p.c * p.q);
  wP = std::sqrt((b - r) / (2.0 * p.A * p.B));
  wN = std::sqrt((b + r) / (2.0 * p.A * p.B));
}

struct Measured {
  cd lambda_book{};     // dominant root (largest Re λ) of the characteristic equation
  double rate{0};       // measured Re λ [1/s]
  double frequency{0};  // measured |Im λ| [rad/s]
  double max_angle{0};  // largest |φ|, |β| seen [rad]
};

// Simulate from a generic small state and read the dominant mode through its left eigenvector.
Measured measure_dominant_mode(const MonorailParams& p, double Omega3) {
  const Eigen::Matrix4d M = state_matrix(p, Omega3);
  const dynamics::EigenDecomposition es = dynamics::eigen_decomposition(M);
  int i = 0;
  for (int j = 1; j < 4; ++j) {
    if (es.values[j].real() > es.values[i].real()) i = j;
  }
  const Eigen::Matrix4cd left = Eigen::Matrix4cd(es.vectors).inverse();  // rows: left eigenvectors
  const Eigen::Matrix<cd, 1, 4> w = left.row(i);
  Measured m;
  m.lambda_book = es.values[i];
  Monorail model(p);
  model.inputs.Omega3 = Omega3;
  Rk4 integ(model);
  Monorail::State x = Monorail::make_state(1e-5, 1e-5, 0.0, 0.0);
  const double h = 1e-3;
  // Long enough to see the rate, short enough to keep the amplitude ≤ 1e-4 rad (growth ≤ e^2).
  const double T = std::min(60.0, 2.0 / std::abs(m.lambda_book.real()));
  const long n = std::lround(T / h);
  cd eta = w * x.cast<cd>();
  const double log0 = std::log(std::abs(eta));
  double arg = 0.0;
  for (long k = 0; k < n; ++k) {
    integ.step(static_cast<double>(k) * h, h, x);
    const cd next = w * x.cast<cd>();
    arg += std::arg(next / eta);  // |Im λ| h ≤ 0.01 rad per step: no wrap
    eta = next;
    m.max_angle = std::max({m.max_angle, std::abs(x[0]), std::abs(x[1])});
  }
  const double t = static_cast<double>(n) * h;
  m.rate = (std::log(std::abs(eta)) - log0) / t;
  m.frequency = std::abs(arg) / t;
  return m;
}

MonorailParams digest_car(double k) {
  MonorailParams p;  // A 3000, c 2e4, B 50, q 500, H 4000, d 200 by default
  p.k = k;
  return p;
}

TEST(MonorailOracle, GainWindowAndRootsMatchTheDigest) {
  const MonorailParams p = digest_car(0.0);
  double wP = 0, wN = 0;
  undamped_frequencies(p, wP, wN);
  const double k_lo = p.d * (p.c + p.A * wP * wP) / p.H, k_hi = p.d * (p.c + p.A * wN * wN) / p.H;
  // Reference car (docs/models/monorail.md, 3-4 digits): ω_P = 0.864, ω_N = 9.447, window 1112 < k < 14388.
  EXPECT_NEAR(wP, 0.864, 5e-4);
  EXPECT_NEAR(wN, 9.447, 5e-4);
  EXPECT_NEAR(k_lo, 1112.0, 0.5);
  EXPECT_NEAR(k_hi, 14388.0, 0.5);
  // (14.4): H > sqrt(qA) + sqrt(cB) (undamped car stabilizable), and the window is where (14.5) holds.
  EXPECT_GT(p.H, std::sqrt(p.q * p.A) + std::sqrt(p.c * p.B));
  // The reference roots (max Re λ) at 0.9, 1.01 × k_lo, mid-window, 0.99, 1.1 × k_hi; the reference gives
  // the gains rounded (1001, 1123, 7750, 14244, 15827) and the roots to 2-3 digits: within half a unit of
  // the last.
  struct Case {
    double k, max_re, half_unit;
  };
  for (const Case cs :
       {Case{0.9 * k_lo, 0.0167, 5e-5}, Case{1.01 * k_lo, -0.0017, 5e-5}, Case{7750, -0.486, 5e-4},
        Case{0.99 * k_hi, -0.018, 5e-4}, Case{1.1 * k_hi, 0.178, 5e-4}}) {
    const Eigen::Vector4cd r = characteristic_roots(digest_car(cs.k), 0.0);
    EXPECT_NEAR(r.real().maxCoeff(), cs.max_re, cs.half_unit) << "k " << cs.k;
    // Same roots from the state matrix of (14.2): the two forms of the linear theory agree.
    const Eigen::Vector4cd e =
        dynamics::eigenvalues<4>(state_matrix(digest_car(cs.k), 0.0));
    EXPECT_NEAR(e.real().maxCoeff(), r.real().maxCoeff(), 1e-10);
  }
  // At the window edges the roots cross the imaginary axis at ±iω_P, ±iω_N (the window's derivation).
  for (const double kb : {k_lo, k_hi}) {
    const Eigen::Vector4cd r = characteristic_roots(digest_car(kb), 0.0);
    EXPECT_NEAR(r.real().maxCoeff(), 0.0, 1e-9) << "k " << kb;
  }
}

// Gains 1 % and 10 % inside and outside each edge of the window: the simulated car decays inside and grows
// outside, at the rate and frequency of (14.3)'s dominant root.
TEST(MonorailOracle, GainsInsideTheWindowDecayOutsideGrowAtTheRootsRates) {
  const MonorailParams p0 = digest_car(0.0);
  double wP = 0, wN = 0;
  undamped_frequencies(p0, wP, wN);
  const double k_lo = p0.d * (p0.c + p0.A * wP * wP) / p0.H, k_hi = p0.d * (p0.c + p0.A * wN * wN) / p0.H;
  struct Case {
    double k;
    bool stable;
    double edge_frequency;  // the mode that crosses at this edge
  };
  for (const Case cs :
       {Case{0.90 * k_lo, false, wP}, Case{0.99 * k_lo, false, wP}, Case{1.01 * k_lo, true, wP},
        Case{1.10 * k_lo, true, wP}, Case{0.90 * k_hi, true, wN}, Case{0.99 * k_hi, true, wN},
        Case{1.01 * k_hi, false, wN}, Case{1.10 * k_hi, false, wN}}) {
    const MonorailParams p = digest_car(cs.k);
    const Measured m = measure_dominant_mode(p, 0.0);
    std::printf("k %8.1f  Re λ book %+.6e  measured − book %+.1e  Im λ book %.6f measured − book %+.1e\n",
                cs.k, m.lambda_book.real(), m.rate - m.lambda_book.real(), std::abs(m.lambda_book.imag()),
                m.frequency - std::abs(m.lambda_book.imag()));
    // The dominant root of the quartic is the state matrix's (checked above), and its sign is the window's.
    const Eigen::Vector4cd r = characteristic_roots(p, 0.0);
    EXPECT_NEAR(r.real().maxCoeff(), m.lambda_book.real(), 1e-10);
    EXPECT_EQ(m.lambda_book.real() < 0.0, cs.stable) << "k " << cs.k;
    // The measured sign, rate and frequency (tolerance 1e-6 s⁻¹, rad/s: see the file header).
    EXPECT_EQ(m.rate < 0.0, cs.stable) << "k " << cs.k;
    EXPECT_NEAR(m.rate, m.lambda_book.real(), 1e-6) << "k " << cs.k;
    EXPECT_NEAR(m.frequency, std::abs(m.lambda_book.imag()), 1e-6) << "k " << cs.k;
    // Near an edge the critical mode is the one of that edge's frequency (5 %: 1 % from the edge).
    if (std::abs(cs.k / (cs.edge_frequency == wP ? k_lo : k_hi) - 1.0) < 0.02) {
      EXPECT_NEAR(m.frequency / cs.edge_frequency, 1.0, 0.05) << "k " << cs.k;
    }
    EXPECT_LT(m.max_angle, 1e-3);  // small-amplitude premise of the tolerance
  }
}

// (14.6)-(14.7): in a curve with c > HΩ3 > q the car overturns even with a gain mid-window; the growth is
// aperiodic at (14.6)'s positive real root. With HΩ3 < q the same car stays stable.
TEST(MonorailOracle, CurveRunningWithCAboveHOmega3AboveQOverturns14_7) {
  const MonorailParams p = digest_car(7750.0);  // mid-window, Re λ = −0.486 on the straight
  // Ω3 = 1 rad/s: HΩ3 = 4000, between q = 500 and c = 2e4.
  const double Omega3 = 1.0;
  ASSERT_GT(p.c, p.H * Omega3);
  ASSERT_GT(p.H * Omega3, p.q);
  const Measured m = measure_dominant_mode(p, Omega3);
  std::printf("curve: Re λ book %+.6e measured − book %+.1e\n", m.lambda_book.real(),
              m.rate - m.lambda_book.real());
  EXPECT_GT(m.lambda_book.real(), 0.0);
  EXPECT_EQ(m.lambda_book.imag(), 0.0);  // (c − HΩ3)(q − HΩ3) < 0: the constant term is negative, a real root
  EXPECT_NEAR(m.rate, m.lambda_book.real(), 1e-6);
  EXPECT_LT(m.frequency, 1e-6);  // aperiodic
  // A gentle curve, HΩ3 = 200 < q: stable, at (14.6)'s rate.
  const Measured g = measure_dominant_mode(p, 0.05);
  EXPECT_LT(g.lambda_book.real(), 0.0);
  EXPECT_NEAR(g.rate, g.lambda_book.real(), 1e-6);

  // Large angles: from φ0 = 1e-3 rad the car in the curve passes 60° within a few e-folding times, while the
  // same car on the straight returns towards upright.
  for (const double W : {Omega3, 0.0}) {
    Monorail model(p);
    model.inputs.Omega3 = W;
    Rk4 integ(model);
    Monorail::State x = Monorail::make_state(1e-3, 0.0, 0.0, 0.0);
    const double h = 1e-3, t_end = 3.0 * std::log(1e3) / m.lambda_book.real();
    double t_over = -1.0;
    const long n = std::lround(t_end / h);
    for (long k = 0; k < n; ++k) {
      integ.step(static_cast<double>(k) * h, h, x);
      if (std::abs(x[0]) > kPi / 3.0) {
        t_over = static_cast<double>(k + 1) * h;
        break;
      }
    }
    if (W != 0.0) {
      // Overturned, and not before the linear growth from 1e-3 to ~1 rad could take (ln(1e3)/λ, halved to
      // allow for the initial mode mix and the nonlinear acceleration).
      EXPECT_GT(t_over, 0.5 * std::log(1e3) / m.lambda_book.real()) << "t_end " << t_end;
    } else {
      EXPECT_LT(t_over, 0.0);
      EXPECT_LT(std::abs(x[0]), 1e-3);
    }
  }
}

// Without damper, motor and inputs, at constant Ω3, the large-angle model conserves its energy in the path
// frame: a wrong sign or a missing cos in a large-angle term shows as drift.
TEST(MonorailModel, EnergyIsConservedWithTheLargeAngleTerms) {
  MonorailParams p = digest_car(0.0);
  p.d = 0.0;
  p.Q = 0.3 * p.B;
  Monorail model(p);
  model.inputs.Omega3 = 0.05;  // HΩ3 = 200 < q: the undamped car is gyroscopically stable (14.4) ...
  Rk4 integ(model);
  Monorail::State x =
      Monorail::make_state(0.0, 0.7, 0.0, 0.0);  // ... and stays upright from this tilt of the case
  const double E0 = model.energy(x);
  double drift = 0, beta_max = 0, phi_max = 0;
  const double h = 1e-3;
  for (long k = 0; k < 20000; ++k) {
    integ.step(static_cast<double>(k) * h, h, x);
    drift = std::max(drift, std::abs(model.energy(x) - E0));
    beta_max = std::max(beta_max, std::abs(x[1]));
    phi_max = std::max(phi_max, std::abs(x[0]));
  }
  std::printf("monorail energy drift %.3e of |E0| = %.3e, beta_max %.3f phi_max %.3f\n", drift / std::abs(E0),
              std::abs(E0), beta_max, phi_max);
  EXPECT_GT(beta_max, 0.9);  // large angles are exercised (cosβ < 0.62) ...
  EXPECT_LT(phi_max, 0.3);   // ... in a bounded motion (the car does not fall over)
  // RK4 at h ω_N ≈ 0.01: energy error ~(hω)⁶/144 per step ≈ 1e-14; 1e-9 |E0| is 1e7 below the drift of a 1 %
  // error in any term over this run.
  EXPECT_LT(drift, 1e-9 * std::abs(E0));
}

// derivative() and the RK4 step allocate nothing.
TEST(MonorailModel, StepsWithoutHeapAllocation) {
  Monorail model(digest_car(7750.0));
  Rk4 integ(model);
  Monorail::State x = Monorail::make_state(0.01, 0.0, 0.0, 0.0);
  const testing::AllocationCounter allocations;
  for (int i = 0; i < 10000; ++i) {
    model.inputs.Omega3 = 0.01;
    model.inputs.M2 = 1.0;
    integ.step(i * 1e-3, 1e-3, x);
  }
  EXPECT_EQ(allocations.count(), 0u);  // exact: any allocation is a defect
}

}  // namespace monorail_test
}  // namespace gyrostab
