// Steering laws of a single-gimbal CMG cluster (Magnus §14.4, (14.45): the gimbal rate turns the rotor's
// momentum, the carrier takes the reaction; docs/models/cmg-cluster.md#steering-laws): the gimbal rates ν that
// make the cluster put the torque u on the spacecraft.
//
// CMG i: gimbal axis g_i, spin axis s_i(δ) = cos δ s0_i + sin δ (g_i × s0_i), torque axis t_i = g_i × s_i,
// rotor momentum h. The cluster's momentum h Σ s_i changes at A ν with A = h [t_1 … t_N] (3 × N), and the
// spacecraft takes −A ν: so ν = −A⁺ u.
//   pseudo_inverse       A⁺ = Aᵀ (A Aᵀ)⁻¹ (Moore–Penrose, the least-squares gimbal rates); fails where
//                        det(A Aᵀ) = 0: the singular directions are those the cluster cannot torque about.
//   singularity_robust   A⁺ = Aᵀ (A Aᵀ + λ I)⁻¹, λ = λ0 exp(−μ det(T Tᵀ)) (Nakamura–Hanafusa; Wie's
//                        exponential schedule): a torque error near a singularity instead of unbounded rates.
//   generalized_singularity_robust   A# = Aᵀ (A Aᵀ + λ E)⁻¹, E = [[1, ε3, ε2], [ε3, 1, ε1], [ε2, ε1, 1]],
//                        ε_i = ε0 sin(ω t + φ_i), φ = (0, π/2, π) (Wie, Bailey, Heiberg 2001): the off-diagonal
//                        dither turns a demand along the singular direction u_s into a small demand off it,
//                        which A# maps onto rates (Aᵀ(AAᵀ + λI)⁻¹ u_s = 0: the plain robust inverse cannot).
//                        E is positive definite for every t when ε0 < 1/2 (Gershgorin: its eigenvalues lie in
//                        [1 − 2ε0, 1 + 2ε0], and all ε_i = −ε0 reaches 1 − 2ε0), so A Aᵀ + λ E stays invertible
//                        with its smallest eigenvalue ≥ λ (1 − 2ε0): check() refuses ε0 ≥ 1/2. t is the caller's
//                        tick count times the tick period (deterministic: no clock is read).
// Computed with T = A/h (dimensionless): ν = −(1/h) Tᵀ (T Tᵀ + λ I)⁻¹ u, and the singularity measure
// m = det(T Tᵀ) = det(A Aᵀ)/h⁶, so λ0, μ need no unit. The pseudo-inverse refuses to invert where
// m ≤ singular_floor (ν = 0, `singular` set): at the singular configuration it cannot give a torque along
// the singular direction, and the rates it would give just before diverge as 1/σ_min.
// Rate limit: when the largest |ν_i| exceeds max_rate, all ν_i are scaled by the same factor (the torque
// keeps its direction and loses magnitude).
// O(N) with a 3 × 3 solve by the adjugate, no heap. Transcendentals from firmware/math/deterministic_math.hpp.
// Tests: tests/oracle/cmg_cluster_test.cpp. Docs: docs/models/cmg-cluster.md#steering-laws
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/control/config_check.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

inline constexpr int kMaxCmgUnits = 4;

// The cluster as the law knows it.
struct CmgArray {
  int count{4};
  double gimbal_axis[kMaxCmgUnits][3]{};  // g_i, unit, body axes
  double spin_axis0[kMaxCmgUnits][3]{};   // s0_i, unit, ⟂ g_i
  double h{5.0};                          // rotor momentum of each CMG [N m s]
};

enum class SteeringLaw : std::uint8_t { kPseudoInverse, kSingularityRobust, kGeneralizedSingularityRobust };

// The dither's phases φ_i (Wie, Bailey, Heiberg 2001): ε_1 = −ε_3 = ε0 sin ωt and ε_2 = ε0 cos ωt, a quarter
// period apart, so E never returns to I (at every t one |ε_i| ≥ ε0/√2).
inline constexpr double kDitherPhase[3] = {0.0, 1.5707963267948966, 3.141592653589793};
// The sampled dither must be resolved: ω T_c ≤ 0.5 (at least 12 samples per period).
inline constexpr double kMaxDitherStep = 0.5;

