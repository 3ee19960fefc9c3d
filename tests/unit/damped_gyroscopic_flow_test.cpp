// The closed-form damped gyroscopic flow against the exponential of the augmented 6×6 system matrix
// (Eigen's Padé scaling-and-squaring), over the regimes a gimbal gyro meets: spinning, damped, overdamped,
// zero spin, critically damped, reversed spin.
#include "sim/dynamics/damped_gyroscopic_flow.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <cstdint>

#include <unsupported/Eigen/MatrixFunctions>

namespace gyrostab {
namespace damped_gyroscopic_flow_test {

Eigen::Matrix<double, 4, 1> reference(const dynamics::GyroscopicPair& k, double tau, double r0, double r1,
                                      const Eigen::Matrix<double, 4, 1>& x) {
  Eigen::Matrix<double, 6, 6> Z = Eigen::Matrix<double, 6, 6>::Zero();
  Z(0, 2) = Z(1, 3) = 1.0;
  Z(2, 2) = -k.p; Z(2, 3) = -k.a; Z(3, 2) = k.b; Z(3, 3) = -k.q;
  Z(2, 4) = Z(3, 5) = 1.0;
  const Eigen::Matrix<double, 6, 6> E = (Z * tau).exp();
  Eigen::Matrix<double, 6, 1> y;
  y << x, r0, r1;
  return (E * y).head<4>();
}

struct Case {
  const char* name;
  dynamics::GyroscopicPair k;
  double tau;
};

TEST(DampedGyroscopicFlow, MatchesTheMatrixExponential) {
  const Case cases[] = {
      {"200 Hz nutation at 1 ms", {1256.6, 1256.6, 0.0, 0.0}, 1e-3},
      {"resonance bound h·ω = 5", {5000.0, 5000.0, 0.0, 0.0}, 1e-3},
      {"damped, unequal axes", {300.0, 500.0, 2.0, 7.0}, 1e-3},
      {"reversed spin", {-300.0, -500.0, 2.0, 7.0}, 1e-3},
      {"zero spin, friction", {0.0, 0.0, 3.0, 1.0}, 0.01},
      {"zero spin, equal friction", {0.0, 0.0, 2.0, 2.0}, 0.01},
      {"zero everything", {0.0, 0.0, 0.0, 0.0}, 0.01},
      {"critically damped", {1.0, 1.0, 4.0, 0.0}, 0.05},          // δ = (p-q)²/4 - ab = 0
      {"just overdamped", {1.0, 1.0, 4.0 + 1e-9, 0.0}, 0.05},
      {"just underdamped", {1.0, 1.0, 4.0 - 1e-9, 0.0}, 0.05},
      {"overdamped", {1.0, 2.0, 40.0, 0.5}, 0.05},
      {"slow spin, small step", {1e-3, 2e-3, 0.0, 0.0}, 1e-4},
  };
  const Eigen::Matrix<double, 4, 1> x(0.3, -0.2, 1.5, -0.7);
  for (const Case& c : cases) {
    Eigen::Matrix<double, 4, 1> out;
    dynamics::damped_gyroscopic_flow(c.k, c.tau, 0.8, -1.3, x.data(), out.data());
    const auto ref = reference(c.k, c.tau, 0.8, -1.3, x);
    // Both sides are double-precision evaluations of the same entire function; the Padé reference itself
    // carries ~1e-15·|Zτ| relative error. 1e-12 of the state's scale leaves room for both.
    EXPECT_LT((out - ref).norm(), 1e-12 * (1.0 + ref.norm())) << c.name << "\n" << out.transpose() << "\n"
                                                              << ref.transpose();
  }
}

// φ2 on the series branch (|w| < 0.5) against the series summed in long double to 40 terms, over random w
// and along the axes (where the imaginary part, divided by μ in the flow, is small): the relative error of
// the value and of its imaginary part stays at round-off (measured 3.2e-16 and 4.0e-16).
TEST(DampedGyroscopicFlow, Phi2SeriesIsAtRoundOff) {
  auto reference_phi2 = [](std::complex<long double> w) {
    std::complex<long double> sum = 0.0L, term = 0.5L;
    for (int k = 0; k < 40; ++k) {
      sum += term;
      term *= w / static_cast<long double>(k + 3);
    }
    return sum;
  };
  double worst = 0.0, worst_imag = 0.0;
  std::uint64_t seed = 12345;
  auto uniform = [&seed] {  // splitmix64 → [-0.5, 0.5)
    seed += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = seed;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53 - 0.5;
  };
  for (int i = 0; i < 200000; ++i) {
    const std::complex<double> w = i % 4 == 0 ? std::complex<double>(uniform(), 1e-7 * uniform())
                                              : std::complex<double>(uniform(), uniform());
    if (std::norm(w) >= 0.25 || w.imag() == 0.0) continue;
    const std::complex<long double> r = reference_phi2({w.real(), w.imag()});
    const std::complex<double> f = dynamics::detail::phi2(w);
    const std::complex<long double> fl(f.real(), f.imag());
    worst = std::max(worst, static_cast<double>(std::abs(fl - r) / std::abs(r)));
    worst_imag = std::max(worst_imag, static_cast<double>(std::abs((fl.imag() - r.imag()) / r.imag())));
  }
  EXPECT_LT(worst, 2e-15);
  EXPECT_LT(worst_imag, 2e-15);
}

}  // namespace damped_gyroscopic_flow_test
}  // namespace gyrostab
