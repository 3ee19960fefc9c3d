// Gyro-pendulum systems with a moving suspension point in Rodrigues–Hamilton parameters — Chelnokov,
// "Quaternion methods in problems of relative motion of dynamically symmetric material systems. II"
// (docs/models/gyro-pendulum.md#chelnokovs-quaternion-form), the second-order quaternion equations
//   (1.3)-(1.5)  κ: the gyro frame Y relative to the reference trihedron Z        (ChelnokovKappa)
//   (3.1)-(3.2)  λ: the frame Y' (turning with Ω = ω − c r y3) relative to Z    (ChelnokovLambda, M = 0)
//   (4.1)-(4.4)  z: Y' relative to the non-rotating frame X (inertial axes)      (ChelnokovZ, M = 0)
// The equations are reconstructed from the scanned paper and checked numerically; [OCR-fix] places used
// here (listed in docs/models/gyro-pendulum.md): (1.4) reads
// ¼(ω°² − ω²) (printed ¼(ω° − ω²)); (4.1) is z'' + ¼Ω²z (printed ż); κ = ν̄∘z∘μ̄ (printed z = …); u' = −c r y3;
// M3 = I3 r0'; U' = (3/2)(I1 − I3)(g/R)γ3²; all time-derivative dots restored.
//
// Class of systems (Chelnokov (1.2)): rotors with H1 = (k − I1) p, H2 = (k − I2) q, H3 = 0, so the angular
// momentum is L_Y = k ω_Y + (I3 − k) r i3 — the system moves like a rigid body of transverse inertia k
// (k = I1: a physical pendulum; k > I1: "formally H = 0" gyro pendulum, the effective inertia of the
// cross-walk §6.9). n = 1/k, c = (k − I3)/k. Centre of mass on −y3 at distance l, mass m.
//   A = l m a + z3 dU'/dγ3      (a = w − g: the pivot's specific force; (1.6), (1.9)), A3 = A·z3, A3' = A·y3
//   U' = (3/2)(I1g − I3g) (GM/r³) γ3²   (gravity gradient, optional; I1g, I3g the physical moments)
// Quaternions here are stored in the PAPER's order (q0 scalar, q1, q2, q3) — not Eigen's (x, y, z, w) of
// dynamics/quaternion.hpp. Products compose left to right as in the paper: s = ν∘κ, x_Z = κ∘x_Y∘κ̄, so
// κ = q_IZ⁻¹ q_IB in Eigen terms (kappa_from_body()).
// χ, χ*: the multiplier that keeps |κ| = 1. The models use the constraint form
//   χ = −(|κ'|² + κ·T)/|κ|²  (T = the right-hand side without χκ),
// which equals the paper's closed forms (1.4)/(3.2) on |κ| = 1; chi_closed_form() evaluates (1.4) for the
// residual test. For (4.1) the constraint form reduces exactly to −¼Ω² = −Σ zj'² (4.3).
//
// State (Kappa): x = [κ0..κ3 (-), κ0'..κ3' (1/s), r (rad/s)], r = ω·y3 (1.5) I3 r' = M3.
// State (Lambda, Z): x = [λ or z (4) (-), their rates (4) (1/s)].
// Parameters: k, I3 [kg m²], l m [kg m], I1g, I3g [kg m²]. Reference: any functor t → SuspensionSample
// (ω°_Z, ω°_Z', a_Z in Z; a and z3 in inertial axes for the z-form; GM/r³).
// Integrator: dynamics::Rk4 (no fast mode in this class: the rotors are idealised by (1.2)); project()
// renormalises the quaternion and removes the radial part of its rate.
// Oracles: tests/oracle/chelnokov_test.cpp — (1.3)/(1.4)/(4.1) residuals on a 3-D rigid-body run,
// κ/λ/z forms giving the same motion, unperturbability (2.5), energy integral (2.11), stability (2.14),
// Kepler oscillator (§4); cross-check with Magnus (12.58) in tests/oracle/gyro_pendulum_cross_test.cpp.
// Docs: docs/models/gyro-pendulum.md#chelnokovs-quaternion-form
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"
#include "sim/motion/suspension_reference.hpp"

