// Recorded motion of the base: what an IMU or a ship's motion recorder logs — time, attitude, absolute angular
// rate and specific force in base axes — interpolated into models::BaseSample between the samples.
//
// Interpolation (one interval [t_i, t_i+1], h = t_i+1 − t_i, s = (t − t_i)/h):
//   ω_B(t), f_B(t)   cubic Hermite  y = h00 y_i + h h10 y'_i + h01 y_i+1 + h h11 y'_i+1, with the node slopes y'
//                    from the three-point difference on the (possibly non-uniform) grid, one-sided at the ends
//   ω̇_B(t)           the derivative of the ω_B interpolant (continuous at the nodes)
//   up_B             f_B/g
//   q_WB(t)          cubic Hermite on the quaternion's components with the slopes q̇ = ½ q ⊗ (0, ω_B) the
//                    recorded rate gives exactly, renormalized (attitude consistent with the recorded rate)
// Error, y with bounded 3rd and 4th derivatives M3, M4 over the interval (docs/models/suspension-motion.md):
//   |Δy| ≤ h⁴ M4/384 + h³ M3/24 (interior intervals; h³ M3/12 in the first and last, one-sided slopes)
//   |Δẏ| ≤ √3 h³ M4/216 + h² M3/6 (h² M3/3 in the first and last)
// Units: t [s], ω [rad/s], f [m/s²], g [m/s²]; the file's own units are converted by the reader
// (tools/scene/motion_csv.hpp). Frames: q_WB maps base to world (world axis 3 up), as PrescribedBaseRotation.
// The record is read and checked once at start-up and shared read-only (std::shared_ptr); sampling is a
// binary search and a few multiply-adds, allocation-free and stateless, so the same record and times give the
// same bits. Test: tests/unit/recorded_motion_test.cpp (the bound against a harmonic generator, the replay of
// the shipped record).
// Docs: docs/models/suspension-motion.md#recorded-motion
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "sim/dynamics/quaternion.hpp"
#include "sim/models/base_motion.hpp"
#include "sim/motion/wave_transfer.hpp"

namespace gyrostab::motion {

struct MotionRecord {
  std::vector<double> t;                 // strictly increasing [s]
  std::vector<dynamics::Quat> q_WB;      // unit, sign-continuous (q·q_prev ≥ 0)
  std::vector<dynamics::Vec3> w_B;       // [rad/s]
  std::vector<dynamics::Vec3> f_B;       // [m/s²]
  std::vector<dynamics::Vec3> dw_B;      // node slopes of ω_B [rad/s²] (finish())
  std::vector<dynamics::Vec3> df_B;      // node slopes of f_B [m/s³] (finish())

  std::size_t size() const { return t.size(); }

  // After the samples are in (≥ 3, times increasing): the node slopes, and q made sign-continuous so that
  // the component-wise Hermite never interpolates across q ↔ −q.
  void finish() {
    const std::size_t n = t.size();
    for (std::size_t i = 1; i < n; ++i) {
      if (q_WB[i].coeffs().dot(q_WB[i - 1].coeffs()) < 0.0) q_WB[i].coeffs() = -q_WB[i].coeffs();
    }
    dw_B = slopes(w_B);
    df_B = slopes(f_B);
  }

  // Three-point difference of y at every node (the parabola through the node and its neighbours).
  std::vector<dynamics::Vec3> slopes(const std::vector<dynamics::Vec3>& y) const {
    const std::size_t n = t.size();
    std::vector<dynamics::Vec3> d(n, dynamics::Vec3::Zero());
    if (n < 3) return d;
    for (std::size_t i = 0; i < n; ++i) {
      // The stencil i-1, i, i+1 (shifted inward at the ends); x is where the derivative is taken.
      const std::size_t c = std::clamp<std::size_t>(i, 1, n - 2);
      const double x0 = t[c - 1], x1 = t[c], x2 = t[c + 1], x = t[i];
      // Derivatives of the Lagrange basis polynomials at x.
      const double l0 = ((x - x1) + (x - x2)) / ((x0 - x1) * (x0 - x2));
      const double l1 = ((x - x0) + (x - x2)) / ((x1 - x0) * (x1 - x2));
      const double l2 = ((x - x0) + (x - x1)) / ((x2 - x0) * (x2 - x1));
      d[i] = l0 * y[c - 1] + l1 * y[c] + l2 * y[c + 1];
    }
    return d;
  }
};

class RecordedMotion {
 public:
  RecordedMotion() = default;
  RecordedMotion(std::shared_ptr<const MotionRecord> record, double g) : r_(std::move(record)), g_(g) {}

