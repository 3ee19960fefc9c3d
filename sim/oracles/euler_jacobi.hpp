// Exact body rates of a torque-free asymmetric rigid body (Euler-Poinsot), Jacobi elliptic form.
// Docs: docs/models/rigid-bodies.md#free-rigid-body
//
// Book: Magnus §2.3.1 (with the corrections listed in docs/models/rigid-bodies.md). With the principal
// moments ordered A > B > C and x = ω2, the first integrals 2T = Aω1² + Bω2² + Cω3²,
// H² = A²ω1² + B²ω2² + C²ω3² (2.1)-(2.2) reduce Euler's equations (1.84) to the quadrature
// (2.11)-(2.12), solved by
//
//   case a, H² < 2TB (motion about the min-moment axis C), (2.15):
//     ω1 = -√((H²-2TC)/(A(A-C))) cn τ,  ω2 = √((H²-2TC)/(B(B-C))) sn τ,  ω3 = √((2TA-H²)/(C(A-C))) dn τ
//     k² = (H²-2TC)(A-B) / ((2TA-H²)(B-C)),  τ = √((B-C)(2TA-H²)/(ABC)) (t - t0)
//       (the rate printed first in the book, x2·√((A-B)(B-C)/(AB)), is wrong: /(AC), checked numerically)
//     T_s = 4K(k) √(ABC / ((2TA-H²)(B-C)))                                                   (2.16)
//   case b, H² > 2TB (motion about the max-moment axis A), (2.17):
//     ω1 = √((H²-2TC)/(A(A-C))) dn τ,  ω2 = √((2TA-H²)/(B(A-B))) sn τ,  ω3 = -√((2TA-H²)/(C(A-C))) cn τ
//     k² = (2TA-H²)(B-C) / ((H²-2TC)(A-B)),  τ = √((A-B)(H²-2TC)/(ABC)) (t - t0)
//     T_s = 4K(k) √(ABC / ((H²-2TC)(A-B)))                                                   (2.18)
//   case c, H² = 2TB (separatrix, the Dzhanibekov flip), (2.19):
//     ω1 = √(2T(B-C)/(A(A-C))) sech τ,  ω2 = √(2T/B) tanh τ,  ω3 = -√(2T(A-B)/(C(A-C))) sech τ
//     τ = √(2T/B) √((A-B)(B-C)/(AC)) (t - t0)     (rate not printed in the book; it follows from (2.12))
//
// Every other solution is one of these with a phase τ0 and the sign pattern that Euler's equations allow
// (the product of the three signs is -1 in cases a and b); the constructor finds both from ω(t0).
// The caller's axes may be in any order: they are sorted to A > B > C by a permutation P, and for an odd
// permutation the rates are also negated (P(a × b) = det P (Pa × Pb), so ω̂ = det P · P ω solves Euler's
// equations in the sorted axes).
//
// Numerics: the three "gaps" 2TA - H², H² - 2TC and 2TB - H² are formed from sums of non-negative terms
// (e.g. 2TB - H² = C(B-C)ω3² - A(A-B)ω1²), so k² near 1 (near-separatrix starts, 1 - k² ~ 1e-6) keeps its
// relative accuracy. τ is reduced modulo 4K before Boost's sn/cn (AGM), and dn is taken as
// √(k'² + k² cn²), which stays accurate where Boost's cn/cos ratio for dn loses digits (τ ≈ K, k → 1).
// ω(t) costs one Jacobi evaluation (~1 µs): an oracle for tests, not an in-loop flow.
//
// Units: inertia [kg m²], rates [rad/s], time [s].
// Held to: tests/oracle/free_rigid_body_test.cpp (reference cases E1-E3, Euler-equation residual,
// and every integrator of sim/dynamics against it).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace gyrostab::oracles {

enum class EulerPoinsotCase {
  kAboutMinAxis,  // case a, H² < 2TB: ω stays near the axis of least moment C (epicycloidal)
  kAboutMaxAxis,  // case b, H² > 2TB: ω stays near the axis of greatest moment A (pericycloidal)
  kSeparatrix,    // case c, H² = 2TB: aperiodic, one turn-over of the middle axis
};

class EulerJacobiSolution {
 public:
  // |2TB - H²| ≤ this × 2TB is treated as the separatrix (case c); the rest is case a or b.
  static constexpr double kSeparatrixTolerance = 1e-13;