namespace gyrostab::models {

namespace chelnokov {

using Quat4 = Eigen::Vector4d;  // (q0, q1, q2, q3): the paper's order
using dynamics::Vec3;

inline Quat4 mul(const Quat4& a, const Quat4& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}
inline Quat4 pure(const Vec3& v) { return {0.0, v.x(), v.y(), v.z()}; }
inline Quat4 scalar_vector(double s, const Vec3& v) { return {s, v.x(), v.y(), v.z()}; }
inline Quat4 conj(const Quat4& q) { return {q[0], -q[1], -q[2], -q[3]}; }
inline Vec3 vec(const Quat4& q) { return {q[1], q[2], q[3]}; }
// q∘i3
inline Quat4 times_i3(const Quat4& q) { return {-q[3], q[2], -q[1], q[0]}; }
// y3 = κ∘i3∘κ̄ for a unit κ (the instrument vertical in the frame κ maps into), Chelnokov (1.8).
inline Vec3 vertical(const Quat4& k) {
  return {2.0 * (k[1] * k[3] + k[0] * k[2]), 2.0 * (k[2] * k[3] - k[0] * k[1]),
          k[0] * k[0] - k[1] * k[1] - k[2] * k[2] + k[3] * k[3]};
}
inline Quat4 from_eigen(const dynamics::Quat& q) { return {q.w(), q.x(), q.y(), q.z()}; }
inline dynamics::Quat to_eigen(const Quat4& q) { return dynamics::Quat(q[0], q[1], q[2], q[3]); }

}  // namespace chelnokov

struct ChelnokovParams {
  double k{1.0};       // effective transverse inertia (1.2) [kg m²]; unperturbable: k = l m R (2.5)
  double I3{0.5};      // axial moment [kg m²]
  double lm{1.0 / 6.371e6};  // l m [kg m]
  bool gravity_gradient{false};  // U' of the Newtonian field
  double I1g{1.0}, I3g{0.5};     // physical moments for U' [kg m²]

  double n() const { return 1.0 / k; }
  double c() const { return (k - I3) / k; }
  const char* invalid_reason() const {
    if (!(std::isfinite(k) && k > 0.0)) return "k must be finite and > 0";
    if (!(std::isfinite(I3) && I3 >= 0.0)) return "I3 must be finite and >= 0";
    if (!std::isfinite(lm)) return "l m must be finite";
    if (!(std::isfinite(I1g) && std::isfinite(I3g))) return "gravity-gradient moments must be finite";
    return nullptr;
  }
};

namespace chelnokov {

// dU'/dγ3 for the Newtonian field, 3 (I1g − I3g) (GM/r³) γ3; 0 without the gradient.
inline double gradient_force(const ChelnokovParams& p, double gm_r3, double gamma3) {
  return p.gravity_gradient ? 3.0 * (p.I1g - p.I3g) * gm_r3 * gamma3 : 0.0;
}

// Second derivative from T (everything but χ q) with the constraint multiplier.
inline Quat4 constrained(const Quat4& q, const Quat4& dq, const Quat4& T, double& chi) {
  chi = -(dq.squaredNorm() + q.dot(T)) / q.squaredNorm();
  return chi * q + T;
}

inline void project_unit(Eigen::Ref<Eigen::Matrix<double, 8, 1>> x8) {
  const double n = x8.head<4>().norm();
  x8.head<4>() /= n;
  const Quat4 q = x8.head<4>();
  x8.segment<4>(4) -= q.dot(x8.segment<4>(4)) * q;
}

}  // namespace chelnokov

// (1.3)-(1.5): κ relative to the reference trihedron Z.
template <class Reference>
class ChelnokovKappa {
 public:
  static constexpr int kStateSize = 9;
  using State = Eigen::Matrix<double, 9, 1>;
  using Quat4 = chelnokov::Quat4;
  using Vec3 = dynamics::Vec3;
  static constexpr const char* kName = "chelnokov-kappa";

  ChelnokovKappa(const ChelnokovParams& p, const Reference& ref) : p_(p), ref_(ref) {}

  Vec3 torque_Y{Vec3::Zero()};  // M_Y: torques other than potential and inertial forces, Y axes [N m] (held)

  const ChelnokovParams& params() const { return p_; }
  const Reference& reference() const { return ref_; }
  Reference& reference() { return ref_; }

  struct Terms {
    Quat4 kappa_dd;   // κ''
    double chi;       // χ (constraint form)
    double r_dot;     // r'
    Vec3 A_Z;         // A in Z axes
    double gamma3;    // cos ϑ
  };

