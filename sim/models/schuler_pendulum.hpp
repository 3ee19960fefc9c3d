// A rigid body (optionally with a fast spin: a gyro pendulum) hung at a point O that moves over the Earth or
// along any path — the full nonlinear 3-D Newton–Euler model about the moving pivot, for the Schuler
// (unperturbability) phenomena of Magnus §12.3.3 (12.52)-(12.68) and Chelnokov §1-§4.
//
// Body axes B: principal axes about O; axis 3 from the centre of mass up through O (the instrument vertical
// y3 of Chelnokov); the centre of mass at −l e3 (pendulous for l > 0).  Inertial frame I as in
// sim/motion/earth_vehicle.hpp.  Euler's equations about the accelerating pivot:
//   I ω' + ω × (I ω) = M,    M = m l (e3 × f_B) + 3 (GM/r³) (c_B × I_g c_B) + M_ext
//   f_B = specific force of O (a_abs − g_grav) in body axes, c_B = geocentric vertical in body axes.
// The first torque is gravity + the inertial force of the accelerated pivot acting at the centre of mass
// (Chelnokov's y3 × lm a, (1.6)/(1.9)); the second is the gravity-gradient torque of the body, whose
// small-tilt stiffness is −(3g/R)(C − A) — Magnus (12.57) k = m g s − (3g/R)(C − A),
// Chelnokov's U' = (3/2)(I1 − I3)(g/R)γ3² ([OCR-fix]: docs/models/gyro-pendulum.md). I_g (default = I) are
// the physical moments used by the gradient: Chelnokov's rotor class (1.2) has L = diag(k, k, I3) ω, i.e. it
// moves exactly like a rigid body of transverse inertia k while its gradient torque still uses the physical
// I1. A spinning rotor (gyro pendulum) is represented by the whole body spinning about its symmetry axis
// at ω3 = H/C: for an axisymmetric body and axisymmetric torques this is the gyrostat of Magnus
// (12.53)-(12.54) (total axial momentum H); see make_state().
//
// State x = [ω_IB_B (rad/s) | q_IB (x, y, z, w)] (sim/models/rigid_body_state.hpp).
// Parameters: I1, I2, I3 [kg m²] about O; m l [kg m]; optional I_g [kg m²]; M_ext [N m] body axes (held).
// Reference (template): any functor t → motion::SuspensionSample (suspension_reference.hpp).
// Integrators: dynamics::Rk4 (no spin: the slowest Schuler dynamics, steps of seconds), dynamics::RotorStrang /
// RotorYoshida4 (with spin: the fast rotation and nutation are carried by the exact free-body flow, the
// pendulous/gravity-gradient torque is the kick; steps up to h ω_N ≤ 0.8·2π, step_validation.hpp).
// Oracles: tests/oracle/schuler_pendulum_test.cpp — unperturbability for I1 = I2 = m l R under arbitrary
// manoeuvres (Chelnokov (2.5)), the period (12.60) for rod/sphere/4A = 3C, mistuned swing period;
// tests/oracle/gyro_pendulum_cross_test.cpp — same motion as Magnus (12.58) and Chelnokov (1.3).
// Docs: docs/models/gyro-pendulum.md#the-3-d-body-schuler_pendulumhpp
#pragma once

#include <cmath>

#include "sim/models/rigid_body_state.hpp"
#include "sim/motion/suspension_reference.hpp"

namespace gyrostab::models {

struct SchulerPendulumParams {
  dynamics::Vec3 inertia{1.0, 1.0, 1.0};  // I1, I2, I3 about O [kg m²] (I1 = I2 = A, I3 = C: Magnus's A, C)
  double ml{1.0 / 6.371e6};               // m l [kg m]; Schuler tuning: m l R = I1
  bool gravity_gradient{true};            // include 3 GM/r³ c × I_g c
  dynamics::Vec3 gradient_inertia{std::nan(""), 0.0, 0.0};  // I_g; NaN in x: same as `inertia`

  const char* invalid_reason() const {
    if (!(inertia.allFinite() && inertia.minCoeff() >= 0.0 && inertia.maxCoeff() > 0.0))
      return "moments of inertia must be finite and >= 0 (and not all 0)";
    if (!(inertia[0] > 0.0 && inertia[1] > 0.0)) return "transverse moments I1, I2 must be > 0";
    if (!(inertia[0] + inertia[1] >= inertia[2] && inertia[1] + inertia[2] >= inertia[0] &&
          inertia[2] + inertia[0] >= inertia[1]))
      return "moments of inertia violate the triangle inequality";
    if (!std::isfinite(ml)) return "m l must be finite";
    if (!std::isnan(gradient_inertia[0]) && !(gradient_inertia.allFinite() && gradient_inertia.minCoeff() >= 0.0))
      return "gravity-gradient moments must be finite and >= 0";
    return nullptr;
  }
};

template <class Reference>
class SchulerPendulum {
 public:
  static constexpr int kStateSize = 7;
  using State = RigidBodyState;
  static constexpr const char* kName = "schuler-pendulum";
  // The state's parts, by their first component: ω_IB_B (3), q_IB (x, y, z, w).
  static constexpr int kBodyRate = 0, kAttitude = 3;
  static constexpr bool kHasTorque = true;

