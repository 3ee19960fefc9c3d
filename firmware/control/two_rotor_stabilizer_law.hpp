// Stabilization-motor law of the two-rotor stabilizers (Magnus §14.3.4; docs/models/two-rotor-stabilizer.md):
//   gyro frame (Fig. 14.7):   M1^K = −k1 β − dK1 α'                      (β the linked cases' angle)
//   two-axis   (Fig. 14.8):   M1^K = −k1 β1 − dK1 α',  M2^K = σ k2 β2 − dK2 γ'
// — the single-rotor law (14.19) with rate damping, each frame's motor driven by the case angle of the gyro
// that precesses under that frame's torque (σ the spin sign of gyro II). The start-up check builds the closed
// loop's characteristic polynomial from what the law assumes about the plant and applies the Hurwitz test:
//   gyro frame: λ [ 2AB λ³ + (A D2 + 2B D1) λ² + (4H² + D1 D2) λ + 2H k1 ],  D1 = d1 + dK1, D2 = 2 d2 (TR3)
//   two-axis:   det(M λ² + C λ + K) = λ² P6(λ)  (sim/models/two_rotor_two_axis.hpp), expanded here over the 24
//               permutations of the 4×4 determinant of quadratics, then the Routh array of P6
// and refuses gains outside the stable region, giving the largest stable scale of (k1, k2) as the bound; the
// sampled rate loops also need dK T / A ≤ 0.5 (sampled_loop_limits.hpp).
// Signals: reads the case angle(s) and the frame rate(s); writes the frame torques, clipped at torque_limit_Nm.
// O(1), no heap, no exceptions. Test: tests/oracle/two_rotor_stabilizer_test.cpp.
// Docs: docs/models/two-rotor-stabilizer.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/control/config_check.hpp"
#include "firmware/control/sampled_loop_limits.hpp"

