// Symmetric rotor in a two-gimbal (Cardan) suspension on a moving base — the full nonlinear model.
//
// Book: Magnus §4.2-4.4 and §10.1-10.2: equations (10.4)-(10.7) (and (4.45), (4.61) as special cases),
// extended, with the same kinematics, to a prescribed base angular velocity (§10.2, whose small-angle form
// is (10.21)-(10.22)). Derived with Kane's method: for each generalised speed, the partial angular
// velocities of the outer gimbal and of the inner gimbal + rotor (a gyrostat with spin momentum H) dotted
// with their Euler equations. Angles are the book's Cardan angles (§1.4.3c):
//   α  outer gimbal about base axis 1;  β  inner gimbal about the outer gimbal's axis 2;
//   the rotor spins about inner axis 3, α = β = 0 has all axes aligned.
// State x = [α (rad), β (rad), α' (rad/s), β' (rad/s), H (N m s)], H = C^R (γ' + ω_J3) the rotor's
// absolute spin momentum (10.3), constant unless a rotor torque M3 acts.
// Parameters (book symbols, SI): rotor A^R, C^R; inner gimbal A^J, B^J, C^J; outer gimbal A^A about its
// axis (B^A, C^A about the other two, which matter only on a rotating base) [kg m²]; Gs = weight × offset
// of the centre of mass along the rotor axis [N m] (> 0 towards +axis 3); viscous d1, d2 [N m s/rad] and
// Coulomb r1, r2 [N m] friction in the outer and inner bearings.
// Inputs (zero-order hold): gimbal torques M1 (outer), M2 (inner), rotor torque M3 [N m].
// Derived: A = A^A + A^J + A^R, B = B^J + A^R, P = A^A + C^J, Q = A^R + A^J - C^J, outer-axis inertia
// I(β) = A cos²β + P sin²β.
// Assumptions (§4.2): axes intersect, bodies rigid, principal axes along the gimbal axes, rotor symmetric.
// Coulomb friction r1, r2 (§11.2.2, (11.6)-(11.18)): stick-slip by default (friction_model kStickSlip,
// sim/drives/gimbal_bearings.hpp, decided once per integrator step in begin_step with the axis inertias
// I(β), B): an axis is held while its net other torque stays within r, so a torque below friction moves
// nothing. kSmooth keeps the regularised r·v/sqrt(v² + v_c²), v_c = `coulomb_velocity`: viscous r/v_c at
// small rates, under which a torque below friction still precesses (creeps) — for comparison only.
// Oracles: tests/oracle/gimbal_gyro_test.cpp — quartic (10.14), kinetic drift (4.67), viscous nutation
// decay (A d2 + B d1)/(2AB), Coulomb linear decay (§11.2.2), torque-step transient
// (docs/models/gimbal-gyro.md#precession-model-p0); tests/oracle/gimbal_stick_slip_test.cpp — the
// stick/slip threshold r1 (no motion below it, the drift (M1 − r1)/H of (11.11)-(11.15) above it).
// Docs: docs/models/gimbal-gyro.md#full-model
#pragma once

#include <cmath>

#include "sim/drives/gimbal_bearings.hpp"
#include "sim/dynamics/damped_gyroscopic_flow.hpp"
#include "sim/models/base_motion.hpp"

namespace gyrostab::models {

struct GimbalGyroParams {
  double AR{0.5}, CR{1.0};              // rotor transverse / axial moment [kg m²]
  double AJ{0.0}, BJ{0.0}, CJ{0.0};     // inner gimbal [kg m²]
  double AA{0.0}, BA{0.0}, CA{0.0};     // outer gimbal: about its axis, and the two others [kg m²]
  double Gs{0.0};                       // weight × centre-of-mass offset along the rotor axis [N m]
  double d1{0.0}, d2{0.0};              // viscous friction, outer / inner bearing [N m s/rad]
  double r1{0.0}, r2{0.0};              // Coulomb friction, outer / inner bearing [N m]
  drives::CoulombModel friction_model{drives::CoulombModel::kStickSlip};
  double stick_velocity{1e-9};          // v_st, stick-slip dead band [rad/s]
  double coulomb_velocity{1e-4};        // regularisation speed of the smooth Coulomb law [rad/s]

