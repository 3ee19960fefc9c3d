// Kinematic (gimbal) error of a two-gimbal position gyro on a rotating vehicle: the rotor axis keeps its
// direction in inertial space, the vehicle yaws, pitches and rolls, and the two gimbal angles α (outer
// gimbal against the case, about gyro axis 1) and β (inner against outer, about axis 2) that the pick-offs
// read are not the vehicle's Euler angles.
//
// Book: Magnus, Kreisel §12.1, (12.2)-(12.20), Figs. 12.1-12.5 (docs/models/gimbal-error.md).
//   vehicle attitude (12.2)-(12.3):  a^F = Rz(ψ) Ry(ϑ) Rx(φ)   (yaw ψ about 3, pitch ϑ about 2', roll φ about 1^F)
//   gimbal chain (12.4)-(12.7):      r^F = a^E Rx(α) Ry(β) r^J, rotor axis = inner-gimbal axis 3
//   inertially fixed rotor (12.6):   v = (a^E)ᵀ (a^F)ᵀ a^E e3 = (sinβ, −sinα cosβ, cosα cosβ)
// so sinβ = v1 and tanα = −v2/v3. The mounting a^E is the signed permutation that puts gyro axis c[i] along
// vehicle axis i for the configuration string c ("321": gyro 3 along the longitudinal axis 1^F, gyro 2 along
// 2^F, gyro 1 along the normal axis 3^F); its signs are the proper rotation (det +1) whose angles are those
// of the book's closed forms (12.11), (12.16)-(12.20) — sim/oracles/gimbal_error_closed_forms.hpp, which the
// oracle test holds this kinematics to. The rotor axis in inertial space is a^E e3: the gyro was aligned
// (α = β = 0) with the vehicle at ψ = ϑ = φ = 0, the book's reference.
//
// State x = q_WF, the vehicle attitude (vehicle axes to inertial axes, Eigen's (x, y, z, w)) [-], integrated
// from the prescribed body rates w_WF_F [rad/s] of sim/motion/prescribed_base_rotation.hpp (the same
// a^F = Rz Ry Rx); the gimbal angles are computed from the integrated attitude, not from the Euler angles.
// Or from the rates of a scene's [motion] (sim/motion/scene_base_motion.hpp: prescribed, or a recorded motion
// whose attitude q_WB is the vehicle's q_WF); the Euler angles are then read from its attitude (ZYX).
// Parameters: the mounting configuration; the vehicle motion (angles [rad], rates [rad/s], harmonics).
// Assumptions (book): the rotor axis is exactly fixed in inertial space (no drift, no nutation, no gimbal
// friction: a free gyro whose H is large); ideal pick-offs; the vehicle angles are the flight-mechanics
// sequence ψ, ϑ, φ. At cosβ = 0 (gimbal lock) α is undefined: atan2 returns a value, the error is then
// meaningless.
// Oracle: tests/oracle/gimbal_error_test.cpp — every configuration against its closed form over random
// attitudes, the heading gyro "321" in a level turn (12.13)-(12.15) and its extreme value (bank 30°:
// 4.117°), and the integrated attitude against the analytic one.
// Docs: docs/models/gimbal-error.md
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include "sim/dynamics/quaternion.hpp"
#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/motion/scene_base_motion.hpp"

namespace gyrostab::models {

// The six configurations of §12.1, in the book's order of (12.11), (12.16)-(12.20).
enum class GimbalMounting : int { k321, k312, k213, k231, k123, k132 };
inline constexpr std::string_view kGimbalMountingNames[] = {"321", "312", "213", "231", "123", "132"};

// Vehicle axis (0 = 1^F, 1 = 2^F, 2 = 3^F) along which gyro axis `gyro_axis` (0, 1, 2) lies.
inline int vehicle_axis_of(GimbalMounting m, int gyro_axis) {
  const std::string_view c = kGimbalMountingNames[static_cast<int>(m)];
  for (int i = 0; i < 3; ++i) {
    if (c[static_cast<std::size_t>(i)] - '1' == gyro_axis) return i;
  }
  return -1;
}

// a^E: case (gyro) axes to vehicle axes, R_F_G. The signs are the det +1 solution that reproduces the
// closed forms (the other sign set of each configuration has det −1, a mirror image).
inline Eigen::Matrix3d mounting_matrix(GimbalMounting m) {
  constexpr std::array<std::array<int, 3>, 6> kSigns{{{-1, -1, -1},   // 321
                                                      {1, -1, -1},    // 312
                                                      {-1, -1, -1},   // 213
                                                      {-1, 1, -1},    // 231
                                                      {-1, -1, 1},    // 123
                                                      {-1, -1, -1}}};  // 132
  const std::string_view c = kGimbalMountingNames[static_cast<int>(m)];
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    a(i, c[static_cast<std::size_t>(i)] - '1') = kSigns[static_cast<std::size_t>(m)][static_cast<std::size_t>(i)];
  }
  return a;
}

