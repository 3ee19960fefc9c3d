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
//   (e) the identification of the roots from a run (sim/analysis/linear_prediction_fit.hpp): the PD loop of (c)
//       at T = 1 ms with one tick of latency, released from an offset with white noise on both sensors: the fit
//       of y with the noise samples as inputs recovers the loop's root to 1e-9 (the recurrence is exact; what
//       is left is the QR's round-off on a 1500-row fit); the fit of y alone misses it by more than 1e-3 (the
//       noise, reaching y through the hold and the latency, is a coloured equation error).
// Tolerances: the discretisation is one matrix exponential (scaling and squaring with a Padé approximant,
// accurate to a few ulp of ‖AT‖) and one eigensolve of a well-conditioned small matrix: 1e-12 on z.
#include "sim/analysis/sampled_loop_roots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <complex>
#include <random>
#include <vector>

#include "sim/analysis/linear_prediction_fit.hpp"

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

TEST(LinearPredictionFit, RecoversTheSampledRootsFromANoisyRun) {
  // ẍ = u, u = −k y1 − d y2 with y = (x, ẋ) + noise; s² + d s + k: k = 400, d = 4 (ω ≈ 20 rad/s, ζ = 0.1).
  const double T = 1e-3, k = 400.0, d = 4.0;
  LinearPlant p;
  p.A = Eigen::MatrixXd::Zero(2, 2);
  p.A(0, 1) = 1.0;
  p.B = Eigen::MatrixXd::Zero(2, 1);
  p.B(1, 0) = 1.0;
  p.C = Eigen::MatrixXd::Identity(2, 2);
  Eigen::MatrixXd D(1, 2);
  D << -k, -d;
  const auto roots = sampled_loop_roots(p, DiscreteLaw::gain(D), {T, T});
  const C continuous(-0.5 * d, std::sqrt(k - 0.25 * d * d));
  const C want = gyrostab::analysis::nearest_root(roots.s, continuous);
  // The loop as the runner closes it: the command computed at sample k acts over [(k+1)T, (k+2)T).
  const auto step = gyrostab::analysis::zoh_step(p.A, p.B, T);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int n = 1500;
  std::vector<double> y(n), v(2 * n);
  Eigen::Vector2d x(0.01, 0.0);
  double u_prev = 0.0;
  for (int i = 0; i < n; ++i) {
    const double n1 = 2e-5 * noise(rng), n2 = 2e-3 * noise(rng);
    v[2 * static_cast<std::size_t>(i)] = n1;
    v[2 * static_cast<std::size_t>(i) + 1] = n2;
    y[static_cast<std::size_t>(i)] = x(0);
    const double u = D(0, 0) * (x(0) + n1) + D(0, 1) * (x(1) + n2);
    x = step.Phi * x + step.Gamma * u_prev;
    u_prev = u;
  }
  const C with_inputs = gyrostab::analysis::nearest_root(
      gyrostab::analysis::linear_prediction_roots(y.data(), v.data(), 2, y.size(), 6, T), continuous);
  const C alone = gyrostab::analysis::nearest_root(
      gyrostab::analysis::linear_prediction_roots(y.data(), nullptr, 0, y.size(), 6, T), continuous);
  std::printf("  with the noise as inputs %.3e, alone %.3e (relative to the root)\n", std::abs(with_inputs - want) / std::abs(want),
              std::abs(alone - want) / std::abs(want));
  EXPECT_LT(std::abs(with_inputs - want) / std::abs(want), 1e-9) << with_inputs << " vs " << want;
  EXPECT_GT(std::abs(alone.real() / want.real() - 1.0), 1e-3) << alone << " vs " << want;
  // Too few samples for the regressors: no roots rather than a guess.
  EXPECT_TRUE(gyrostab::analysis::linear_prediction_roots(y.data(), v.data(), 2, 30, 6, T).empty());
}

}  // namespace sampled_loop_roots_test
