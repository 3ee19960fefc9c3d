// Two-rotor gyro frame ("Kreiselrahmen", Magnus §14.3.4, Fig. 14.7): two identical gyros in one outer frame
// that turns about axis 1 (the stabilized axis, frame angle α relative to the base); each gyro's case turns
// about a case axis parallel to axis 2; the cases are linked (gears or a rod) so that β^II = s β^I, and the
// rotors spin with H^II = σ H^I. The book's gyro frame is σ = −1, s = −1 (counter-rotating rotors, mirrored
// cases); σ = +1, s = +1 (co-rotating, cases moving together) is one gyro of spin 2H and case inertia 2B: the
// single-rotor single-axis stabilizer, kept in the same code for the comparison. A stabilization motor on the
// frame (M1^K, input) is driven by the case angle in the firmware (M1^K = −k β − d_K α', as the single-rotor law
// (14.19) plus rate damping).
//
// Derivation (small angles, constant spin, Magnus (14.20) / (15.1) for one gyro on a base turning at
// Ω = (Ω1, Ω2, Ω3) in base axes): rotor axis of gyro i, n_i ≈ e3 + β_i e1 − α e2, spin momentum h_i n_i; its
// absolute rate of change gives, about the frame axis 1 and about its case axis 2,
//   frame:   h_i (β_i' + Ω2 + Ω3 α)                       case i:  B (β_i'' + Ω2') − h_i (α' + Ω1 − Ω3 β_i)
// The frame equation sums both gyros; the link's torque Q_i on case i does no work, Q_I δβ^I + Q_II δβ^II = 0,
// so Q_I = −s Q_II and the generalized equation of β = β^I is case I + s · case II:
//   A (α'' + Ω1') + Σ_i h_i (β_i' + Ω2 + Ω3 α) = M1^S + M1^K − d1 α'
//   Σ_i s_i [B (β_i'' + Ω2') − h_i (α' + Ω1 − Ω3 β_i)] = Σ_i s_i M2_i − 2 d2 β'         (s_I = 1, s_II = s)
// Gyro frame (σ = s = −1, h_I = H): the Ω2 and Ω3 α terms of the frame cancel, the B Ω2' and H Ω3 β of the
// cases cancel, leaving
//   (TR1)  A α'' + 2H β' + d1 α' = M1^S + M1^K − A Ω1'
//          2B β'' − 2H α' + 2 d2 β' = M2^S + 2H Ω1            (M2^S on case I)
// A base rotation about 2 moves nothing (the two H Ω2 are a bending moment in the frame); about 3 the two
// H Ω3 β_i on the cases are equal and opposite in the generalized equation: the link carries them,
//   (TR2)  link torque on case I  Q = B Ω2' + H Ω3 β − ½ M2^S    (exact within the linear model)
// Single rotor (σ = s = +1): 2H Ω2 and 2H Ω3 α act on the frame, 2B Ω2' and 2H Ω3 β on the case.
// Closed loop M1^K = −k β − d_K α', fixed base (D1 = d1 + d_K, D2 = 2 d2):
//   (TR3)  λ [ 2AB λ³ + (A D2 + 2B D1) λ² + (4H² + D1 D2) λ + 2H k ] = 0
// the λ = 0 root is the frame angle's neutral equilibrium (not fed back; cf. (14.29)); stable iff
//   (TR4)  k < k_max = (A D2 + 2B D1)(4H² + D1 D2) / (4 A B H)
// Constant M1^S: β → M1^S/k, and the frame turns by α∞ − α0 = D2 M1^S/(2H k) while the case deflects.
// Constant Ω1: the frame stays fixed in space, α' → −Ω1, with β → D1 Ω1/k.
//
// State: x = [α (rad), β (rad), α' (rad/s), β' (rad/s)], α the frame angle about 1 and β = β^I the case
//   angle of gyro I about 2, both relative to the base/frame.
// Parameters (SI): A frame + both gyros about axis 1 [kg m²], B one case + rotor about its case axis [kg m²],
//   H one rotor's spin momentum [N m s], d1 frame bearing viscous [N m s/rad], d2 each case bearing viscous
//   [N m s/rad], spin_sign σ, link_sign s (±1).
// Inputs (held): M1S disturbance on the frame, M1K motor torque on the frame, M2S disturbance on case I [N m].
// Assumptions: small α, β (linear in the angles, products of base rates and angles kept as in (15.1));
//   constant spin; rigid frame, rigid backlash-free link; the rotors' transverse inertia is in A and B;
//   products of base rates without angles (centrifugal terms of the cases) neglected, as in (15.1).
// Integrator: any (Rk4); the linear system has the nutation 2H/sqrt(2AB) = H/sqrt(AB) as fastest mode.
// Oracle: tests/oracle/two_rotor_stabilizer_test.cpp. Docs: docs/models/two-rotor-stabilizer.md
#pragma once

#include <Eigen/Core>

#include "sim/models/base_motion.hpp"

namespace gyrostab::models {

struct TwoRotorFrameParams {
  double A{4.0};         // frame + both gyros about axis 1 [kg m²]
  double B{0.5};         // one case + rotor about its case axis (∥ 2) [kg m²]
  double H{100.0};       // one rotor's spin momentum [N m s]
  double d1{0.0};        // frame bearing viscous [N m s/rad]
  double d2{0.5};        // each case bearing viscous [N m s/rad]
  double spin_sign{-1};  // σ: H^II = σ H^I
  double link_sign{-1};  // s: β^II = s β^I