struct GimbalAngles {
  double alpha{0.0};  // outer gimbal against the case, about gyro axis 1, in (−π, π] [rad]
  double beta{0.0};   // inner gimbal against the outer, about axis 2, in [−π/2, π/2] [rad]
};

// The gimbal angles for the vehicle attitude R_WF (12.6)-(12.10). β from atan2 rather than asin keeps its
// accuracy near ±90°.
inline GimbalAngles gimbal_angles(const Eigen::Matrix3d& R_WF, const Eigen::Matrix3d& a_E) {
  const Eigen::Vector3d rotor_W = a_E.col(2);
  const Eigen::Vector3d rotor_F = R_WF.transpose() * rotor_W;
  const Eigen::Vector3d v = a_E.transpose() * rotor_F;
  return {std::atan2(-v[1], v[2]), std::atan2(v[0], std::hypot(v[1], v[2]))};
}

struct PositionGyroGimbalErrorParams {
  GimbalMounting mounting{GimbalMounting::k321};
  motion::PrescribedBaseRotation<2> vehicle{};  // ψ(t), ϑ(t), φ(t) of (12.2)
  bool from_motion{false};                      // the vehicle moves by `motion` instead
  motion::SceneBaseMotion motion{};

  dynamics::Vec3 rate(double t) const { return from_motion ? motion(t).w_B : vehicle(t).w_B; }  // w_WF_F
  dynamics::Quat attitude(double t) const { return from_motion ? motion.attitude(t) : vehicle.attitude(t); }
  // (φ, ϑ, ψ) [rad]: the generator's angles, or those of the motion's attitude R = Rz(ψ) Ry(ϑ) Rx(φ).
  std::array<double, 3> euler(double t) const {
    if (!from_motion) return {vehicle.roll(t).angle, vehicle.pitch(t).angle, vehicle.yaw(t).angle};
    const Eigen::Matrix3d R = motion.attitude(t).toRotationMatrix();
    return {std::atan2(R(2, 1), R(2, 2)), -std::asin(std::clamp(R(2, 0), -1.0, 1.0)), std::atan2(R(1, 0), R(0, 0))};
  }
};

// The vehicle attitude kinematics dq_WF/dt = ½ q_WF ⊗ (0, w_WF_F) under the prescribed rates, and the
// gyro's gimbal angles read from it.
class PositionGyroGimbalError {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  static constexpr const char* kName = "position-gyro-gimbal-error";
  // The state's components, by name (q_WF in Eigen's order).
  static constexpr int kQx = 0, kQy = 1, kQz = 2, kQw = 3;

  explicit PositionGyroGimbalError(const PositionGyroGimbalErrorParams& p = {})
      : p_(p), a_E_(mounting_matrix(p.mounting)) {}

  const PositionGyroGimbalErrorParams& params() const { return p_; }

  // The attitude at t from the Euler angles (the start of the integration).
  State initial_state(double t) const {
    const dynamics::Quat q = p_.attitude(t);
    State x;
    x << q.x(), q.y(), q.z(), q.w();
    return x;
  }

  void derivative(double t, const State& x, State& dx) const {
    dynamics::quaternion_rate(x, p_.rate(t), dx);
  }
  // RK4 does not keep |q| = 1; the drift per step is far below the cheap projection's validity.
  void project(State& x) const { dynamics::renormalize_cheap(x); }

  GimbalAngles gimbal_angles_of(const State& x) const {
    const Eigen::Map<const dynamics::Quat> q(x.data());
    return gimbal_angles(q.toRotationMatrix(), a_E_);
  }
  const Eigen::Matrix3d& mounting() const { return a_E_; }

 private:
  PositionGyroGimbalErrorParams p_;
  Eigen::Matrix3d a_E_;
};

}  // namespace gyrostab::models