struct SteeringParams {
  SteeringLaw law{SteeringLaw::kSingularityRobust};
  double lambda0{0.01};          // λ0 [-]
  double mu{10.0};               // μ [-]
  double max_rate{1.0};          // gimbal rate limit [rad/s]
  double singular_floor{1e-10};  // the pseudo-inverse's smallest invertible det(T Tᵀ) [-]
  double dither_amplitude{0.01};                 // ε0 of the generalized inverse, < 1/2 [-]
  double dither_frequency{1.5707963267948966};  // ω of the generalized inverse [rad/s]
};

inline bool is_robust(SteeringLaw law) {
  return law == SteeringLaw::kSingularityRobust || law == SteeringLaw::kGeneralizedSingularityRobust;
}

// ε_i = ε0 sin(ω t + φ_i) at the time t [s]. O(1).
inline void dither_epsilons(const SteeringParams& p, double t, double (&eps)[3]) {
  for (int i = 0; i < 3; ++i) eps[i] = p.dither_amplitude * math::sin(p.dither_frequency * t + kDitherPhase[i]);
}

struct SteeringOutput {
  double rate[kMaxCmgUnits]{};  // ν_i [rad/s]
  double measure{0.0};          // det(T Tᵀ) = det(A Aᵀ)/h⁶ [-]
  double lambda{0.0};           // the damping used [-]
  bool rate_limited{false};     // scaled down to max_rate
  bool singular{false};         // pseudo-inverse at m ≤ singular_floor: no rates
  double eps[3]{};              // ε_1, ε_2, ε_3 of the generalized inverse (0 otherwise) [-]
};

struct CmgAxes {
  double s[kMaxCmgUnits][3]{};  // s_i(δ_i)
  double t[kMaxCmgUnits][3]{};  // t_i(δ_i)
};

// s_i and t_i at the gimbal angles delta [rad]. O(N).
inline CmgAxes cmg_axes(const CmgArray& a, const double* delta) {
  CmgAxes out;
  for (int i = 0; i < a.count; ++i) {
    const double* g = a.gimbal_axis[i];
    const double* s0 = a.spin_axis0[i];
    const double gxs[3] = {g[1] * s0[2] - g[2] * s0[1], g[2] * s0[0] - g[0] * s0[2], g[0] * s0[1] - g[1] * s0[0]};
    const double c = math::cos(delta[i]), s = math::sin(delta[i]);
    for (int k = 0; k < 3; ++k) {
      out.s[i][k] = c * s0[k] + s * gxs[k];
      out.t[i][k] = -s * s0[k] + c * gxs[k];
    }
  }
  return out;
}

