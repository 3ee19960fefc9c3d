// Free rigid body about its centre of mass (torque-free Euler-Poinsot case).
//
// Book: Magnus ch. 2 — Euler's equations (1.84) with M = 0, first integrals (2.1)-(2.2), exact
// Jacobi-elliptic solution (2.15)/(2.17)/(2.19), stability of permanent rotations (§2.4).
// State: rigid_body_state.hpp, x = [w_WB_B (rad/s) | q_WB].  Parameters: principal moments I1, I2, I3
// (kg m²), which must satisfy the triangle inequalities (1.10).
// Invariants: T = ½ w·Iw and the world-frame angular momentum L_W = R_WB I w.
// Oracles: tests/oracle/free_rigid_body_test.cpp (Jacobi solution, energy/|L| drift, middle-axis flips).
// Docs: docs/models/rigid-bodies.md#free-rigid-body
#pragma once

#include "sim/models/rigid_body_state.hpp"

namespace gyrostab::models {

struct FreeRigidBodyParams {
  dynamics::Vec3 inertia{1.0, 2.0, 3.0};  // principal moments I1, I2, I3 [kg m²]
};

class FreeRigidBody {
 public:
  static constexpr int kStateSize = 7;
  using State = RigidBodyState;
  static constexpr const char* kName = "free-rigid-body";

  explicit FreeRigidBody(const FreeRigidBodyParams& p = {}) : p_(p), inv_inertia_(p.inertia.cwiseInverse()) {}

  const dynamics::Vec3& inertia() const { return p_.inertia; }
  // Torque-free: the splitting integrator's kicks vanish.
  dynamics::Vec3 body_torque(double /*t*/, const Eigen::Ref<const Eigen::Vector4d>& /*q*/) const {
    return dynamics::Vec3::Zero();
  }
  static constexpr bool kHasTorque = false;

  void derivative(double /*t*/, const State& x, State& dx) const {
    rigid_body_derivative(p_.inertia, inv_inertia_, dynamics::Vec3::Zero(), x, dx);
  }
  void jacobian(double /*t*/, const State& x, Eigen::Matrix<double, 7, 7>& J) const {
    rigid_body_jacobian(p_.inertia, Eigen::Matrix<double, 3, 4>::Zero(), x, J);
  }
  void project(State& x) const { dynamics::renormalize_cheap(x.segment<4>(3)); }

  double kinetic_energy(const State& x) const {
    return 0.5 * x.segment<3>(0).dot(p_.inertia.cwiseProduct(x.segment<3>(0)));
  }
  dynamics::Vec3 angular_momentum_world(const State& x) const {
    const Eigen::Map<const dynamics::Quat> q(x.data() + 3);
    return q * p_.inertia.cwiseProduct(x.segment<3>(0)).eval();
  }

 private:
  FreeRigidBodyParams p_;
  dynamics::Vec3 inv_inertia_;
};

}  // namespace gyrostab::models
