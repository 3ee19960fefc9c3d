// Splitting integrators for spinning rigid bodies: exact free symmetric-rotor flow + torque kicks.
//
// Hamiltonian in body momentum m = I w (Lie-Poisson form of Euler's equations, Magnus (1.84)), with a base
// axis b, a symmetry axis s and a remainder axis r (a permutation of the principal axes):
//   H = |m|²/(2 I_b) + (1/I_s - 1/I_b) m_s²/2   [symmetric rotor about s: exact, two rotations]
//     + (1/I_r - 1/I_b) m_r²/2                   [remainder: one exact rotation about r; empty if I_r = I_b]
//     + V(q)                                     [potential: a kick m += τ(q) dt, attitude frozen]
// The base is the axis of the middle moment and s the axis whose moment differs most from it: for a symmetric
// rotor (A, A, C) that is b = 1, s = 3 and no remainder; for an asymmetric body the middle-moment base gives the
// smallest error constant (Fassò 2003; measured on I = (1, 2, 3): 6.7x smaller for Strang, 290x for
// Yoshida-4, than base I1).
// Each piece is solved exactly, so |m| (and m3 when I1 = I2 and the torque has no axis-3 part) is kept
// to round-off and there is no stability limit from the spin or the nutation frequency — only the kick
// resonances h·ω_n ≈ 2πk, which step_validation.hpp keeps away from (h·ω_n ≤ 0.8·2π).
//
// Strang:    K(h/2) R(h/2) S(h) R(h/2) K(h/2)      second order, symplectic, time-reversible.
// Yoshida-4: Strang(w1 h) Strang(w0 h) Strang(w1 h), w1 = 1/(2 - 2^(1/3)), w0 = 1 - 2 w1; fourth order.
//
// A Model provides inertia() (principal I1, I2, I3, axis 3 the figure axis), body_torque(t, q) depending
// on attitude only, kHasTorque, and the rigid-body state layout of sim/models/rigid_body_state.hpp.
// Docs: docs/models/integrators.md#methods
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::dynamics {

template <class Model>
class RotorStrang {
 public:
  using State = typename Model::State;
  static constexpr const char* kName = "strang";

  explicit RotorStrang(const Model& model) : model_(model), inv_I_(model.inertia().cwiseInverse()) {
    const Vec3& I = model.inertia();
    // b: the middle moment (first such axis on ties); s: the other axis farthest from it; r: the last one.
    for (int i = 0; i < 3; ++i) {
      const int lo = (I[(i + 1) % 3] <= I[i]) + (I[(i + 2) % 3] <= I[i]);
      const int hi = (I[(i + 1) % 3] >= I[i]) + (I[(i + 2) % 3] >= I[i]);
      if (lo >= 1 && hi >= 1) {
        b_ = i;
        break;
      }
    }
    const int o1 = (b_ + 1) % 3, o2 = (b_ + 2) % 3;
    const bool o1_farther = std::abs(I[o1] - I[b_]) > std::abs(I[o2] - I[b_]);
    s_ = o1_farther ? o1 : o2;
    r_ = o1_farther ? o2 : o1;
    e_s_ = Vec3::Unit(s_);
    e_r_ = Vec3::Unit(r_);
  }

  void step(double t, double h, State& x) {
    Vec3 m = model_.inertia().cwiseProduct(x.template segment<3>(0));
    auto q = x.template segment<4>(3);
    substep(t, h, m, q);
    x.template segment<3>(0) = m.cwiseProduct(inv_I_);
    renormalize_cheap(q);
  }

  // One Strang step on (m, q); used by the Yoshida composition without converting back to w.
  // First same as last: a step's closing kick and the next step's opening kick see the same attitude, so the
  // torque is computed once (keyed on the attitude, for models whose torque depends on it alone).
  template <class Q>
  void substep(double t, double h, Vec3& m, Q&& q) const {
    if constexpr (Model::kHasTorque) m += (0.5 * h) * torque(t, q);
    remainder(0.5 * h, m, q);
    symmetric(h, m, q);
    remainder(0.5 * h, m, q);
    if constexpr (Model::kHasTorque) {
      cached_torque_ = model_.body_torque(t + h, q);
      cached_q_ = q;
      cache_valid_ = true;
      m += (0.5 * h) * cached_torque_;
    }
  }

 private:
  // Flow of |m|²/(2 I1) + (1/I3 - 1/I1) m3²/2. The first term is a Casimir, so the two rotations commute:
  // the body turns about m by |m| h / I1 (m fixed in body axes), then about e3 by (1/I3 - 1/I1) m3 h.
  // Flow of |m|²/(2 I_b) + (1/I_s - 1/I_b) m_s²/2. The first term is a Casimir, so the two rotations commute:
  // the body turns about m by |m| h / I_b (m fixed in body axes), then about e_s by (1/I_s - 1/I_b) m_s h.
  template <class Q>
  void symmetric(double h, Vec3& m, Q&& q) const {
    const double norm_m = m.norm();
    if (norm_m > 0.0) rotate_about_body_axis(q, m / norm_m, h * norm_m * inv_I_[b_]);
    turn(h * (inv_I_[s_] - inv_I_[b_]) * m[s_], s_, e_s_, m, q);
  }

  // Flow of (1/I_r - 1/I_b) m_r²/2: rotation about e_r; empty for a symmetric body.
  template <class Q>
  void remainder(double h, Vec3& m, Q&& q) const {
    const double k = inv_I_[r_] - inv_I_[b_];
    if (k == 0.0) return;
    turn(h * k * m[r_], r_, e_r_, m, q);
  }

  // The body turns by +phi about principal axis `axis`; the body components of the fixed vector m turn by
  // -phi about it.
  template <class Q>
  static void turn(double phi, int axis, const Vec3& e, Vec3& m, Q&& q) {
    // One sincos of the half angle serves the quaternion and, by the double-angle formulas, m.
    const double sh = std::sin(0.5 * phi), ch = std::cos(0.5 * phi);
    Eigen::Map<Quat> qq(q.data());
    qq = qq * Quat(ch, sh * e.x(), sh * e.y(), sh * e.z());
    const double c = 1.0 - 2.0 * sh * sh, s = 2.0 * sh * ch;
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    const double mi = m[i], mj = m[j];
    m[i] = c * mi + s * mj;
    m[j] = -s * mi + c * mj;
  }

  template <class Q>
  Vec3 torque(double t, const Q& q) const {
    if constexpr (requires { Model::kTorqueDependsOnAttitudeOnly; }) {
      if (Model::kTorqueDependsOnAttitudeOnly && cache_valid_ && cached_q_ == q) return cached_torque_;
    }
    return model_.body_torque(t, q);
  }

  const Model& model_;
  Vec3 inv_I_;
  mutable Vec3 cached_torque_{Vec3::Zero()};
  mutable Eigen::Vector4d cached_q_{Eigen::Vector4d::Zero()};
  mutable bool cache_valid_{false};
  int b_{0}, s_{2}, r_{1};
  Vec3 e_s_{Vec3::UnitZ()}, e_r_{Vec3::UnitY()};
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