namespace gyrostab::firmware {

enum class TwoRotorKind : std::uint8_t { kGyroFrame, kTwoAxis };

struct TwoRotorStabilizerParams {
  TwoRotorKind kind{TwoRotorKind::kGyroFrame};
  // What the law assumes about the plant (the check only).
  double A{4.0};         // about axis 1 [kg m²]
  double B{0.5};         // gyro frame: one case about its axis; two-axis: about axis 2 [kg m²]
  double J{0.5};         // two-axis: one case about its axis [kg m²]
  double H{100.0};       // one rotor [N m s]
  double d1{0.0};        // passive bearing damping, frame 1 [N m s/rad]
  double d2{0.5};        // gyro frame: each case bearing; two-axis: frame 2 bearing [N m s/rad]
  double c{2.0};         // two-axis: each case bearing [N m s/rad]
  double spin_sign{-1};  // σ of gyro II
  // Gains.
  double k1{2000.0}, k2{0.0};  // per rad of case angle [N m/rad]
  double dK1{20.0}, dK2{0.0};  // per rad/s of frame rate [N m s/rad]
  double torque_limit_Nm{200.0};
};

// Polynomial a[0] + a[1] λ + ... + a[degree] λ^degree.
struct TwoRotorPoly {
  double a[9]{};
  int degree{0};
};

namespace two_rotor_detail {

// q(λ) = q0 + q1 λ + q2 λ² entries of M λ² + C λ + K.
struct Quad {
  double q0, q1, q2;
};

inline void mul_add(const Quad (&m)[4][4], const int (&perm)[4], double sign, double (&out)[9]) {
  double prod[9] = {1.0, 0, 0, 0, 0, 0, 0, 0, 0};
  int deg = 0;
  for (int r = 0; r < 4; ++r) {
    const Quad& e = m[r][perm[r]];
    double next[9] = {};
    for (int i = 0; i <= deg; ++i) {
      next[i] += prod[i] * e.q0;
      next[i + 1] += prod[i] * e.q1;
      next[i + 2] += prod[i] * e.q2;
    }
    deg += 2;
    for (int i = 0; i <= deg; ++i) prod[i] = next[i];
  }
  for (int i = 0; i < 9; ++i) out[i] += sign * prod[i];
}

}  // namespace two_rotor_detail

// The closed loop's characteristic polynomial without its zero roots (the frame angles are not fed back):
// the cubic of (TR3), or P6 of the two-axis stabilizer.
inline TwoRotorPoly two_rotor_characteristic(const TwoRotorStabilizerParams& p) {
  TwoRotorPoly r;
  const double H = p.H;
  if (p.kind == TwoRotorKind::kGyroFrame) {
    const double D1 = p.d1 + p.dK1, D2 = 2.0 * p.d2;
    r.degree = 3;
    r.a[3] = 2.0 * p.A * p.B;
    r.a[2] = p.A * D2 + 2.0 * p.B * D1;
    r.a[1] = 4.0 * H * H + D1 * D2;
    r.a[0] = 2.0 * H * p.k1;
    return r;
  }
  using two_rotor_detail::Quad;
  const double s = p.spin_sign, J = p.J;
  // Rows/columns (α, γ, β1, β2) of sim/models/two_rotor_two_axis.hpp.
  const Quad m[4][4] = {
      {{0, p.d1 + p.dK1, p.A}, {0, (1 + s) * H, 0}, {p.k1, H, 0}, {0, 0, J}},
      {{0, -(1 + s) * H, 0}, {0, p.d2 + p.dK2, p.B}, {0, 0, J}, {-s * p.k2, -s * H, 0}},
      {{0, -H, 0}, {0, 0, J}, {0, p.c, J}, {0, 0, 0}},
      {{0, 0, J}, {0, s * H, 0}, {0, 0, 0}, {0, p.c, J}},
  };
  double det[9] = {};
  // The 24 permutations of {0,1,2,3} with their signs (Heap's order is not needed: listed).
  static constexpr int kPerm[24][4] = {
      {0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 1, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {0, 3, 2, 1},
      {1, 0, 2, 3}, {1, 0, 3, 2}, {1, 2, 0, 3}, {1, 2, 3, 0}, {1, 3, 0, 2}, {1, 3, 2, 0},
      {2, 0, 1, 3}, {2, 0, 3, 1}, {2, 1, 0, 3}, {2, 1, 3, 0}, {2, 3, 0, 1}, {2, 3, 1, 0},
      {3, 0, 1, 2}, {3, 0, 2, 1}, {3, 1, 0, 2}, {3, 1, 2, 0}, {3, 2, 0, 1}, {3, 2, 1, 0}};
  for (const auto& perm : kPerm) {
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) inversions += perm[i] > perm[j] ? 1 : 0;
    two_rotor_detail::mul_add(m, perm, (inversions % 2 == 0) ? 1.0 : -1.0, det);
  }
  r.degree = 6;
  for (int i = 0; i <= 6; ++i) r.a[i] = det[i + 2];  // det[0] = det[1] = 0: the λ² factor
  return r;
}

// Routh-Hurwitz: every root in the open left half-plane iff the first column of the Routh array is positive
// (a[degree] > 0 assumed by the caller's sign convention; the arrays are normalised to it). NaN → false.
inline bool routh_stable(const TwoRotorPoly& p) {
  const int n = p.degree;
  if (!(p.a[n] > 0.0)) return false;
  double row0[5] = {}, row1[5] = {};
  for (int i = 0; 2 * i <= n; ++i) row0[i] = p.a[n - 2 * i];
  for (int i = 0; 2 * i + 1 <= n; ++i) row1[i] = p.a[n - 2 * i - 1];
  for (int k = 0; k < n; ++k) {
    if (!(row1[0] > 0.0)) return false;
    double next[5] = {};
    for (int i = 0; i < 4; ++i) next[i] = row0[i + 1] - row0[0] * row1[i + 1] / row1[0];
    for (int i = 0; i < 5; ++i) {
      row0[i] = row1[i];
      row1[i] = next[i];
    }
    if (k == n - 2) return row1[0] > 0.0;  // the last row: a[0]'s
  }
  return true;
}

// The gains scaled by g (k1, k2 → g k1, g k2).
inline bool two_rotor_stable_at(TwoRotorStabilizerParams p, double g) {
  p.k1 *= g;
  p.k2 *= g;
  return routh_stable(two_rotor_characteristic(p));
}

// Largest g with (g k1, g k2) stable, by bisection from g = 1 (60 halvings: relative 1e-18 of the bracket),
// assuming the region is star-shaped about 0 along the ray (true of (TR4) and observed for P6); 0 if even
// small gains are unstable, +inf if stable up to g = 1e6.
inline double two_rotor_gain_scale_max(const TwoRotorStabilizerParams& p) {
  if (!(p.k1 > 0.0) && !(p.k2 > 0.0)) return 0.0;
  double lo = 0.0, hi = 1.0;
  if (two_rotor_stable_at(p, 1.0)) {
    lo = 1.0;
    while (two_rotor_stable_at(p, hi)) {
      lo = hi;
      hi *= 2.0;
      if (hi > 1e6) return INFINITY;
    }
  }
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (two_rotor_stable_at(p, mid)) lo = mid; else hi = mid;
  }
  return lo;
}