  Terms terms(const motion::SuspensionSample& z, const State& x) const {
    using namespace chelnokov;
    const Quat4 kap = x.head<4>(), dk = x.segment<4>(4);
    const double r = x[8];
    const double n = p_.n(), c = p_.c();
    Terms out;
    const Vec3 y3 = vertical(kap) / kap.squaredNorm();
    out.gamma3 = y3.z();
    out.A_Z = p_.lm * z.f_Z + Vec3(0.0, 0.0, gradient_force(p_, z.gm_r3, out.gamma3));
    const double A3 = out.A_Z.z();
    out.r_dot = p_.I3 > 0.0 ? torque_Y.z() / p_.I3 : 0.0;  // (1.5)
    const Quat4 w0 = pure(z.w_Z);
    const Quat4 Q1 = scalar_vector(-c * r * r + n * A3, z.dw_Z);
    const Quat4 Q2 = scalar_vector(-c * out.r_dot, n * out.A_Z - c * r * z.w_Z);
    const Quat4 T = -mul(w0, dk) + c * r * times_i3(dk) - 0.5 * mul(Q1, kap) - 0.5 * times_i3(mul(Q2, kap)) +
                    0.5 * n * mul(kap, pure(torque_Y));
    out.kappa_dd = constrained(kap, dk, T, out.chi);
    return out;
  }

  void derivative(double t, const State& x, State& dx) const {
    const Terms tm = terms(ref_(t), x);
    dx.head<4>() = x.segment<4>(4);
    dx.segment<4>(4) = tm.kappa_dd;
    dx[8] = tm.r_dot;
  }
  void project(State& x) const { chelnokov::project_unit(x.head<8>()); }

  // (1.4), second (closed) form, for the residual oracle.
  double chi_closed_form(const motion::SuspensionSample& z, const State& x) const {
    const Quat4 k = x.head<4>(), d = x.segment<4>(4);
    const Terms tm = terms(z, x);
    const double p0 = z.w_Z.x(), q0 = z.w_Z.y(), r0 = z.w_Z.z();
    const double A3 = tm.A_Z.z();
    const double lmw1 = tm.A_Z.x(), lmw2 = tm.A_Z.y();  // l m w1, l m w2 (g and U' are vertical)
    return -d.squaredNorm() - p0 * (k[0] * d[1] - k[1] * d[0] + k[2] * d[3] - k[3] * d[2]) -
           q0 * (k[0] * d[2] - k[2] * d[0] - k[1] * d[3] + k[3] * d[1]) -
           r0 * (k[0] * d[3] - k[3] * d[0] + k[1] * d[2] - k[2] * d[1]) -
           p_.n() * (lmw1 * (k[0] * k[2] + k[1] * k[3]) + lmw2 * (k[2] * k[3] - k[0] * k[1]) -
                     A3 * (k[1] * k[1] + k[2] * k[2]));
  }
  // (1.4), first form: ¼(ω°² − ω²) + ½ n (A3 − A3') with ω_Y = 2 κ̄∘κ' + κ̄∘ω°_Z∘κ.
  double chi_first_form(const motion::SuspensionSample& z, const State& x) const {
    using namespace chelnokov;
    const Quat4 k = x.head<4>(), d = x.segment<4>(4);
    const Terms tm = terms(z, x);
    const Vec3 w_Y = vec(2.0 * mul(conj(k), d) + mul(mul(conj(k), pure(z.w_Z)), k));
    const double A3p = tm.A_Z.dot(vertical(k));
    return 0.25 * (z.w_Z.squaredNorm() - w_Y.squaredNorm()) + 0.5 * p_.n() * (tm.A_Z.z() - A3p);
  }

  // From a rigid-body attitude/rate (q_IB, ω_B) and the trihedron Z: κ = ν̄∘s, 2κ' = κ∘ω_Y − ω°_Z∘κ, r = ω_Y3.
  static State kappa_from_body(const motion::SuspensionSample& z, const dynamics::Quat& q_IB, const Vec3& w_B) {
    using namespace chelnokov;
    const Quat4 k = from_eigen(z.q_IZ.conjugate() * q_IB);
    State x;
    x.head<4>() = k;
    x.segment<4>(4) = 0.5 * (mul(k, pure(w_B)) - mul(pure(z.w_Z), k));
    x[8] = w_B.z();
    return x;
  }
  static State aligned_state() {
    State x = State::Zero();
    x[0] = 1.0;
    return x;
  }

