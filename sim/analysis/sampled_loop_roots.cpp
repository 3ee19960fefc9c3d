// sampled_loop_roots.hpp: the zero-order-hold discretisation (one augmented matrix exponential per interval)
// and the discrete closed loop with its delay line. Compiled once: Eigen's matrix exponential and eigensolver
// are slow to compile.
#include "sim/analysis/sampled_loop_roots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::analysis {

DiscreteLaw DiscreteLaw::gain(const Eigen::MatrixXd& D) {
  DiscreteLaw l;
  l.F = Eigen::MatrixXd::Zero(0, 0);
  l.G = Eigen::MatrixXd::Zero(0, D.cols());
  l.H = Eigen::MatrixXd::Zero(D.rows(), 0);
  l.D = D;
  return l;
}

ZohStep zoh_step(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double t) {
  const Eigen::Index n = A.rows(), p = B.cols();
  Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(n + p, n + p);
  aug.topLeftCorner(n, n) = A * t;
  aug.topRightCorner(n, p) = B * t;
  const Eigen::MatrixXd e = aug.exp();
  return {e.topLeftCorner(n, n), e.topRightCorner(n, p)};
}

Eigen::MatrixXd sampled_closed_loop(const LinearPlant& pl, const DiscreteLaw& law, const SampledTiming& t) {
  const double T = t.period_s;
  // τ = m T + τf; a latency that is a whole number of periods up to rounding is taken as one.
  const double q = t.latency_s / T;
  int m = static_cast<int>(std::floor(q + 1e-9));
  double tf = t.latency_s - m * T;
  if (tf < 1e-9 * T) tf = 0.0;
  m = std::max(m, 0);
  const Eigen::Index n = pl.A.rows(), p = pl.B.cols(), r = law.F.rows();
  const int slots = m + (tf > 0.0 ? 1 : 0);  // d_j = u[k − j], j = 1 … slots
  const Eigen::Index N = n + r + slots * p;
  const Eigen::Index xc0 = n, d0 = n + r;
  const ZohStep s0 = zoh_step(pl.A, pl.B, T - tf);
  Eigen::MatrixXd G0 = s0.Gamma, G1 = Eigen::MatrixXd::Zero(n, p);
  if (tf > 0.0) G1 = s0.Phi * zoh_step(pl.A, pl.B, tf).Gamma;
  const Eigen::MatrixXd Phi = (pl.A * T).exp();

  // u[k − j] as a row block over w: j = 0 is the law's output now, j ≥ 1 a delay slot.
  const auto command = [&](int j) {
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(p, N);
    if (j == 0) {
      U.leftCols(n) = law.D * pl.C;
      if (r > 0) U.middleCols(xc0, r) = law.H;
    } else {
      U.middleCols(d0 + (j - 1) * p, p) = Eigen::MatrixXd::Identity(p, p);
    }
    return U;
  };
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(N, N);
  M.topLeftCorner(n, n) = Phi;
  M.topRows(n) += G0 * command(m);
  if (tf > 0.0) M.topRows(n) += G1 * command(m + 1);
  if (r > 0) {
    M.block(xc0, 0, r, n) = law.G * pl.C;
    M.block(xc0, xc0, r, r) = law.F;
  }
  for (int j = 1; j <= slots; ++j) {
    if (j == 1) M.middleRows(d0, p) = command(0);
    else M.block(d0 + (j - 1) * p, d0 + (j - 2) * p, p, p) = Eigen::MatrixXd::Identity(p, p);
  }
  return M;
}

