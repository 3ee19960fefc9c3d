// Oracle tests of the sampled-data loop roots (sim/analysis/sampled_loop_roots.hpp) against closed forms:
//   (a) a first-order plant ẋ = λ x + u under u = −K y: with no latency z = a − K b, with one tick of latency
//       z² − a z + b K = 0, with half a tick z² − (a − K b0) z + K b1 = 0 (a = e^{λT}, b = (e^{λT} − 1)/λ,
//       b0, b1 the two parts of the held interval);
//   (b) a law with a state (a discrete integrator) on an integrating plant: (z − 1 + K T)(z − 1) + Ki T² = 0;
//   (c) T → 0 recovers the continuous roots of s² + d s + k (a PD law on ẍ = u, one tick of latency) with an
//       error O(T): the error shrinks by 10 per decade of T, and its first-order term is the effective delay
//       1.5 T (hold ½ T + latency T);
//   (d) the verdict: the integrating plant with K T = 1.2 and one tick of latency is stable in continuous time
//       (s = −K) but |z| = sqrt(K T) = 1.0954 sampled, and the message says so.
// Tolerances: the discretisation is one matrix exponential (scaling and squaring with a Padé approximant,
// accurate to a few ulp of ‖AT‖) and one eigensolve of a well-conditioned small matrix: 1e-12 on z.
#include "sim/analysis/sampled_loop_roots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