 private:
  ChelnokovParams p_;
  Reference ref_;
};

// (3.1)-(3.2) with M = 0: λ relative to Z (no r: Y' does not share the gyro frame's axial rotation).
template <class Reference>
class ChelnokovLambda {
 public:
  static constexpr int kStateSize = 8;
  using State = Eigen::Matrix<double, 8, 1>;
  using Quat4 = chelnokov::Quat4;
  using Vec3 = dynamics::Vec3;
  static constexpr const char* kName = "chelnokov-lambda";

  ChelnokovLambda(const ChelnokovParams& p, const Reference& ref) : p_(p), ref_(ref) {}

  const Reference& reference() const { return ref_; }
  Reference& reference() { return ref_; }

  Quat4 lambda_dd(const motion::SuspensionSample& z, const State& x, double& chi) const {
    using namespace chelnokov;
    const Quat4 l = x.head<4>(), dl = x.segment<4>(4);
    const double n = p_.n();
    const double gamma3 = vertical(l).z() / l.squaredNorm();
    const Vec3 A_Z = p_.lm * z.f_Z + Vec3(0.0, 0.0, gradient_force(p_, z.gm_r3, gamma3));
    const Quat4 T = -mul(pure(z.w_Z), dl) - 0.5 * mul(scalar_vector(n * A_Z.z(), z.dw_Z), l) -
                    0.5 * n * times_i3(mul(pure(A_Z), l));
    return constrained(l, dl, T, chi);
  }
  void derivative(double t, const State& x, State& dx) const {
    double chi;
    dx.head<4>() = x.segment<4>(4);
    dx.segment<4>(4) = lambda_dd(ref_(t), x, chi);
  }
  void project(State& x) const { chelnokov::project_unit(x); }

 private:
  ChelnokovParams p_;
  Reference ref_;
};

// (4.1)-(4.4) with M = 0: z = Y' relative to the non-rotating X (inertial axes), A_X = l m a_X + z3 dU'/dγ3.
template <class Reference>
class ChelnokovZ {
 public:
  static constexpr int kStateSize = 8;
  using State = Eigen::Matrix<double, 8, 1>;
  using Quat4 = chelnokov::Quat4;
  using Vec3 = dynamics::Vec3;
  static constexpr const char* kName = "chelnokov-z";

  ChelnokovZ(const ChelnokovParams& p, const Reference& ref) : p_(p), ref_(ref) {}

  const Reference& reference() const { return ref_; }
  Reference& reference() { return ref_; }

  // z'' = −¼Ω² z − ½ n (A_X∘z∘i3 + A3' z), ¼Ω² = Σ zj'² (4.3) — in the constraint form (identical on |z| = 1).
  Quat4 z_dd(const motion::SuspensionSample& s, const State& x, double& quarter_Omega2) const {
    using namespace chelnokov;
    const Quat4 q = x.head<4>(), dq = x.segment<4>(4);
    const double n = p_.n();
    const Vec3 y3 = vertical(q) / q.squaredNorm();  // in X
    const double gamma3 = y3.dot(s.up_I);
    const Vec3 A_X = p_.lm * s.f_I + gradient_force(p_, s.gm_r3, gamma3) * s.up_I;
    const double A3p = A_X.dot(y3);  // (4.4)
    const Quat4 T = -0.5 * n * (times_i3(mul(pure(A_X), q)) + A3p * q);
    double chi;
    const Quat4 dd = constrained(q, dq, T, chi);
    quarter_Omega2 = -chi;
    return dd;
  }
  void derivative(double t, const State& x, State& dx) const {
    double w2;
    dx.head<4>() = x.segment<4>(4);
    dx.segment<4>(4) = z_dd(ref_(t), x, w2);
  }
  void project(State& x) const { chelnokov::project_unit(x); }

  // z from a rigid body with r = 0 (μ = 1): z = s = q_IB, z' = ½ s∘ω_Y (ε' = c r = 0).
  static State z_from_body(const dynamics::Quat& q_IB, const Vec3& w_B) {
    using namespace chelnokov;
    State x;
    x.head<4>() = from_eigen(q_IB);
    x.segment<4>(4) = 0.5 * mul(x.head<4>(), pure(w_B));
    return x;
  }

 private:
  ChelnokovParams p_;
  Reference ref_;
};

}  // namespace gyrostab::models