SampledLoopRoots sampled_loop_roots(const LinearPlant& p, const DiscreteLaw& law, const SampledTiming& t) {
  SampledLoopRoots out;
  out.M = sampled_closed_loop(p, law, t);
  const Eigen::VectorXcd ev = dynamics::eigenvalues(out.M);
  for (Eigen::Index i = 0; i < ev.size(); ++i) {
    const std::complex<double> z = ev(i);
    out.z.push_back(z);
    out.max_abs_z = std::max(out.max_abs_z, std::abs(z));
    // A delay line's roots sit at z = 0; rounding moves a repeated one to ~ε^(1/k). Below 1e-6 (a decay
    // faster than 13.8/T) a root is taken as one of them.
    if (std::abs(z) > 1e-6) out.s.push_back(std::log(z) / t.period_s);
  }
  return out;
}

Eigen::VectorXd sampled_steady_state(const LinearPlant& p, const DiscreteLaw& law, const SampledTiming& t,
                                     const Eigen::MatrixXd& E, const Eigen::VectorXd& v) {
  const Eigen::MatrixXd M = sampled_closed_loop(p, law, t);
  const Eigen::Index n = p.A.rows(), N = M.rows();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(N);
  f.head(n) = zoh_step(p.A, E, t.period_s).Gamma * v;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(Eigen::MatrixXd::Identity(N, N) - M);
  if (!lu.isInvertible()) return Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  return lu.solve(f).head(n);
}

std::complex<double> nearest_root(const std::vector<std::complex<double>>& s, std::complex<double> continuous) {
  std::complex<double> best{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  double dist = std::numeric_limits<double>::infinity();
  for (const std::complex<double>& x : s) {
    const std::complex<double> y = (continuous.imag() >= 0.0) == (x.imag() >= 0.0) ? x : std::conj(x);
    if (std::abs(y - continuous) < dist) {
      dist = std::abs(y - continuous);
      best = y;
    }
  }
  return best;
}

StateFeedbackLoop restrict_state_feedback(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& K,
                                          const std::vector<int>& keep) {
  const auto n = static_cast<Eigen::Index>(keep.size());
  StateFeedbackLoop out;
  out.plant.A = Eigen::MatrixXd::Zero(n, n);
  out.plant.B = Eigen::MatrixXd::Zero(n, B.cols());
  out.plant.C = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd Kr = Eigen::MatrixXd::Zero(K.rows(), n);
  for (Eigen::Index r = 0; r < n; ++r) {
    const int i = keep[static_cast<std::size_t>(r)];
    for (Eigen::Index q = 0; q < n; ++q) out.plant.A(r, q) = A(i, keep[static_cast<std::size_t>(q)]);
    out.plant.B.row(r) = B.row(i);
    Kr.col(r) = K.col(i);
  }
  out.law = DiscreteLaw::gain(Kr);
  return out;
}

std::string sampled_instability(const SampledLoopRoots& r, const SampledTiming& t, bool continuous_stable) {
  if (r.stable()) return "";
  char buf[200];
  std::snprintf(buf, sizeof buf, "%sunstable at the law's period %.4g ms with latency %.4g ms (%.4g periods): |z| = %.6g",
                continuous_stable ? "stable in continuous time but " : "", t.period_s * 1e3, t.latency_s * 1e3,
                t.latency_s / t.period_s, r.max_abs_z);
  return buf;
}

std::array<std::complex<double>, 2> nearest_pair(std::vector<std::complex<double>> s, std::complex<double> centre) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::array<std::complex<double>, 2> out{std::complex<double>(nan, nan), std::complex<double>(nan, nan)};
  for (std::size_t i = 0; i < 2 && !s.empty(); ++i) {
    std::size_t best = 0;
    for (std::size_t j = 1; j < s.size(); ++j)
      if (std::abs(s[j] - centre) < std::abs(s[best] - centre)) best = j;
    out[i] = s[best];
    s.erase(s.begin() + static_cast<std::ptrdiff_t>(best));
  }
  return out;
}

PairShape pair_shape(std::complex<double> s1, std::complex<double> s2) {
  const double wn = std::sqrt((s1 * s2).real());
  return {wn, -(s1 + s2).real() / (2.0 * wn)};
}

}  // namespace gyrostab::analysis