  double A() const { return AA + AJ + AR; }
  double B() const { return BJ + AR; }
  double P() const { return AA + CJ; }
  double Q() const { return AR + AJ - CJ; }
  double outer_axis_inertia(double beta) const {
    const double c = std::cos(beta), s = std::sin(beta);
    return A() * c * c + P() * s * s;
  }
};

struct GimbalTorques {
  double M1{0.0};  // outer gimbal axis [N m]
  double M2{0.0};  // inner gimbal axis [N m]
  double M3{0.0};  // rotor axis (spin motor) [N m]
};

template <class Base = FixedBase>
class GimbalGyro {
 public:
  static constexpr int kStateSize = 5;
  using State = Eigen::Matrix<double, 5, 1>;
  static constexpr const char* kName = "gimbal-gyro";

  explicit GimbalGyro(const GimbalGyroParams& p = {}, const Base& base = {})
      : p_(p), base_(base), I1_(p.AJ + p.AR), I2_(p.BJ + p.AR), I3_(p.CJ),
        bearings_(p.r1, p.r2, p.stick_velocity),
        stick_slip_(p.friction_model == drives::CoulombModel::kStickSlip && bearings_.active()) {}

  GimbalTorques torques{};  // inputs, held between steps

  const GimbalGyroParams& params() const { return p_; }
  const Base& base() const { return base_; }

  static State make_state(double alpha, double beta, double alpha_rate, double beta_rate, double H) {
    State x;
    x << alpha, beta, alpha_rate, beta_rate, H;
    return x;
  }

  void derivative(double t, const State& x, State& dx) const { (void)derivative_with_pair(t, x, dx); }

  // derivative() and gyroscopic_pair() at the same (t, x) from one evaluation of sinβ, cosβ and I(β): what
  // dynamics::GyroscopicExponential asks for at each of its two stages. Bit-identical to calling both.
  dynamics::GyroscopicPair derivative_with_pair(double t, const State& x, State& dx) const {
    const BaseSample b = base_(t);
    const double sa = std::sin(x[0]), ca = std::cos(x[0]);
    const double sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double u = x[2], w = x[3], H = x[4];
    // Outer gimbal: angular velocity in its axes, and its rate of change with α'' = 0.
    const double a1 = u + b.w_B[0];
    const double a2 = b.w_B[1] * ca + b.w_B[2] * sa;
    const double a3 = -b.w_B[1] * sa + b.w_B[2] * ca;
    const double dA1 = b.dw_B[0];
    const double dA2 = b.dw_B[1] * ca + b.dw_B[2] * sa + u * a3;
    const double dA3 = -b.dw_B[1] * sa + b.dw_B[2] * ca - u * a2;
    // Inner gimbal (carrying the rotor's transverse inertia): Ry(β)^T ω_A + (0, β', 0), rate with β'' = 0.
    const double j1 = cb * a1 - sb * a3, j2 = a2 + w, j3 = sb * a1 + cb * a3;
    const double dJ1 = cb * dA1 - sb * dA3 - w * j3;
    const double dJ2 = dA2;
    const double dJ3 = sb * dA1 + cb * dA3 + w * j1;
    // Euler equations of the outer gimbal (axis-1 row) and of the gyrostat inner gimbal + rotor.
    const double eA1 = p_.AA * dA1 + (p_.CA - p_.BA) * a2 * a3;
    const double L1 = I1_ * j1, L2 = I2_ * j2, L3 = I3_ * j3 + H;
    const double eJ1 = I1_ * dJ1 + (j2 * L3 - j3 * L2);
    const double eJ2 = I2_ * dJ2 + (j3 * L1 - j1 * L3);
    const double eJ3 = I3_ * dJ3 + torques.M3 + (j1 * L2 - j2 * L1);
    // Generalised active forces: motors, gravity/specific force (potential Gs·(e3_J · up)), friction.
    const double Qa = torques.M1 + p_.Gs * cb * (ca * b.up_B[1] + sa * b.up_B[2]) - p_.d1 * u - coulomb(0, p_.r1, u);
    const double Qb = torques.M2 - p_.Gs * (cb * b.up_B[0] + sa * sb * b.up_B[1] - ca * sb * b.up_B[2]) -
                      p_.d2 * w - coulomb(1, p_.r2, w);
    const double M11 = p_.AA + I1_ * cb * cb + I3_ * sb * sb;
    dx[0] = u;
    dx[1] = w;
    dx[2] = (Qa - eA1 - cb * eJ1 - sb * eJ3) / M11;
    dx[3] = (Qb - eJ2) / I2_;
    dx[4] = torques.M3;
    return {x[4] * cb / M11, x[4] * cb / I2_, p_.d1 / M11, p_.d2 / I2_};
  }
  void project(State& /*x*/) const {}

