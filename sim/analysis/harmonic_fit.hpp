// Mean and one harmonic of a sampled signal by least squares, streaming and allocation-free:
//
//   y_k ≈ c + d τ_k + a cos θ_k + b sin θ_k
//
// over the samples fed so far, θ the harmonic's phase (e.g. 2γ for a U-gyro's twice-spin output, β for a servo
// gyro's drive angle) and τ the time (the trend d only when asked for). A Fourier sum 2/n Σ y cos θ gives a only
// when the samples cover whole periods uniformly in θ; over a window that ends on a tick it lets the mean leak
// into a and b by (mean) × (the fraction of a period left over)/(periods), which is the whole error when the mean
// is 10³ times the harmonic. The fit has no such leak: a mean, a linear trend and the harmonic are separated
// exactly on any window and any sampling in θ, so the estimate is limited by what is not in the model (other
// harmonics, noise, decaying transients).
//
// The normal equations (4 × 4, or 3 × 3 without the trend) are accumulated as sums of the basis products; the
// samples are taken relative to the first one (y − y₀, τ − τ₀) so that a large mean costs no digits in the sums,
// and the solve scales the matrix to unit diagonal (Jacobi) before an LDLᵀ. Results: mean over the window
// (c + d τ̄), amplitude sqrt(a² + b²), phase φ in y = A cos(θ − φ), the trend d.
// Test: tests/unit/harmonic_fit_test.cpp (a constant or a slow trend 10³ times the harmonic, windows of
// non-whole periods, against the Fourier sums that leak).
#pragma once

#include <cmath>
#include <cstdint>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace gyrostab::analysis {

class HarmonicFit {
 public:
  explicit HarmonicFit(bool trend = false) : trend_(trend) {}

  // One sample: the phase θ [rad] of the harmonic, the value y and its time τ [s] (used with the trend only).
  void add(double theta, double y, double tau = 0.0) {
    if (n_ == 0) {
      y0_ = y;
      tau0_ = tau;
    }
    const double v[4] = {1.0, std::cos(theta), std::sin(theta), tau - tau0_};
    const double dy = y - y0_;
    for (int i = 0; i < 4; ++i) {
      for (int j = i; j < 4; ++j) m_[i][j] += v[i] * v[j];
      r_[i] += v[i] * dy;
    }
    ++n_;
  }

  std::int64_t samples() const { return n_; }
  bool trend() const { return trend_; }

  struct Result {
    bool valid{false};
    double mean{0.0};       // c + d τ̄: the fitted mean over the window
    double cos_coef{0.0};   // a
    double sin_coef{0.0};   // b
    double slope{0.0};      // d [1/s] (0 without the trend)
    double amplitude() const { return std::hypot(cos_coef, sin_coef); }
    double phase() const { return std::atan2(sin_coef, cos_coef); }  // y = A cos(θ − φ)
  };

  Result solve() const {
    Result out;
    const int k = trend_ ? 4 : 3;
    if (n_ < k + 1) return out;
    Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
    Eigen::Vector4d r = Eigen::Vector4d::Zero();
    for (int i = 0; i < k; ++i) {
      r[i] = r_[i];
      for (int j = i; j < k; ++j) M(i, j) = M(j, i) = m_[i][j];
    }
    Eigen::Vector4d s = Eigen::Vector4d::Ones();
    for (int i = 0; i < k; ++i) {
      if (!(M(i, i) > 0.0)) return out;
      s[i] = 1.0 / std::sqrt(M(i, i));
    }
    const Eigen::Matrix4d Ms = s.asDiagonal() * M * s.asDiagonal();
    const Eigen::LDLT<Eigen::Matrix4d> ldlt(Ms);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-12)) return out;
    const Eigen::Vector4d x = s.asDiagonal() * ldlt.solve(s.asDiagonal() * r).eval();
    const double n = static_cast<double>(n_);
    const double tau_mean = m_[0][3] / n;
    out.valid = x.allFinite();
    out.cos_coef = x[1];
    out.sin_coef = x[2];
    out.slope = trend_ ? x[3] : 0.0;
    out.mean = y0_ + x[0] + out.slope * tau_mean;
    return out;
  }

 private:
  bool trend_{false};
  std::int64_t n_{0};
  double y0_{0.0}, tau0_{0.0};
  double m_[4][4]{};  // upper triangle of Σ v vᵀ, v = (1, cos θ, sin θ, τ − τ₀)
  double r_[4]{};     // Σ v (y − y₀)
};

}  // namespace gyrostab::analysis
