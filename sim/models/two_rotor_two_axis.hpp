// Two-rotor two-axis stabilizer (Magnus §14.3.4, Fig. 14.8): a platform in two frames — the outer frame turns
// about axis 1 (angle α), the inner frame (the platform) about axis 2 (angle γ) — carries two gyros whose
// rotors spin along axis 3 with H^I = H, H^II = σ H (σ = −1: counter-rotating, the book's arrangement;
// σ = +1: co-rotating, kept for the comparison). Gyro I's case turns about an axis parallel to 2 (angle β1),
// gyro II's about an axis parallel to 1 (angle β2), both relative to the platform. A motor on each frame
// (inputs M1K, M2K) is driven by the gyros' case angles in the firmware
// (firmware/control/two_rotor_stabilizer_law.hpp: M1^K = −k1 β1 − d_K1 α', M2^K = σ k2 β2 − d_K2 γ').
//
// Derivation (small angles, fixed base, constant spin): rotor axes n_I ≈ e3 + (γ + β1) e1 − α e2,
// n_II ≈ e3 + γ e1 − (α + β2) e2; the generalized gyroscopic forces are the components of Σ h_i n_i' along
// each coordinate's axis, q = (α, γ, β1, β2):
//   α :  A α'' + J β2''           + (1 + σ) H γ' + H β1'   + d1 α' = M1^S + M1^K
//   γ :  B γ'' + J β1''           − (1 + σ) H α' − σ H β2' + d2 γ' = M2^S + M2^K
//   β1:  J (γ'' + β1'')           − H α'                    + c β1' = 0
//   β2:  J (α'' + β2'')           + σ H γ'                  + c β2' = 0
// (A, B the inertias of everything about axes 1 and 2, J one case + rotor about its case axis, c each case
// bearing's viscous damping). Counter-rotating (σ = −1): the platform's own gyroscopic coupling (1 + σ) H
// vanishes — the total spin is zero, which is the point of the arrangement on a moving base — and the axis-1
// loop (α, β1) and the axis-2 loop (γ, β2) are coupled only through the case inertia J.
// Characteristic equation: det(M λ² + C λ + K) = 0 (M, C, K below); the frame angles α, γ are not fed back,
// so it is λ² P6(λ) = 0 with the sextic P6 of two_rotor_characteristic() (firmware/control/
// two_rotor_stabilizer_law.hpp). J → 0, σ = −1: P6 factors into two quadratics of the form
// (J→0)  c A λ² + (c d1 + H²) λ + H k1   and the same with B, d2, k2 — stable for all k1, k2 > 0.
//
// State: x = [α, γ, β1, β2 (rad), α', γ', β1', β2' (rad/s)].
// Parameters (SI): A, B [kg m²] about axes 1, 2 (everything inside the frame), J [kg m²], H [N m s],
//   d1, d2 frame bearings and c each case bearing [N m s/rad], spin_sign σ.
// Inputs (held): M1S, M2S disturbances and M1K, M2K motor torques on the frames [N m].
// Assumptions: small angles; fixed base; constant spins; the case inertias about the other axes are in A, B;
//   equal cases (J, c); rigid frames.
// Oracle: tests/oracle/two_rotor_stabilizer_test.cpp. Docs: docs/models/two-rotor-stabilizer.md
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace gyrostab::models {

struct TwoRotorTwoAxisParams {
  double A{4.0};         // about axis 1, everything inside the outer frame [kg m²]
  double B{3.0};         // about axis 2, platform + gyros [kg m²]
  double J{0.5};         // one case + rotor about its case axis [kg m²]
  double H{100.0};       // one rotor's spin momentum [N m s]
  double d1{0.0};        // outer frame bearing [N m s/rad]
  double d2{0.0};        // inner frame bearing [N m s/rad]
  double c{2.0};         // each case bearing [N m s/rad]
  double spin_sign{-1};  // σ: H^II = σ H

  const char* invalid_reason() const {
    if (!(J > 0.0) || !(A > J) || !(B > J) || !(H > 0.0)) return "need H > 0 and A > J > 0, B > J";
    if (!(d1 >= 0.0) || !(d2 >= 0.0) || !(c >= 0.0)) return "damping d1, d2, c must be >= 0";
    if (!(spin_sign == 1.0 || spin_sign == -1.0)) return "spin_sign must be +1 or -1";
    return nullptr;
  }
};

struct TwoRotorTwoAxisInputs {
  double M1S{0.0}, M2S{0.0};  // disturbances on the frames [N m]
  double M1K{0.0}, M2K{0.0};  // motor torques on the frames [N m]
};

// The linear equations M q'' + C q' + K q = f of the header; K from the motors' case-angle gains (the firmware
// law's, for the linearisation of the closed loop), dK rate gains added to C.
struct TwoRotorTwoAxisMatrices {
  Eigen::Matrix4d M, C, K;
};
inline TwoRotorTwoAxisMatrices two_axis_matrices(const TwoRotorTwoAxisParams& p, double k1 = 0.0,
                                                 double k2 = 0.0, double dK1 = 0.0, double dK2 = 0.0) {
  const double H = p.H, s = p.spin_sign, J = p.J;
  TwoRotorTwoAxisMatrices m;
  m.M << p.A, 0, 0, J,  //
      0, p.B, J, 0,     //
      0, J, J, 0,       //
      J, 0, 0, J;
  m.C << p.d1 + dK1, (1 + s) * H, H, 0,  //
      -(1 + s) * H, p.d2 + dK2, 0, -s * H,  //
      -H, 0, p.c, 0,                        //
      0, s * H, 0, p.c;
  m.K.setZero();
  m.K(0, 2) = k1;       // M1^K = −k1 β1
  m.K(1, 3) = -s * k2;  // M2^K = σ k2 β2
  return m;
}

// The closed loop's state matrix (x = [q; q']), for eigenvalues.
inline Eigen::Matrix<double, 8, 8> two_axis_state_matrix(const TwoRotorTwoAxisMatrices& m) {
  Eigen::Matrix<double, 8, 8> S = Eigen::Matrix<double, 8, 8>::Zero();
  const Eigen::Matrix4d Mi = m.M.inverse();
  S.block<4, 4>(0, 4).setIdentity();
  S.block<4, 4>(4, 0) = -Mi * m.K;
  S.block<4, 4>(4, 4) = -Mi * m.C;
  return S;
}

class TwoRotorTwoAxis {
 public:
  static constexpr int kStateSize = 8;
  using State = Eigen::Matrix<double, 8, 1>;
  static constexpr int kAlpha = 0, kGamma = 1, kBeta1 = 2, kBeta2 = 3;
  static constexpr int kAlphaRate = 4, kGammaRate = 5, kBeta1Rate = 6, kBeta2Rate = 7;

  explicit TwoRotorTwoAxis(const TwoRotorTwoAxisParams& p = {})
      : p_(p), m_(two_axis_matrices(p)), Minv_(m_.M.inverse()) {}

  TwoRotorTwoAxisInputs inputs{};
  const TwoRotorTwoAxisParams& params() const { return p_; }

  void derivative(double /*t*/, const State& x, State& dx) const {
    Eigen::Vector4d f;
    f << inputs.M1S + inputs.M1K, inputs.M2S + inputs.M2K, 0.0, 0.0;
    f.noalias() -= m_.C * x.tail<4>();
    dx.head<4>() = x.tail<4>();
    dx.tail<4>().noalias() = Minv_ * f;
  }
  void project(State&) const {}

 private:
  TwoRotorTwoAxisParams p_;
  TwoRotorTwoAxisMatrices m_;
  Eigen::Matrix4d Minv_;
};

}  // namespace gyrostab::models
