// State layout shared by the rigid-body models (free body, heavy top):
//   x = [ w_WB_B (3) rad/s | q_WB (x, y, z, w) (4) ]
// Principal body axes 1, 2, 3 (Magnus §1.3); axis 3 is the figure axis of a symmetric body.
// Docs: docs/models/rigid-bodies.md#state-layout-both-bodies
#pragma once

#include <Eigen/Core>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

using RigidBodyState = Eigen::Matrix<double, 7, 1>;

inline auto body_rate(RigidBodyState& x) { return x.segment<3>(0); }
inline auto body_rate(const RigidBodyState& x) { return x.segment<3>(0); }
inline auto attitude(RigidBodyState& x) { return x.segment<4>(3); }
inline auto attitude(const RigidBodyState& x) { return x.segment<4>(3); }

inline RigidBodyState make_rigid_body_state(const dynamics::Vec3& w_B, const dynamics::Quat& q_WB) {
  RigidBodyState x;
  x.segment<3>(0) = w_B;
  x.segment<4>(3) = q_WB.normalized().coeffs();
  return x;
}

// Rigid-body dynamics in body axes, Euler (1.84): I w' = M - w × (I w), and the quaternion kinematics.
// Shared by every rigid-body model so that the Jacobian below stays in one place.
// `inv_inertia` is 1/I per axis, precomputed: three divisions would sit on the step's dependency chain.
inline void rigid_body_derivative(const dynamics::Vec3& inertia, const dynamics::Vec3& inv_inertia,
                                  const dynamics::Vec3& torque_B, const RigidBodyState& x, RigidBodyState& dx) {
  const dynamics::Vec3 w = x.segment<3>(0);
  const dynamics::Vec3 L = inertia.cwiseProduct(w);
  dx.segment<3>(0) = (torque_B - w.cross(L)).cwiseProduct(inv_inertia);
  dynamics::quaternion_rate(x.segment<4>(3), w, dx.segment<4>(3));
}

// d(rigid_body_derivative)/dx for a torque that depends on attitude only, given dM/dq (3x4).
inline void rigid_body_jacobian(const dynamics::Vec3& I, const Eigen::Matrix<double, 3, 4>& dM_dq,
                                const RigidBodyState& x, Eigen::Matrix<double, 7, 7>& J) {
  J.setZero();
  const double w1 = x[0], w2 = x[1], w3 = x[2];
  // Euler equations: I1 w1' = (I2 - I3) w2 w3 + M1, cyclic.
  J(0, 1) = (I[1] - I[2]) * w3 / I[0];
  J(0, 2) = (I[1] - I[2]) * w2 / I[0];
  J(1, 0) = (I[2] - I[0]) * w3 / I[1];
  J(1, 2) = (I[2] - I[0]) * w1 / I[1];
  J(2, 0) = (I[0] - I[1]) * w2 / I[2];
  J(2, 1) = (I[0] - I[1]) * w1 / I[2];
  J.block<3, 4>(0, 3) = dM_dq.array().colwise() / I.array();
  // Quaternion kinematics dq/dt = 1/2 q ⊗ (0, w): linear in q and in w.
  const double qx = x[3], qy = x[4], qz = x[5], qw = x[6];
  J.block<4, 3>(3, 0) << qw, -qz, qy,  //
      qz, qw, -qx,                    //
      -qy, qx, qw,                    //
      -qx, -qy, -qz;
  J.block<4, 3>(3, 0) *= 0.5;
  J.block<4, 4>(3, 3) << 0, w3, -w2, w1,  //
      -w3, 0, w1, w2,                    //
      w2, -w1, 0, w3,                    //
      -w1, -w2, -w3, 0;
  J.block<4, 4>(3, 3) *= 0.5;
}

}  // namespace gyrostab::models