  SchulerPendulum(const SchulerPendulumParams& p, const Reference& ref)
      : p_(p),
        ref_(ref),
        inertia_(p.inertia),
        inv_inertia_(p.inertia.cwiseInverse()),
        Ig_(std::isnan(p.gradient_inertia[0]) ? p.inertia : p.gradient_inertia) {
    // I3 = 0 (Chelnokov's c = 1 idealisation) has no axial dynamics: keep ω3 constant instead of 1/0.
    if (!(inertia_[2] > 0.0)) inv_inertia_[2] = 0.0;
  }

  dynamics::Vec3 torque_ext_B{dynamics::Vec3::Zero()};  // external torque, body axes [N m] (held)

  const SchulerPendulumParams& params() const { return p_; }
  const dynamics::Vec3& inertia() const { return inertia_; }
  const Reference& reference() const { return ref_; }
  Reference& reference() { return ref_; }

  // The body aligned with the reference trihedron Z and turning with it, plus a spin ω3 about its axis
  // (H = I3 ω_spin, the gyro pendulum's rotor): Chelnokov's (2.1) κ = 1, κ' = 0 when spin = 0.
  static State aligned_state(const motion::SuspensionSample& z, double spin = 0.0) {
    return make_rigid_body_state(z.w_Z + dynamics::Vec3(0.0, 0.0, spin), z.q_IZ);
  }

  dynamics::Vec3 body_torque(double t, const Eigen::Ref<const Eigen::Vector4d>& q) const {
    return torque_at(ref_(t), q);
  }

  dynamics::Vec3 torque_at(const motion::SuspensionSample& s, const Eigen::Ref<const Eigen::Vector4d>& q) const {
    const Eigen::Map<const dynamics::Quat> q_IB(q.data());
    const dynamics::Quat q_BI = q_IB.conjugate();
    const dynamics::Vec3 f_B = q_BI * s.f_I;
    dynamics::Vec3 M(-p_.ml * f_B.y(), p_.ml * f_B.x(), 0.0);  // m l (e3 × f_B)
    if (p_.gravity_gradient && s.gm_r3 != 0.0) {
      const dynamics::Vec3 c = q_BI * s.up_I;
      M += (3.0 * s.gm_r3) * c.cross(Ig_.cwiseProduct(c));
    }
    return M + torque_ext_B;
  }

  void derivative(double t, const State& x, State& dx) const {
    rigid_body_derivative(inertia_, inv_inertia_, body_torque(t, x.segment<4>(3)), x, dx);
  }
  void project(State& x) const { dynamics::renormalize_cheap(x.segment<4>(3)); }

  // The instrument vertical y3 (body axis 3) in the reference trihedron's axes.
  static dynamics::Vec3 vertical_in(const motion::SuspensionSample& z, const State& x) {
    const Eigen::Map<const dynamics::Quat> q_IB(x.data() + 3);
    return z.q_IZ.conjugate() * (q_IB * dynamics::Vec3::UnitZ());
  }
  // Angle between the instrument vertical and the geocentric vertical [rad] (Chelnokov's ϑ, (1.8)).
  static double tilt(const motion::SuspensionSample& z, const State& x) {
    const Eigen::Map<const dynamics::Quat> q_IB(x.data() + 3);
    const dynamics::Vec3 e3 = q_IB * dynamics::Vec3::UnitZ();
    return std::atan2(e3.cross(z.up_I).norm(), e3.dot(z.up_I));
  }
  // Magnus's small angles (12.54)-(12.56) of the case relative to Z: y3 ≈ (β, −α, 1).
  static void magnus_angles(const motion::SuspensionSample& z, const State& x, double& alpha, double& beta) {
    const dynamics::Vec3 y3 = vertical_in(z, x);
    alpha = std::atan2(-y3.y(), y3.z());
    beta = std::atan2(y3.x(), y3.z());
  }

 private:
  SchulerPendulumParams p_;
  Reference ref_;
  dynamics::Vec3 inertia_, inv_inertia_, Ig_;
};

}  // namespace gyrostab::models