  const char* invalid_reason() const {
    if (!(A > 0.0) || !(B > 0.0) || !(H > 0.0)) return "A, B, H must be > 0";
    if (!(d1 >= 0.0) || !(d2 >= 0.0)) return "bearing damping d1, d2 must be >= 0";
    if (!(spin_sign == 1.0 || spin_sign == -1.0) || !(link_sign == 1.0 || link_sign == -1.0))
      return "spin_sign and link_sign must be +1 or -1";
    return nullptr;
  }
};

// A base turning at a constant rate (base axes) from t = 0.
struct ConstantRateBase {
  dynamics::Vec3 w_B{dynamics::Vec3::Zero()};  // [rad/s]
  BaseSample operator()(double /*t*/) const { return {w_B, dynamics::Vec3::Zero(), dynamics::Vec3::UnitZ()}; }
};

struct TwoRotorFrameInputs {
  double M1S{0.0};  // disturbance on the frame, axis 1 [N m]
  double M1K{0.0};  // stabilization motor on the frame [N m]
  double M2S{0.0};  // disturbance on case I, axis 2 [N m]
};

template <class Base = FixedBase>
class TwoRotorGyroFrame {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  static constexpr int kAlpha = 0, kBeta = 1, kAlphaRate = 2, kBetaRate = 3;

  explicit TwoRotorGyroFrame(const TwoRotorFrameParams& p = {}, const Base& base = {}) : p_(p), base_(base) {}

  TwoRotorFrameInputs inputs{};

  const TwoRotorFrameParams& params() const { return p_; }
  const Base& base() const { return base_; }

  static State make_state(double alpha, double beta, double alpha_rate, double beta_rate) {
    State x;
    x << alpha, beta, alpha_rate, beta_rate;
    return x;
  }

  // Each gyro's terms are formed separately and summed, so that the cancellations of (TR1) happen in the
  // arithmetic (to round-off), not by having been simplified away.
  void derivative(double t, const State& x, State& dx) const {
    const BaseSample b = base_(t);
    const double W1 = b.w_B[0], W2 = b.w_B[1], W3 = b.w_B[2];
    const double alpha = x[kAlpha], beta = x[kBeta], ar = x[kAlphaRate], br = x[kBetaRate];
    const double h[2] = {p_.H, p_.spin_sign * p_.H};
    const double s[2] = {1.0, p_.link_sign};
    double frame_gyro = 0.0, case_gen = 0.0;  // Σ h_i(β_i' + Ω2 + Ω3 α); Σ s_i[B Ω2' − h_i(α' + Ω1 − Ω3 β_i)]
    for (int i = 0; i < 2; ++i) {
      frame_gyro += h[i] * (s[i] * br + W2 + W3 * alpha);
      case_gen += s[i] * (p_.B * b.dw_B[1] - h[i] * (ar + W1 - W3 * s[i] * beta));
    }
    const double M1 = inputs.M1S + inputs.M1K - p_.d1 * ar;
    const double case_torque = inputs.M2S - 2.0 * p_.d2 * br;  // Σ s_i M2_i − d2 Σ s_i² β'
    dx[kAlpha] = ar;
    dx[kBeta] = br;
    dx[kAlphaRate] = (M1 - frame_gyro) / p_.A - b.dw_B[0];
    dx[kBetaRate] = (case_torque - case_gen) / (2.0 * p_.B);  // Σ s_i² B = 2B
  }
  void project(State&) const {}

  // Torque the link puts on case I about its axis [N m] (equal to −s × the one on case II): case I's own
  // equation, B(β'' + Ω2') − H(α' + Ω1 − Ω3 β) = M2S − d2 β' + Q, solved for Q with β'' from derivative().
  double link_torque(double t, const State& x) const {
    State dx;
    derivative(t, x, dx);
    const BaseSample b = base_(t);
    const double lhs = p_.B * (dx[kBetaRate] + b.dw_B[1]) -
                       p_.H * (x[kAlphaRate] + b.w_B[0] - b.w_B[2] * x[kBeta]);
    return lhs - inputs.M2S + p_.d2 * x[kBetaRate];
  }

 private:
  TwoRotorFrameParams p_;
  Base base_;
};

// (TR3) without the λ factor: a3 λ³ + a2 λ² + a1 λ + a0, for M1^K = −k β − dK α' on a fixed base, for either
// arrangement (σ s = +1 for both: the gyro frame and the single rotor of 2H, 2B have the same equations there).
struct Cubic {
  double a3, a2, a1, a0;
};
inline Cubic gyro_frame_characteristic(const TwoRotorFrameParams& p, double k, double dK) {
  const double D1 = p.d1 + dK, D2 = 2.0 * p.d2, Hs = 2.0 * p.H, Bs = 2.0 * p.B;
  return {p.A * Bs, p.A * D2 + Bs * D1, Hs * Hs + D1 * D2, Hs * k};
}
// (TR4) [N m/rad].
inline double gyro_frame_k_max(const TwoRotorFrameParams& p, double dK) {
  const Cubic c = gyro_frame_characteristic(p, 0.0, dK);
  return c.a2 * c.a1 / (c.a3 * 2.0 * p.H);
}

}  // namespace gyrostab::models
