// Docs: docs/sampled-data.md.
#include "sim/analysis/planar_mode_fit.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace gyrostab::analysis {

PlanarModeFit::PlanarModeFit(double t_start, double t_end, double dt) : t0_(t_start), t1_(t_end), dt_(dt) {
  const double span = t_end - t_start;
  if (dt > 0.0 && span > 0.0) x_.reserve(static_cast<std::size_t>(std::fmin(span / dt, 1e7)) + 2);
}

std::complex<double> PlanarModeFit::root() const {
  const Pair p = pair();
  const std::complex<double> l0 = p.first, l1 = p.second;
  if (l0.imag() == 0.0 && l1.imag() == 0.0) return l0.real() > l1.real() ? l0 : l1;
  return l0.imag() >= 0.0 ? l0 : l1;
}

PlanarModeFit::Pair PlanarModeFit::pair() const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!valid()) return {{nan, nan}, {nan, nan}};
  // Centred and scaled: the equilibrium can be far from zero against the transient; Φ does not change.
  double ma = 0.0, mb = 0.0;
  for (const Sample& s : x_) ma += s.a, mb += s.b;
  ma /= static_cast<double>(x_.size());
  mb /= static_cast<double>(x_.size());
  double scale = 0.0;
  for (const Sample& s : x_) scale = std::fmax(scale, std::fmax(std::fabs(s.a - ma), std::fabs(s.b - mb)));
  if (!(scale > 0.0)) return {{nan, nan}, {nan, nan}};
  const auto rows = static_cast<Eigen::Index>(x_.size() - 1);
  Eigen::MatrixXd X(rows, 4), Y(rows, 2);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const Sample& p = x_[static_cast<std::size_t>(k)];
    const Sample& n = x_[static_cast<std::size_t>(k) + 1];
    X(k, 0) = (p.a - ma) / scale;
    X(k, 1) = (p.b - mb) / scale;
    X(k, 2) = 1.0;
    X(k, 3) = static_cast<double>(k) / static_cast<double>(rows);
    Y(k, 0) = (n.a - ma) / scale;
    Y(k, 1) = (n.b - mb) / scale;
  }
  const Eigen::MatrixXd P = X.colPivHouseholderQr().solve(Y);  // rows 0-1: Φᵀ
  const Eigen::Matrix2d Phi = P.topRows(2).transpose();
  const Eigen::Vector2cd mu = Eigen::EigenSolver<Eigen::Matrix2d>(Phi, false).eigenvalues();
  return {std::log(mu(0)) / dt_, std::log(mu(1)) / dt_};
}

}  // namespace gyrostab::analysis
