// Heavy symmetric top on a fixed point — the Lagrange case (A = B, centre of mass on the figure axis).
//
// Book: Magnus §3.3.2 — equations (3.29)/(3.31), integrals (3.33)-(3.34), (3.36)-(3.38), the cubic
// U(u) (3.46)-(3.54), regular precession (3.57)-(3.61), sleeping-top stability C²ω0² ≥ 4GsA (3.70).
// State: rigid_body_state.hpp, x = [w_WB_B (rad/s) | q_WB]; world Z is up; the centre of mass is at
// s·e3 in body axes, so the gravity torque in body axes is Gs (Γ × e3) with Γ = R_WB^T e_Z.
// Parameters: A (transverse) and C (axial) moments about the fixed point [kg m²]; Gs = weight × distance of
// the centre of mass from the fixed point [N m], > 0 standing, < 0 hanging.
// Invariants: energy ½ w·Iw + Gs Γ3, vertical momentum (Iw)·Γ (3.33), spin w3 (3.36).
// Oracles: tests/oracle/heavy_symmetric_top_test.cpp.
// Docs: docs/models/rigid-bodies.md#heavy-symmetric-top
#pragma once

#include "sim/models/rigid_body_state.hpp"

namespace gyrostab::models {

struct HeavySymmetricTopParams {
  double A{1.0};   // transverse moment about the fixed point [kg m²]
  double C{0.5};   // axial moment [kg m²]
  double Gs{1.0};  // weight × centre-of-mass height on the figure axis [N m]
};

class HeavySymmetricTop {
 public:
  static constexpr int kStateSize = 7;
  using State = RigidBodyState;
  static constexpr const char* kName = "heavy-symmetric-top";
  static constexpr bool kHasTorque = true;
  static constexpr bool kTorqueDependsOnAttitudeOnly = true;  // gravity: lets the splitting reuse a kick

  explicit HeavySymmetricTop(const HeavySymmetricTopParams& p = {})
      : p_(p), inertia_(p.A, p.A, p.C), inv_inertia_(inertia_.cwiseInverse()) {}

  const HeavySymmetricTopParams& params() const { return p_; }
  const dynamics::Vec3& inertia() const { return inertia_; }

  // Gs (Γ × e3) = Gs (Γ2, -Γ1, 0): depends on attitude only, so a kick leaves q untouched.
  dynamics::Vec3 body_torque(double /*t*/, const Eigen::Ref<const Eigen::Vector4d>& q) const {
    const dynamics::Vec3 g = dynamics::up_in_body(q);
    return {p_.Gs * g.y(), -p_.Gs * g.x(), 0.0};
  }

  void derivative(double t, const State& x, State& dx) const {
    rigid_body_derivative(inertia_, inv_inertia_, body_torque(t, x.segment<4>(3)), x, dx);
  }
  void jacobian(double /*t*/, const State& x, Eigen::Matrix<double, 7, 7>& J) const {
    // Γ = (2(xz - wy), 2(yz + wx), 1 - 2(x² + y²)); M = Gs (Γ2, -Γ1, 0).
    const double qx = x[3], qy = x[4], qz = x[5], qw = x[6];
    Eigen::Matrix<double, 3, 4> dM = Eigen::Matrix<double, 3, 4>::Zero();
    dM.row(0) << 2 * qw, 2 * qz, 2 * qy, 2 * qx;      // dΓ2/d(x, y, z, w)
    dM.row(1) << -2 * qz, 2 * qw, -2 * qx, 2 * qy;    // -dΓ1/d(x, y, z, w)
    dM *= p_.Gs;
    rigid_body_jacobian(inertia_, dM, x, J);
  }
  void project(State& x) const { dynamics::renormalize_cheap(x.segment<4>(3)); }

  double energy(const State& x) const {
    const dynamics::Vec3 w = x.segment<3>(0);
    return 0.5 * w.dot(inertia_.cwiseProduct(w)) + p_.Gs * dynamics::up_in_body(x.segment<4>(3)).z();
  }
  // Angular momentum about the vertical, (3.33).
  double vertical_momentum(const State& x) const {
    return inertia_.cwiseProduct(x.segment<3>(0)).dot(dynamics::up_in_body(x.segment<4>(3)));
  }
  // cos θ, θ = angle of the figure axis from the vertical (u of (3.46)).
  static double cos_tilt(const State& x) { return dynamics::up_in_body(x.segment<4>(3)).z(); }

 private:
  HeavySymmetricTopParams p_;
  dynamics::Vec3 inertia_;
  dynamics::Vec3 inv_inertia_;
};

}  // namespace gyrostab::models
