// Splitting integrators for spinning rigid bodies: exact free symmetric-rotor flow + torque kicks.
//
// Hamiltonian in body momentum m = I w (Lie-Poisson form of Euler's equations, Magnus (1.84)):
//   H = |m|²/(2 I1) + (1/I3 - 1/I1) m3²/2   [symmetric rotor about axis 3: exact, two rotations]
//     + (1/I2 - 1/I1) m2²/2                  [remainder for I2 ≠ I1: one exact rotation about axis 2]
//     + V(q)                                 [potential: a kick m += τ(q) dt, attitude frozen]
// Each piece is solved exactly, so |m| (and m3 when I1 = I2 and the torque has no axis-3 part) is kept
// to round-off and there is no stability limit from the spin or the nutation frequency — only the kick
// resonances h·ω_n ≈ 2πk, which step_validation.hpp keeps away from (h·ω_n ≤ 0.8·2π).
//
// Strang:    K(h/2) R(h/2) S(h) R(h/2) K(h/2)      second order, symplectic, time-reversible.
// Yoshida-4: Strang(w1 h) Strang(w0 h) Strang(w1 h), w1 = 1/(2 - 2^(1/3)), w0 = 1 - 2 w1; fourth order.
//
// A Model provides inertia() (principal I1, I2, I3, axis 3 the figure axis), body_torque(t, q) depending
// on attitude only, kHasTorque, and the rigid-body state layout of sim/models/rigid_body_state.hpp.
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::dynamics {

template <class Model>
class RotorStrang {
 public:
  using State = typename Model::State;
  static constexpr const char* kName = "strang";

  explicit RotorStrang(const Model& model) : model_(model), inv_I_(model.inertia().cwiseInverse()) {}

  void step(double t, double h, State& x) {
    Vec3 m = model_.inertia().cwiseProduct(x.template segment<3>(0));
    auto q = x.template segment<4>(3);
    substep(t, h, m, q);
    x.template segment<3>(0) = m.cwiseProduct(inv_I_);
    renormalize_cheap(q);
  }

  // One Strang step on (m, q); used by the Yoshida composition without converting back to w.
  template <class Q>
  void substep(double t, double h, Vec3& m, Q&& q) const {
    if constexpr (Model::kHasTorque) m += (0.5 * h) * model_.body_torque(t, q);
    remainder(0.5 * h, m, q);
    symmetric(h, m, q);
    remainder(0.5 * h, m, q);
    if constexpr (Model::kHasTorque) m += (0.5 * h) * model_.body_torque(t + h, q);
  }

 private:
  // Flow of |m|²/(2 I1) + (1/I3 - 1/I1) m3²/2. The first term is a Casimir, so the two rotations commute:
  // the body turns about m by |m| h / I1 (m fixed in body axes), then about e3 by (1/I3 - 1/I1) m3 h.
  template <class Q>
  void symmetric(double h, Vec3& m, Q&& q) const {
    const double norm_m = m.norm();
    if (norm_m > 0.0) rotate_about_body_axis(q, m / norm_m, h * norm_m * inv_I_[0]);
    const double phi = h * (inv_I_[2] - inv_I_[0]) * m[2];
    rotate_about_body_axis(q, Vec3::UnitZ(), phi);
    const double c = std::cos(phi), s = std::sin(phi);
    // Body components of a fixed vector after the body turns by +phi about e3: Rz(-phi) m.
    m = Vec3(c * m[0] + s * m[1], -s * m[0] + c * m[1], m[2]);
  }

  // Flow of (1/I2 - 1/I1) m2²/2: rotation about e2; empty for a symmetric body.
  template <class Q>
  void remainder(double h, Vec3& m, Q&& q) const {
    const double k = inv_I_[1] - inv_I_[0];
    if (k == 0.0) return;
    const double phi = h * k * m[1];
    rotate_about_body_axis(q, Vec3::UnitY(), phi);
    const double c = std::cos(phi), s = std::sin(phi);
    m = Vec3(c * m[0] - s * m[2], m[1], s * m[0] + c * m[2]);  // Ry(-phi) m
  }

  const Model& model_;
  Vec3 inv_I_;
};

template <class Model>
class RotorYoshida4 {
 public:
  using State = typename Model::State;
  static constexpr const char* kName = "yoshida4";

  explicit RotorYoshida4(const Model& model) : model_(model), strang_(model) {}

  void step(double t, double h, State& x) {
    const double w1 = 1.0 / (2.0 - std::cbrt(2.0));
    const double w0 = 1.0 - 2.0 * w1;
    Vec3 m = model_.inertia().cwiseProduct(x.template segment<3>(0));
    auto q = x.template segment<4>(3);
    strang_.substep(t, w1 * h, m, q);
    strang_.substep(t + w1 * h, w0 * h, m, q);
    strang_.substep(t + (w1 + w0) * h, w1 * h, m, q);
    x.template segment<3>(0) = m.cwiseQuotient(model_.inertia());
    renormalize_cheap(q);
  }

 private:
  const Model& model_;
  RotorStrang<Model> strang_;
};

}  // namespace gyrostab::dynamics