  // Stick-slip (sim/dynamics/step_start.hpp): holds a stuck gimbal (its rate set to 0) and fixes the
  // Coulomb torques for [t, t + h] from the generalised net torques without friction at the step start,
  // I(β) α'' and B β'' (the mass matrix is diagonal in these coordinates).
  void begin_step(double t, double h, State& x) const {
    if (!stick_slip_) return;
    bearings_.begin_step(h, x[2], x[3], [&] {
      State dx;
      (void)derivative_with_pair(t, x, dx);
      const double sb = std::sin(x[1]), cb = std::cos(x[1]);
      const double M11 = p_.AA + I1_ * cb * cb + I3_ * sb * sb;
      return drives::AxisLoads{{M11 * dx[2], I2_ * dx[3]}, {M11, I2_}};
    });
  }
  // The bearings of the current step (stuck flags, held torques); stick-slip only.
  const drives::GimbalBearings& bearings() const { return bearings_; }

  // The fast linear part at the current β: α'' ∋ -a β' - p α', β'' ∋ +b α' - q β' with
  // a = H cosβ/I(β), b = H cosβ/B, p = d1/I(β), q = d2/B; sqrt(ab) = H cosβ/sqrt(I(β) B) is the nutation
  // (4.65), (p + q)/2 its viscous decay rate (11.3).
  dynamics::GyroscopicPair gyroscopic_pair(const State& x) const {
    const double sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double M11 = p_.AA + I1_ * cb * cb + I3_ * sb * sb;
    return {x[4] * cb / M11, x[4] * cb / I2_, p_.d1 / M11, p_.d2 / I2_};
  }

  // Energy of the gimbals (the rotor's spin energy H²/2C^R is constant and left out) on a base at rest;
  // conserved without friction and motor torques. (4.37)
  double energy(const State& x) const {
    const BaseSample b = base_(0.0);
    const double sa = std::sin(x[0]), ca = std::cos(x[0]), sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double V = p_.Gs * (sb * b.up_B[0] - sa * cb * b.up_B[1] + ca * cb * b.up_B[2]);
    return 0.5 * p_.outer_axis_inertia(x[1]) * x[2] * x[2] + 0.5 * I2_ * x[3] * x[3] + V;
  }
  // Momentum about the outer axis, α' I(β) + H sinβ (4.36): conserved on a fixed base when the outer axis
  // is vertical (up_B = e1), without friction and outer torque.
  double outer_axis_momentum(const State& x) const {
    return x[2] * p_.outer_axis_inertia(x[1]) + x[4] * std::sin(x[1]);
  }

 private:
  // The Coulomb torque opposing axis `axis` at rate v, subtracted from its generalised force [N m].
  double coulomb(int axis, double r, double v) const {
    if (r == 0.0) return 0.0;
    if (stick_slip_) return -bearings_.torque(axis);
    return r * v / std::sqrt(v * v + p_.coulomb_velocity * p_.coulomb_velocity);
  }

  GimbalGyroParams p_;
  Base base_;
  double I1_, I2_, I3_;
  // The integrators hold the model const; the step's friction is a function of the step-start state and
  // the held inputs (like them, set between steps), so re-integrating from a saved state reproduces it.
  mutable drives::GimbalBearings bearings_;
  bool stick_slip_;
};

}  // namespace gyrostab::models