  // inertia_B: principal moments in the caller's axis order [kg m²], pairwise distinct.
  // w0_B: body rates at time t0, same axes [rad/s], not zero.
  EulerJacobiSolution(const Eigen::Vector3d& inertia_B, const Eigen::Vector3d& w0_B, double t0 = 0.0)
      : t0_(t0) {
    if (!(inertia_B.minCoeff() > 0.0))
      throw std::invalid_argument("EulerJacobiSolution: moments must be > 0");
    if (!(w0_B.norm() > 0.0))
      throw std::invalid_argument("EulerJacobiSolution: initial rate must be non-zero");
    // Sort the caller's axes to A > B > C; perm_[j] is the caller axis of sorted axis j.
    perm_ = {0, 1, 2};
    std::sort(perm_.begin(), perm_.end(), [&](int i, int j) { return inertia_B[i] > inertia_B[j]; });
    const bool even = (perm_[0] == 0 && perm_[1] == 1) || (perm_[0] == 1 && perm_[1] == 2) ||
                      (perm_[0] == 2 && perm_[1] == 0);
    parity_ = even ? 1.0 : -1.0;
    A_ = inertia_B[perm_[0]];
    B_ = inertia_B[perm_[1]];
    C_ = inertia_B[perm_[2]];
    if (!(A_ - B_ > 1e-12 * A_ && B_ - C_ > 1e-12 * A_)) {
      throw std::invalid_argument("EulerJacobiSolution: moments must be distinct (asymmetric body)");
    }
    const double w1 = parity_ * w0_B[perm_[0]], w2 = parity_ * w0_B[perm_[1]], w3 = parity_ * w0_B[perm_[2]];
    const double A = A_, B = B_, C = C_;
    two_T_ = A * w1 * w1 + B * w2 * w2 + C * w3 * w3;
    H2_ = A * A * w1 * w1 + B * B * w2 * w2 + C * C * w3 * w3;
    // Gaps as sums of non-negative terms (no cancellation), except gap_b which is a true difference.
    const double gap_a = B * (A - B) * w2 * w2 + C * (A - C) * w3 * w3;  // 2TA - H² ≥ 0
    const double gap_c = A * (A - C) * w1 * w1 + B * (B - C) * w2 * w2;  // H² - 2TC ≥ 0
    const double gap_b = C * (B - C) * w3 * w3 - A * (A - B) * w1 * w1;  // 2TB - H²

    if (std::abs(gap_b) <= kSeparatrixTolerance * B * two_T_) {
      regime_ = EulerPoinsotCase::kSeparatrix;
      amp_ = {std::sqrt(two_T_ * (B - C) / (A * (A - C))), std::sqrt(two_T_ / B),
              std::sqrt(two_T_ * (A - B) / (C * (A - C)))};
      rate_ = std::sqrt(two_T_ / B) * std::sqrt((A - B) * (B - C) / (A * C));
      k2_ = 1.0;
      kc2_ = 0.0;
      // ω1 and ω3 keep their signs; ω2 runs towards -s1 s3 (B ω2' = (C - A) ω3 ω1).
      sign_ = {w1 < 0.0 ? -1.0 : 1.0, 0.0, w3 < 0.0 ? -1.0 : 1.0};
      sign_[1] = -sign_[0] * sign_[2];
      const double sech0 = std::sqrt(0.5 * (w1 * w1 / (amp_[0] * amp_[0]) + w3 * w3 / (amp_[2] * amp_[2])));
      const double tanh0 = sign_[1] * w2 / amp_[1];
      permanent_ = (w1 == 0.0 && w3 == 0.0);  // steady spin about the middle axis
      if (permanent_) sign_[1] = w2 < 0.0 ? -1.0 : 1.0;
      tau0_ = permanent_ ? 0.0 : std::asinh(tanh0 / sech0);
      period_ = std::numeric_limits<double>::infinity();
      return;
    }

    double sn0 = 0.0, cn0 = 1.0;
    if (gap_b > 0.0) {  // case a
      regime_ = EulerPoinsotCase::kAboutMinAxis;
      amp_ = {std::sqrt(gap_c / (A * (A - C))), std::sqrt(gap_c / (B * (B - C))),
              std::sqrt(gap_a / (C * (A - C)))};
      k2_ = gap_c * (A - B) / (gap_a * (B - C));
      kc2_ = (A - C) * gap_b / (gap_a * (B - C));  // 1 - k², without cancellation
      rate_ = std::sqrt((B - C) * gap_a / (A * B * C));
      // ω3 = s3 amp3 dn keeps its sign; sn/cn signs from s1 s2 s3 = -1 with s2 = +1.
      const double s3 = w3 < 0.0 ? -1.0 : 1.0;
      sign_ = {-s3, 1.0, s3};
      if (amp_[1] > 0.0) sn0 = w2 / amp_[1];
      if (amp_[0] > 0.0) cn0 = sign_[0] * w1 / amp_[0];
    } else {  // case b
      regime_ = EulerPoinsotCase::kAboutMaxAxis;
      amp_ = {std::sqrt(gap_c / (A * (A - C))), std::sqrt(gap_a / (B * (A - B))),
              std::sqrt(gap_a / (C * (A - C)))};
      k2_ = gap_a * (B - C) / (gap_c * (A - B));
      kc2_ = -(A - C) * gap_b / (gap_c * (A - B));
      rate_ = std::sqrt((A - B) * gap_c / (A * B * C));
      const double s1 = w1 < 0.0 ? -1.0 : 1.0;
      sign_ = {s1, 1.0, -s1};
      if (amp_[1] > 0.0) sn0 = w2 / amp_[1];
      if (amp_[2] > 0.0) cn0 = sign_[2] * w3 / amp_[2];
    }
    k_ = std::sqrt(k2_);
    K_ = boost::math::ellint_1(k_);
    period_ = 4.0 * K_ / rate_;
    // Amplitude φ0 = am(τ0) from (sn, cn) on the unit circle, then τ0 = F(φ0, k) (any φ0: F is odd and
    // F(φ + π) = F(φ) + 2K).
    tau0_ = boost::math::ellint_1(k_, std::atan2(sn0, cn0));
  }

