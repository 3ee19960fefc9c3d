// Precession ("engineering", "technical") model of the gimbal gyro — the reduced model P0.
//
// Book: Magnus §10.1-10.2, (10.19)-(10.20) and, on a rotating base, (10.21)-(10.22) with the inertia terms
// dropped: only the gyroscopic moments of the spin momentum H balance the applied moments.
//   H cosβ (β' + Ω_A2) + sinβ M3 = Q1          (outer axis)
//  -H (cosβ (α' + Ω1) - sinβ Ω_A3) = Q2         (inner axis)
// with Ω_A the base rate in outer-gimbal axes and Q1, Q2 the same motor, gravity and viscous moments as the
// full model (sim/models/gimbal_gyro.hpp). The two equations are solved for (α', β') — a 2×2 system
// because viscous friction involves the rates.
// State x = [α (rad), β (rad), H (N m s)]. No nutation, so no fast mode: the step is bounded by the
// precession ω^P ≈ |c|/H only.
// Validity (§10.1, docs/models/gimbal-gyro.md#precession-model-p0): symmetric rotor, constant spin, small
// nutation, large H; relative error of order ε = ω^P/ω^N. Singular at gimbal lock (cosβ = 0) without damping.
// Coulomb friction is not modelled here (the precession-with-Coulomb case (11.16) would need a set-valued
// solve).
// Oracle: tests/oracle/gimbal_gyro_test.cpp compares it with the full model and reports ε beside the error.
// Docs: docs/models/gimbal-gyro.md#precession-model-p0
#pragma once

#include <cmath>

#include "sim/models/gimbal_gyro.hpp"

namespace gyrostab::models {

template <class Base = FixedBase>
class GimbalGyroPrecession {
 public:
  static constexpr int kStateSize = 3;
  using State = Eigen::Matrix<double, 3, 1>;
  static constexpr const char* kName = "gimbal-gyro-precession";

  explicit GimbalGyroPrecession(const GimbalGyroParams& p = {}, const Base& base = {}) : p_(p), base_(base) {}

  GimbalTorques torques{};

  const GimbalGyroParams& params() const { return p_; }
  const Base& base() const { return base_; }

  static State make_state(double alpha, double beta, double H) { return State(alpha, beta, H); }

  void derivative(double t, const State& x, State& dx) const {
    const BaseSample b = base_(t);
    const double sa = std::sin(x[0]), ca = std::cos(x[0]);
    const double sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double H = x[2];
    const double a2 = b.w_B[1] * ca + b.w_B[2] * sa;
    const double a3 = -b.w_B[1] * sa + b.w_B[2] * ca;
    const double Q1 = torques.M1 + p_.Gs * cb * (ca * b.up_B[1] + sa * b.up_B[2]);
    const double Q2 = torques.M2 - p_.Gs * (cb * b.up_B[0] + sa * sb * b.up_B[1] - ca * sb * b.up_B[2]);
    // [ d1      H cosβ ] [α']   [Q1 - H cosβ Ω_A2 - sinβ M3      ]
    // [-H cosβ  d2     ] [β'] = [Q2 + H cosβ Ω1 - H sinβ Ω_A3    ]
    const double g = H * cb;
    const double r1 = Q1 - g * a2 - sb * torques.M3;
    const double r2 = Q2 + g * b.w_B[0] - H * sb * a3;
    const double det = p_.d1 * p_.d2 + g * g;
    dx[0] = (p_.d2 * r1 - g * r2) / det;
    dx[1] = (p_.d1 * r2 + g * r1) / det;
    dx[2] = torques.M3;
  }
  void project(State& /*x*/) const {}

 private:
  GimbalGyroParams p_;
  Base base_;
};

}  // namespace gyrostab::models