namespace sampled_loop_roots_test {

using gyrostab::analysis::DiscreteLaw;
using gyrostab::analysis::LinearPlant;
using gyrostab::analysis::SampledTiming;
using gyrostab::analysis::sampled_loop_roots;
using C = std::complex<double>;

LinearPlant first_order(double lambda) {
  LinearPlant p;
  p.A = Eigen::MatrixXd::Constant(1, 1, lambda);
  p.B = Eigen::MatrixXd::Constant(1, 1, 1.0);
  p.C = Eigen::MatrixXd::Constant(1, 1, 1.0);
  return p;
}

DiscreteLaw proportional(double K) { return DiscreteLaw::gain(Eigen::MatrixXd::Constant(1, 1, -K)); }

// The non-zero z of the loop, sorted by (Re, Im).
std::vector<C> sorted_nonzero(const std::vector<C>& z) {
  std::vector<C> out;
  for (const C& x : z)
    if (std::abs(x) > 1e-9) out.push_back(x);
  std::sort(out.begin(), out.end(), [](C a, C b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  return out;
}

std::vector<C> quadratic_roots(double b, double c) {  // z² + b z + c = 0
  const C disc = std::sqrt(C(b * b - 4.0 * c, 0.0));
  return sorted_nonzero({(-b - disc) / 2.0, (-b + disc) / 2.0});
}

void expect_same(const std::vector<C>& got, const std::vector<C>& want, double tol) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT(std::abs(got[i] - want[i]), tol) << i << ": " << got[i] << " vs " << want[i];
}

TEST(SampledLoopRoots, FirstOrderProportionalClosedForms) {
  const double lambda = -3.0, K = 40.0, T = 0.01;
  const double a = std::exp(lambda * T), b = (a - 1.0) / lambda;
  const LinearPlant p = first_order(lambda);
  // No latency: z = a − K b.
  expect_same(sorted_nonzero(sampled_loop_roots(p, proportional(K), {T, 0.0}).z), {C(a - K * b, 0.0)}, 1e-12);
  // One tick: z² − a z + b K = 0 (complex here: a² < 4 b K).
  const auto one = sampled_loop_roots(p, proportional(K), {T, T});
  expect_same(sorted_nonzero(one.z), quadratic_roots(-a, b * K), 1e-12);
  EXPECT_NEAR(one.max_abs_z, std::sqrt(b * K), 1e-12);
  // Half a tick: u[k−1] over the first half, u[k] over the second.
  const double h = std::exp(lambda * T / 2.0), b0 = (h - 1.0) / lambda, b1 = h * b0;
  expect_same(sorted_nonzero(sampled_loop_roots(p, proportional(K), {T, T / 2.0}).z),
              quadratic_roots(-(a - K * b0), K * b1), 1e-12);
  // Two ticks: z³ − a z² + b K = 0; check that each root satisfies it.
  const auto two = sampled_loop_roots(p, proportional(K), {T, 2.0 * T});
  const std::vector<C> z2 = sorted_nonzero(two.z);
  ASSERT_EQ(z2.size(), 3u);
  for (const C& z : z2) EXPECT_LT(std::abs(z * z * z - a * z * z + b * K), 1e-12);
}

TEST(SampledLoopRoots, LawWithStateClosedForm) {
  // ẋ = u (λ = 0: a = 1, b = T); x_c[k+1] = x_c[k] + T y[k], u = −Ki x_c − K y; no latency:
  // (z − 1 + K T)(z − 1) + Ki T² = 0.
  const double T = 0.002, K = 30.0, Ki = 200.0;
  DiscreteLaw law;
  law.F = Eigen::MatrixXd::Constant(1, 1, 1.0);
  law.G = Eigen::MatrixXd::Constant(1, 1, T);
  law.H = Eigen::MatrixXd::Constant(1, 1, -Ki);
  law.D = Eigen::MatrixXd::Constant(1, 1, -K);
  const auto r = sampled_loop_roots(first_order(0.0), law, {T, 0.0});
  // z² − (2 − K T) z + (1 − K T + Ki T²) = 0
  expect_same(sorted_nonzero(r.z), quadratic_roots(-(2.0 - K * T), 1.0 - K * T + Ki * T * T), 1e-12);
}

TEST(SampledLoopRoots, SmallTickRecoversContinuousRootsWithOrderTError) {
  // ẍ = u, y = [x, x'], u = −k x − d x' with one tick of latency; continuous roots of s² + d s + k.
  const double k = 400.0, d = 4.0;
  LinearPlant p;
  p.A = (Eigen::MatrixXd(2, 2) << 0, 1, 0, 0).finished();
  p.B = (Eigen::MatrixXd(2, 1) << 0, 1).finished();
  p.C = Eigen::MatrixXd::Identity(2, 2);
  const DiscreteLaw law = DiscreteLaw::gain((Eigen::MatrixXd(1, 2) << -k, -d).finished());
  const C sc = (-d + std::sqrt(C(d * d - 4.0 * k, 0.0))) / 2.0;  // upper root
  // First order in the effective delay τe = 1.5 T: s² + (d s + k)(1 − τe s) = 0 ⇒ δs = τe s (k + d s)/(2 s + d).
  const auto first_order_shift = [&](double T) { return 1.5 * T * sc * (k + d * sc) / (2.0 * sc + d); };
  double previous = 0.0;
  for (double T : {1e-3, 1e-4, 1e-5}) {
    const auto r = sampled_loop_roots(p, law, {T, T});
    const C s = gyrostab::analysis::nearest_root(r.s, sc);
    const double err = std::abs(s - sc);
    // O(T): within 3 % of the first-order term (the rest is O(T²), relative O(|s| T) = 0.02 at T = 1 ms).
    EXPECT_LT(std::abs((s - sc) - first_order_shift(T)), 0.03 * std::abs(first_order_shift(T)) + 1e-9) << T;
    if (previous > 0.0) {
      EXPECT_GT(previous / err, 9.0) << T;
      EXPECT_LT(previous / err, 11.0) << T;
    }
    previous = err;
  }
}

TEST(SampledLoopRoots, VerdictSaysWhenContinuousDiffers) {
  const double T = 0.005, K = 1.2 / T;  // ẋ = u, u = −K x: continuous s = −K, stable
  const auto r = sampled_loop_roots(first_order(0.0), proportional(K), {T, T});
  EXPECT_FALSE(r.stable());
  EXPECT_NEAR(r.max_abs_z, std::sqrt(1.2), 1e-12);
  const std::string why = gyrostab::analysis::sampled_instability(r, {T, T}, true);
  EXPECT_NE(why.find("stable in continuous time but unstable"), std::string::npos) << why;
  EXPECT_NE(why.find("|z| = 1.09545"), std::string::npos) << why;
  // Below K T = 1 the same loop is stable sampled too, with no message.
  const auto ok = sampled_loop_roots(first_order(0.0), proportional(0.9 / T), {T, T});
  EXPECT_TRUE(ok.stable());
  EXPECT_EQ(gyrostab::analysis::sampled_instability(ok, {T, T}, true), "");
}

}  // namespace sampled_loop_roots_test
