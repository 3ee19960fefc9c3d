// Docs: docs/sampled-data.md.
#include "sim/analysis/linear_prediction_fit.hpp"

#include <cmath>

#include <Eigen/Core>
#include <Eigen/QR>

#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::analysis {

namespace {
double max_abs_about(const double* x, std::size_t count, std::size_t stride, double centre) {
  double m = 0.0;
  for (std::size_t k = 0; k < count; ++k) m = std::fmax(m, std::fabs(x[k * stride] - centre));
  return m;
}
}  // namespace

std::vector<std::complex<double>> linear_prediction_roots(const double* y, const double* v, int channels,
                                                          std::size_t count, int order, double dt) {
  std::vector<std::complex<double>> s;
  if (order < 1 || channels < 0 || (channels > 0 && v == nullptr)) return s;
  const auto n = static_cast<std::size_t>(order), m = static_cast<std::size_t>(channels);
  const std::size_t unknowns = n + m * (n + 1) + 1;
  if (count < n + 3 * unknowns) return s;
  // Each column centred and scaled to one size (the equilibrium can be far from zero against the oscillation,
  // a noise far smaller than the signal): the recurrence's roots do not change, the pivoting sees the columns
  // fairly. An input channel that stayed zero (a sensor without noise) is left out.
  double mean = 0.0;
  for (std::size_t k = 0; k < count; ++k) mean += y[k];
  mean /= static_cast<double>(count);
  const double ys = max_abs_about(y, count, 1, mean);
  if (!(ys > 0.0)) return s;
  std::vector<double> vs(m, 0.0);
  int used = 0;
  for (std::size_t c = 0; c < m; ++c) {
    vs[c] = max_abs_about(v + c, count, m, 0.0);
    if (vs[c] > 0.0) ++used;
  }
  const auto rows = static_cast<Eigen::Index>(count - n);
  const auto cols = static_cast<Eigen::Index>(n + static_cast<std::size_t>(used) * (n + 1) + 1);
  Eigen::MatrixXd X(rows, cols);
  Eigen::VectorXd rhs(rows);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const std::size_t k = static_cast<std::size_t>(r) + n;
    Eigen::Index col = 0;
    for (std::size_t i = 1; i <= n; ++i) X(r, col++) = (y[k - i] - mean) / ys;
    for (std::size_t c = 0; c < m; ++c) {
      if (!(vs[c] > 0.0)) continue;
      for (std::size_t j = 0; j <= n; ++j) X(r, col++) = v[(k - j) * m + c] / vs[c];
    }
    X(r, col) = 1.0;
    rhs(r) = (y[k] - mean) / ys;
  }
  const Eigen::VectorXd a = X.colPivHouseholderQr().solve(rhs);
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(order, order);
  for (int i = 0; i < order; ++i) companion(0, i) = a(i);
  for (int i = 1; i < order; ++i) companion(i, i - 1) = 1.0;
  const Eigen::VectorXcd z = dynamics::eigenvalues(companion);
  for (Eigen::Index i = 0; i < z.size(); ++i)
    if (std::abs(z(i)) > 1e-9) s.push_back(std::log(z(i)) / dt);
  return s;
}

LinearPredictionMeter::LinearPredictionMeter(double t_start, double t_end, double dt, int order, int channels)
    : t0_(t_start), t1_(t_end), dt_(dt), order_(order), channels_(channels < 0 ? 0 : channels) {
  // At most 1e7 samples (80 MB): a window longer than that keeps its first 1e7 samples.
  const double span = t_end - t_start;
  if (dt > 0.0 && span > 0.0) {
    const std::size_t n = static_cast<std::size_t>(std::fmin(span / dt, 1e7)) + 2;
    y_.reserve(n);
    v_.reserve(n * static_cast<std::size_t>(channels_));
  }
}

std::size_t LinearPredictionMeter::min_samples() const {
  const auto n = static_cast<std::size_t>(order_), m = static_cast<std::size_t>(channels_);
  return n + 3 * (n + m * (n + 1) + 1);
}

bool LinearPredictionMeter::valid() const { return order_ >= 1 && y_.size() >= min_samples(); }

std::vector<std::complex<double>> LinearPredictionMeter::roots() const {
  return linear_prediction_roots(y_.data(), channels_ > 0 ? v_.data() : nullptr, channels_, y_.size(), order_, dt_);
}

}  // namespace gyrostab::analysis