// ν = −A⁺ u for the torque demand u [N m] (body axes) at the gimbal angles delta [rad]; t [s] is the
// generalized inverse's dither time (unused by the other laws). O(N).
inline SteeringOutput steer_cmg(const CmgArray& a, const SteeringParams& p, const double* delta, const double* u,
                                double t = 0.0) {
  const CmgAxes ax = cmg_axes(a, delta);
  double M[3][3]{};
  for (int i = 0; i < a.count; ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) M[r][c] += ax.t[i][r] * ax.t[i][c];
    }
  }
  SteeringOutput out;
  const auto det3 = [](const double (&m)[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  out.measure = det3(M);
  if (is_robust(p.law)) {
    out.lambda = p.lambda0 * math::exp(-p.mu * out.measure);
    for (int k = 0; k < 3; ++k) M[k][k] += out.lambda;
    if (p.law == SteeringLaw::kGeneralizedSingularityRobust) {
      dither_epsilons(p, t, out.eps);
      // E's off-diagonals: E[1][2] = ε1, E[0][2] = ε2, E[0][1] = ε3.
      M[1][2] += out.lambda * out.eps[0];
      M[2][1] += out.lambda * out.eps[0];
      M[0][2] += out.lambda * out.eps[1];
      M[2][0] += out.lambda * out.eps[1];
      M[0][1] += out.lambda * out.eps[2];
      M[1][0] += out.lambda * out.eps[2];
    }
  } else if (!(out.measure > p.singular_floor)) {
    out.singular = true;
    return out;
  }
  const double det = det3(M);
  // v = M⁻¹ (−u/h) by the adjugate (M is symmetric).
  const double adj[3][3] = {
      {M[1][1] * M[2][2] - M[1][2] * M[2][1], M[0][2] * M[2][1] - M[0][1] * M[2][2], M[0][1] * M[1][2] - M[0][2] * M[1][1]},
      {M[1][2] * M[2][0] - M[1][0] * M[2][2], M[0][0] * M[2][2] - M[0][2] * M[2][0], M[0][2] * M[1][0] - M[0][0] * M[1][2]},
      {M[1][0] * M[2][1] - M[1][1] * M[2][0], M[0][1] * M[2][0] - M[0][0] * M[2][1], M[0][0] * M[1][1] - M[0][1] * M[1][0]}};
  double v[3];
  for (int r = 0; r < 3; ++r) v[r] = -(adj[r][0] * u[0] + adj[r][1] * u[1] + adj[r][2] * u[2]) / (det * a.h);
  double largest = 0.0;
  for (int i = 0; i < a.count; ++i) {
    out.rate[i] = ax.t[i][0] * v[0] + ax.t[i][1] * v[1] + ax.t[i][2] * v[2];
    const double m = out.rate[i] < 0.0 ? -out.rate[i] : out.rate[i];
    if (m > largest) largest = m;
  }
  if (largest > p.max_rate) {
    const double scale = p.max_rate / largest;
    for (int i = 0; i < a.count; ++i) out.rate[i] *= scale;
    out.rate_limited = true;
  }
  return out;
}

// Start-up check of the array and the steering parameters. O(N).
inline ConfigCheck check_cmg_steering(const CmgArray& a, const SteeringParams& p) {
  if (a.count < 1 || a.count > kMaxCmgUnits) {
    return ConfigCheck::refused("cmg steering: 1 to 4 CMGs", a.count, 1.0, kMaxCmgUnits);
  }
  if (!(std::isfinite(a.h) && a.h > 0.0)) return ConfigCheck::refused("cmg steering: h must be finite and > 0", a.h);
  for (int i = 0; i < a.count; ++i) {
    const double* g = a.gimbal_axis[i];
    const double* s = a.spin_axis0[i];
    const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2], ss = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
    const double gs = g[0] * s[0] + g[1] * s[1] + g[2] * s[2];
    if (!(std::fabs(gg - 1.0) < 1e-9 && std::fabs(ss - 1.0) < 1e-9 && std::fabs(gs) < 1e-9)) {
      return ConfigCheck::refused("cmg steering: gimbal and spin axes must be orthonormal pairs", i);
    }
  }
  if (!(std::isfinite(p.max_rate) && p.max_rate > 0.0)) {
    return ConfigCheck::refused("cmg steering: max_rate must be finite and > 0", p.max_rate);
  }
  if (!(std::isfinite(p.lambda0) && p.lambda0 >= 0.0 && std::isfinite(p.mu) && p.mu >= 0.0)) {
    return ConfigCheck::refused("cmg steering: lambda0 and mu must be finite and >= 0", p.lambda0);
  }
  if (!(p.singular_floor > 0.0)) return ConfigCheck::refused("cmg steering: singular_floor must be > 0", p.singular_floor);
  if (p.law == SteeringLaw::kGeneralizedSingularityRobust) {
    // ε0 ≥ 1/2 lets E (and with it A Aᵀ + λ E at a singular configuration) become indefinite.
    if (!(p.dither_amplitude >= 0.0 && p.dither_amplitude < 0.5)) {
      return ConfigCheck::refused("cmg steering: dither_amplitude must be in [0, 0.5) (E positive definite)",
                                  p.dither_amplitude, 0.0, 0.5);
    }
    if (!(std::isfinite(p.dither_frequency) && p.dither_frequency >= 0.0)) {
      return ConfigCheck::refused("cmg steering: dither_frequency must be finite and >= 0", p.dither_frequency);
    }
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