  // Body rates at time t in the caller's axes [rad/s].
  Eigen::Vector3d body_rate(double t) const {
    const double tau = tau0_ + rate_ * (t - t0_);
    double f1, f2, f3;  // the functions multiplying amp_[0..2]
    if (regime_ == EulerPoinsotCase::kSeparatrix) {
      if (permanent_) {
        f1 = 0.0, f2 = 1.0, f3 = 0.0;
      } else {
        f1 = f3 = 1.0 / std::cosh(tau);
        f2 = std::tanh(tau);
      }
    } else {
      const double period_tau = 4.0 * K_;
      const double reduced = tau - period_tau * std::floor(tau / period_tau);
      double cn = 0.0, dn = 0.0;
      const double sn = boost::math::jacobi_elliptic(k_, reduced, &cn, &dn);
      dn = std::sqrt(kc2_ + k2_ * cn * cn);
      if (regime_ == EulerPoinsotCase::kAboutMinAxis) {
        f1 = cn, f2 = sn, f3 = dn;
      } else {
        f1 = dn, f2 = sn, f3 = cn;
      }
    }
    const Eigen::Vector3d w_sorted(sign_[0] * amp_[0] * f1, sign_[1] * amp_[1] * f2, sign_[2] * amp_[2] * f3);
    Eigen::Vector3d w_B;
    for (int j = 0; j < 3; ++j) w_B[perm_[j]] = parity_ * w_sorted[j];
    return w_B;
  }

  // First time ≥ t at which the middle-axis rate changes sign [s]: τ = 2jK in cases a and b (the flips are
  // T_s/2 apart), τ = 0 on the separatrix (one flip); +inf if there is none.
  double next_middle_axis_zero(double t) const {
    const double tau = tau0_ + rate_ * (t - t0_);
    if (regime_ == EulerPoinsotCase::kSeparatrix) {
      return (!permanent_ && tau <= 0.0) ? t0_ - tau0_ / rate_ : std::numeric_limits<double>::infinity();
    }
    if (amp_[1] == 0.0) return std::numeric_limits<double>::infinity();  // permanent rotation
    const double j = std::ceil(tau / (2.0 * K_));
    return t0_ + (2.0 * K_ * j - tau0_) / rate_;
  }

  EulerPoinsotCase regime() const { return regime_; }
  // Period T_s of ω(t) [s], (2.16) in case a, (2.18) in case b; +inf on the separatrix.
  double period() const { return period_; }
  // Elliptic modulus squared k² (1 on the separatrix) and its complement 1 - k², computed separately.
  double modulus_squared() const { return k2_; }
  double complementary_modulus_squared() const { return kc2_; }
  // dτ/dt [1/s].
  double tau_rate() const { return rate_; }
  // Complete elliptic integral K(k) (case a, b).
  double quarter_period_tau() const { return K_; }
  // Twice the kinetic energy 2T [J] and |H|² [(kg m²/s)²] of the initial state.
  double twice_kinetic_energy() const { return two_T_; }
  double angular_momentum_squared() const { return H2_; }
  // Principal moments sorted A > B > C, and the caller's axis that carries each.
  Eigen::Vector3d sorted_moments() const { return {A_, B_, C_}; }
  int caller_axis_of_sorted(int j) const { return perm_[j]; }

 private:
  double t0_;
  std::array<int, 3> perm_{};
  double parity_{1.0};
  double A_{}, B_{}, C_{};
  double two_T_{}, H2_{};
  EulerPoinsotCase regime_{EulerPoinsotCase::kAboutMinAxis};
  std::array<double, 3> amp_{};
  std::array<double, 3> sign_{};
  double k_{0.0}, k2_{0.0}, kc2_{1.0}, K_{std::numbers::pi / 2};
  double rate_{0.0}, tau0_{0.0}, period_{0.0};
  bool permanent_{false};
};

}  // namespace gyrostab::oracles