// Start-up check at the control period T [s].
inline ConfigCheck check_two_rotor_stabilizer(const TwoRotorStabilizerParams& p, double T) {
  const bool two_axis = p.kind == TwoRotorKind::kTwoAxis;
  if (!(p.A > 0.0) || !(p.B > 0.0) || !(p.H > 0.0) || !(p.d1 >= 0.0) || !(p.d2 >= 0.0) ||
      (two_axis && (!(p.J > 0.0) || !(p.A > p.J) || !(p.B > p.J) || !(p.c >= 0.0))))
    return ConfigCheck::refused("two-rotor stabilizer: plant A, B, H (J < A, B) must be > 0, damping >= 0");
  if (!(p.spin_sign == 1.0 || p.spin_sign == -1.0))
    return ConfigCheck::refused("two-rotor stabilizer: spin_sign must be +1 or -1", p.spin_sign);
  if (!(p.k1 > 0.0) || !std::isfinite(p.k1))
    return ConfigCheck::refused("two-rotor stabilizer: k1 must be > 0 (the case angle must drive motor 1)", p.k1);
  if (two_axis && (!(p.k2 > 0.0) || !std::isfinite(p.k2)))
    return ConfigCheck::refused("two-rotor stabilizer: k2 must be > 0 (two-axis)", p.k2);
  if (!(p.dK1 >= 0.0) || !(p.dK2 >= 0.0) || !std::isfinite(p.dK1) || !std::isfinite(p.dK2))
    return ConfigCheck::refused("two-rotor stabilizer: rate gains dK1, dK2 must be finite and >= 0");
  if (!(p.torque_limit_Nm > 0.0) || !std::isfinite(p.torque_limit_Nm))
    return ConfigCheck::refused("two-rotor stabilizer: torque_limit_Nm must be > 0", p.torque_limit_Nm);
  if (p.dK1 > max_sampled_damping(p.A, T))
    return ConfigCheck::refused("two-rotor stabilizer: dK1 T / A > 0.5, the sampled rate loop rings", p.dK1, 0.0,
                                max_sampled_damping(p.A, T));
  if (two_axis && p.dK2 > max_sampled_damping(p.B, T))
    return ConfigCheck::refused("two-rotor stabilizer: dK2 T / B > 0.5, the sampled rate loop rings", p.dK2, 0.0,
                                max_sampled_damping(p.B, T));
  if (!routh_stable(two_rotor_characteristic(p))) {
    const double g = two_rotor_gain_scale_max(p);
    return ConfigCheck::refused(
        two_axis ? "two-rotor two-axis stabilizer: (k1, k2) outside the Hurwitz region of P6; upper = the "
                   "largest stable k1 at this k2/k1"
                 : "gyro frame: k1 >= (A D2 + 2B D1)(4H^2 + D1 D2)/(4ABH) (TR4), the nutation grows; upper = "
                   "that bound",
        p.k1, 0.0, g * p.k1);
  }
  return ConfigCheck::accepted();
}

struct TwoRotorTorques {
  double M1{0.0}, M2{0.0};  // [N m]
  bool saturated{false};
};

// case1/rate1: the axis-1 loop's case angle [rad] and frame rate [rad/s]; case2/rate2 the axis-2 loop's
// (two-axis only).
inline TwoRotorTorques two_rotor_torques(const TwoRotorStabilizerParams& p, double case1, double rate1,
                                         double case2, double rate2) {
  TwoRotorTorques t;
  const double L = p.torque_limit_Nm;
  double M1 = -p.k1 * case1 - p.dK1 * rate1;
  double M2 = p.kind == TwoRotorKind::kTwoAxis ? p.spin_sign * p.k2 * case2 - p.dK2 * rate2 : 0.0;
  if (std::fabs(M1) > L || std::fabs(M2) > L) t.saturated = true;
  t.M1 = M1 > L ? L : (M1 < -L ? -L : M1);
  t.M2 = M2 > L ? L : (M2 < -L ? -L : M2);
  return t;
}

}  // namespace gyrostab::firmware
