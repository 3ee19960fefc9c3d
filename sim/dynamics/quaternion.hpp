// Unit-quaternion attitude with frame-named conventions (Drake style).
//
//   q_WB      rotates body-frame components into world-frame components: v_W = q_WB * v_B.
//   w_WB_B    angular velocity of body B in world W, expressed in B (rad/s).
//   Kinematics: dq_WB/dt = 1/2 q_WB ⊗ (0, w_WB_B)                   (Magnus (1.53)-(1.54) in quaternion form)
//
// A state vector stores the quaternion as Eigen's coefficient order (x, y, z, w), so
// Eigen::Map<Eigen::Quaterniond> views it without a copy.
// Docs: docs/models/integrators.md#methods
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace gyrostab::dynamics {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

// dq/dt for q_WB and body rate w_B, written into the (x, y, z, w) slots of dq.
inline void quaternion_rate(const Eigen::Ref<const Eigen::Vector4d>& q_xyzw, const Vec3& w_B,
                            Eigen::Ref<Eigen::Vector4d> dq_xyzw) {
  const double x = q_xyzw[0], y = q_xyzw[1], z = q_xyzw[2], w = q_xyzw[3];
  dq_xyzw[0] = 0.5 * (w * w_B.x() + y * w_B.z() - z * w_B.y());
  dq_xyzw[1] = 0.5 * (w * w_B.y() + z * w_B.x() - x * w_B.z());
  dq_xyzw[2] = 0.5 * (w * w_B.z() + x * w_B.y() - y * w_B.x());
  dq_xyzw[3] = -0.5 * (x * w_B.x() + y * w_B.y() + z * w_B.z());
}

// First-order projection back to |q| = 1: q (3 - |q|^2) / 2. Costs a multiply instead of a sqrt and a
// divide, and for the drift of one step (|q|^2 - 1 ~ 1e-10) it is as exact as q/|q| (the integrator survey,
// docs/models/integrators.md).
inline void renormalize_cheap(Eigen::Ref<Eigen::Vector4d> q_xyzw) { q_xyzw *= 0.5 * (3.0 - q_xyzw.squaredNorm()); }

// Body-fixed rotation by `angle` about the unit body axis n_B: q_WB <- q_WB ⊗ exp(angle n_B / 2).
inline void rotate_about_body_axis(Eigen::Ref<Eigen::Vector4d> q_xyzw, const Vec3& n_B, double angle) {
  const double s = std::sin(0.5 * angle), c = std::cos(0.5 * angle);
  Eigen::Map<Quat> q(q_xyzw.data());
  q = q * Quat(c, s * n_B.x(), s * n_B.y(), s * n_B.z());
}

// The world "up" direction (+Z_W) expressed in body axes: Gamma = R_WB^T e_Z.  Magnus's a3 vector (3.29).
inline Vec3 up_in_body(const Eigen::Ref<const Eigen::Vector4d>& q_xyzw) {
  const double x = q_xyzw[0], y = q_xyzw[1], z = q_xyzw[2], w = q_xyzw[3];
  return {2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)};
}

}  // namespace gyrostab::dynamics