  bool empty() const { return r_ == nullptr || r_->size() < 2; }
  const MotionRecord* record() const { return r_.get(); }
  double g() const { return g_; }

  models::BaseSample operator()(double t) const {
    const Interval k = locate(t);
    const MotionRecord& r = *r_;
    models::BaseSample b;
    b.w_B = k.h00 * r.w_B[k.i] + k.h10 * r.dw_B[k.i] + k.h01 * r.w_B[k.i + 1] + k.h11 * r.dw_B[k.i + 1];
    b.dw_B = k.d00 * r.w_B[k.i] + k.d10 * r.dw_B[k.i] + k.d01 * r.w_B[k.i + 1] + k.d11 * r.dw_B[k.i + 1];
    b.up_B = (k.h00 * r.f_B[k.i] + k.h10 * r.df_B[k.i] + k.h01 * r.f_B[k.i + 1] + k.h11 * r.df_B[k.i + 1]) / g_;
    return b;
  }

  dynamics::Vec3 specific_force_B(double t) const {  // [m/s²]
    const Interval k = locate(t);
    const MotionRecord& r = *r_;
    return k.h00 * r.f_B[k.i] + k.h10 * r.df_B[k.i] + k.h01 * r.f_B[k.i + 1] + k.h11 * r.df_B[k.i + 1];
  }

  dynamics::Quat attitude(double t) const {
    const Interval k = locate(t);
    const MotionRecord& r = *r_;
    const Eigen::Vector4d q = k.h00 * r.q_WB[k.i].coeffs() + k.h10 * quat_rate(r.q_WB[k.i], r.w_B[k.i]) +
                              k.h01 * r.q_WB[k.i + 1].coeffs() + k.h11 * quat_rate(r.q_WB[k.i + 1], r.w_B[k.i + 1]);
    dynamics::Quat out;
    out.coeffs() = q.normalized();
    return out;
  }

 private:
  // The interval holding t and the Hermite weights there; the slope weights carry the factor h. Outside the
  // record the end interval is extrapolated — the scene reader refuses a record that does not cover the run.
  struct Interval {
    std::size_t i;
    double h00, h10, h01, h11;  // value weights
    double d00, d10, d01, d11;  // derivative weights [1/s]
  };
  Interval locate(double t) const {
    const std::vector<double>& ts = r_->t;
    const auto it = std::upper_bound(ts.begin() + 1, ts.end() - 1, t);
    const std::size_t i = static_cast<std::size_t>(it - ts.begin()) - 1;
    const double h = ts[i + 1] - ts[i], s = (t - ts[i]) / h, s2 = s * s, s3 = s2 * s;
    Interval k{i,
               2 * s3 - 3 * s2 + 1,
               h * (s3 - 2 * s2 + s),
               -2 * s3 + 3 * s2,
               h * (s3 - s2),
               (6 * s2 - 6 * s) / h,
               3 * s2 - 4 * s + 1,
               (-6 * s2 + 6 * s) / h,
               3 * s2 - 2 * s};
    return k;
  }
  // q̇ = ½ q ⊗ (0, ω_B) for q = q_WB and ω in base axes, as Eigen's (x, y, z, w) coefficients.
  static Eigen::Vector4d quat_rate(const dynamics::Quat& q, const dynamics::Vec3& w) {
    dynamics::Quat wq;
    wq.w() = 0.0;
    wq.vec() = w;
    return 0.5 * (q * wq).coeffs();
  }

  std::shared_ptr<const MotionRecord> r_{};
  double g_{kStandardGravity};
};

}  // namespace gyrostab::motion
