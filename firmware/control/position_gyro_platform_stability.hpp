// Stability of the single-axis platform held by a position (two-degree-of-freedom) gyro (Magnus §16.2.2,
// (16.6)-(16.10)): the continuous loop's characteristic equation and its unstable gain bands in closed form,
// and the sampled loop's discrete closed-loop spectral radius (zero-order hold, control period, latency).
//
// Continuous (the book's analog amplifier M1^KP = −k(δ − α)): (16.8)
//   λ² {a4 λ⁴ + a3 λ³ + a2 λ² + a1 λ + a0} = 0,   a4 = ABΘ,  a3 = ABd1 + ΘAd2 + ΘBd1,
//   a2 = ABk + Θd1d2 + Ad1d2 + H²Θ,  a1 = Ad2k + H²d1,  a0 = H²k.
// The factor λ² is the free absolute angle (platform and gyro frame turned together) and the gyro's inner
// angle β (only β' enters). Hurwitz (16.9): D^II = a3a2 − a4a1 = p k + q with p = AB²d1(A + Θ) ≥ 0 and
// q = a3(Θd1d2 + Ad1d2 + H²Θ) − ABΘH²d1 = H²Θ²(Ad2 + Bd1) + a3 d1 d2 (Θ + A) > 0 (the k-terms of a3a2 and
// a4a1 cancel but for p, so D^II > 0 for every k ≥ 0 once d1, d2 > 0), and
//   D^III = a1 D^II − a3² a0 = c2 k² + c1 k + c0,   c2 = Ad2 p > 0,  c0 = H²d1 q > 0,
//   c1 = Ad2 q + H²d1 p − a3²H².
// With every a_i > 0 (d1, d2, k > 0) the loop is stable iff D^III > 0: stable for small and for large k, and
// unstable between the roots k− < k+ of D^III(k) = 0 when c1 < 0 and c1² > 4c2c0 (Hübner's band). For weak
// damping both hold (to leading order in d1, d2: c1 ≈ −H²Θ d1[B²(A + Θ)d1 + AB(2A + Θ)d2] and the
// discriminant ∝ B²(A + Θ)²d1² + 2ABΘ(A + Θ)d1d2 + A²Θ²d2² > 0), so the band always exists then, with edges
// that depend on the ratio d2/d1 but not on the damping's size; heavier damping closes it.
// Undamped (d1 = d2 = 0): a3 = a1 = 0, at best marginal: refused.
//
// Sampled (the firmware's law): the reduced state x = [e = δ − α, δ', α', β'] (the two free coordinates
// dropped), x' = F x + g M1 with M1 held over the control period Tc; the command from the frame of control
// step j acts from τ = latency·T_tick later, τ = m Tc + τ', 0 ≤ τ' < Tc:
//   x_{j+1} = Φ x_j + Γ0 u_{j−m} + Γ1 u_{j−m−1},   u_j = −k e_j,
//   Φ = e^{F Tc},  Γ0 = ∫_0^{Tc−τ'} e^{Fs} ds g,  Γ1 = e^{F(Tc−τ')} ∫_0^{τ'} e^{Fs} ds g.
// With the delay slots [u_{j−1} … u_{j−m−1}] the closed loop has 5 + m states. Its characteristic polynomial
// is built in w = z − 1 from Ψ = Φ − I by Faddeev-LeVerrier (no large matrix: the target's stack is 8 KB; and
// in w, not z, because the roots z = e^{λTc} crowd near 1 where the roots w ≈ λTc are well separated relative
// to their size — built in z, its rounding moved ρ by up to 4e-8 at Tc = 0.25 ms); for a radius ρ it is mapped
// onto the left half-plane (z = ρ(1 + v)/(1 − v)) and goes through Routh-Hurwitz; ρ is bisected. The sampled
// loop is stable iff ρ < 1; −ln(ρ)/Tc is its slowest decay rate.
// e^{Ft} − I: scaling and squaring (E ← E² + 2E) with a 13-term Taylor series without its 1 (‖F t‖ ≤ 1/2
// after scaling: truncation ≤ 0.5¹⁴/14! ≈ 7e-16 relative).
//
// O(1): the sampled part a few 4- and 5-square matrix products and ≤ 100 Routh tests of degree ≤ 21. No
// heap, no exceptions, + − × ÷ and sqrt only. Tests: tests/oracle/position_gyro_platform_test.cpp (the coefficients
// against the model's linearisation, the band edges against the roots' signs, ρ against the eigenvalues).
// Docs: docs/models/position-gyro-platform.md#stability
#pragma once

#include <cmath>

#include "firmware/control/hurwitz.hpp"

namespace gyrostab::firmware {

// What the check assumes about the plant (SI).
struct PositionGyroPlatformPlant {
  double Theta{0.2};  // platform inertia about axis 1 [kg m²]
  double A{0.02};     // gyro outer gimbal (with inner gimbal and rotor) about axis 1 [kg m²]
  double B{0.016};    // inner gimbal with rotor about axis 2 [kg m²]
  double H{0.5};      // spin momentum [N m s]
  double d1{0.2};     // damping of platform against the outer gimbal [N m s/rad]
  double d2{0.1};     // damping of the inner gimbal axis [N m s/rad]
};

struct PlatformQuartic {
  double a4, a3, a2, a1, a0;  // (16.8) without its λ², highest power first
};

constexpr PlatformQuartic platform_quartic(const PositionGyroPlatformPlant& p, double k) {
  const double A = p.A, B = p.B, T = p.Theta, H2 = p.H * p.H, d1 = p.d1, d2 = p.d2;
  return {A * B * T, A * B * d1 + T * A * d2 + T * B * d1, A * B * k + T * d1 * d2 + A * d1 * d2 + H2 * T,
          A * d2 * k + H2 * d1, H2 * k};
}

// D^II = p k + q and D^III = c2 k² + c1 k + c0 of (16.9) as polynomials in k.
struct PlatformHurwitzInK {
  double p, q;       // D^II
  double c2, c1, c0;  // D^III
};

constexpr PlatformHurwitzInK platform_hurwitz_in_k(const PositionGyroPlatformPlant& s) {
  const PlatformQuartic a = platform_quartic(s, 0.0);
  const double A = s.A, B = s.B, T = s.Theta, H2 = s.H * s.H, d1 = s.d1, d2 = s.d2;
  PlatformHurwitzInK h{};
  h.p = A * B * B * d1 * (A + T);
  h.q = H2 * T * T * (A * d2 + B * d1) + a.a3 * d1 * d2 * (T + A);  // = a3 a2(0) − a4 a1(0), no cancellation
  h.c2 = A * d2 * h.p;
  h.c1 = A * d2 * h.q + H2 * d1 * h.p - a.a3 * a.a3 * H2;
  h.c0 = H2 * d1 * h.q;
  return h;
}

struct PlatformGainBand {
  bool exists{false};  // D^III(k) < 0 on (lower, upper)
  double lower{0.0};   // k− [N m/rad]
  double upper{0.0};   // k+ [N m/rad]
};

// The unstable band of k: the real roots of D^III(k) = 0 when both are positive (c1 < 0, c1² > 4 c2 c0).
// k− = 2c0/(−c1 + √Δ) and k+ = (−c1 + √Δ)/(2c2): no cancellation in either.
inline PlatformGainBand platform_gain_band(const PositionGyroPlatformPlant& s) {
  const PlatformHurwitzInK h = platform_hurwitz_in_k(s);
  PlatformGainBand b;
  const double disc = h.c1 * h.c1 - 4.0 * h.c2 * h.c0;
  if (!(h.c1 < 0.0 && disc > 0.0 && h.c2 > 0.0)) return b;
  const double r = -h.c1 + std::sqrt(disc);
  b.exists = true;
  b.lower = 2.0 * h.c0 / r;
  b.upper = r / (2.0 * h.c2);
  return b;
}

// The continuous loop's Hurwitz verdict at gain k (quartic of (16.8); D2 = D^II, D3 = D^III).
constexpr HurwitzResult platform_hurwitz(const PositionGyroPlatformPlant& s, double k) {
  const PlatformQuartic a = platform_quartic(s, k);
  return hurwitz_quartic(a.a4, a.a3, a.a2, a.a1, a.a0);
}

// ---- the sampled loop -------------------------------------------------------------------------------------

inline constexpr int kPlatformReducedStates = 4;  // [e, δ', α', β']
inline constexpr int kPlatformMaxDelay = 16;      // m ≤ 16 control periods of latency
inline constexpr int kPlatformMaxDegree = kPlatformReducedStates + kPlatformMaxDelay + 1;

// The reduced plant x' = F x + g M1 (x = [e, δ', α', β']) of (16.6) with M1 the platform torquer.
struct PlatformReducedPlant {
  double F[4][4];
  double g[4];
};

constexpr PlatformReducedPlant platform_reduced_plant(const PositionGyroPlatformPlant& s) {
  const double T = s.Theta, A = s.A, B = s.B, H = s.H, d1 = s.d1, d2 = s.d2;
  return {{{0.0, 1.0, -1.0, 0.0},
           {0.0, -d1 / T, d1 / T, 0.0},
           {0.0, d1 / A, -d1 / A, -H / A},
           {0.0, 0.0, H / B, -d2 / B}},
          {0.0, 1.0 / T, 0.0, 0.0}};
}

// The plant over one control period: x_{j+1} = Phi x_j + G0 u_{j−m} + G1 u_{j−m−1}; Psi = Phi − I, kept apart
// because the polynomial below is built from it (Phi's eigenvalues crowd near 1, Psi's are ≈ λ Tc).
struct PlatformDiscretized {
  double Phi[4][4];
  double Psi[4][4];
  double G0[4];
  double G1[4];
  int m{0};  // whole control periods of latency
};

namespace detail {

// e^{X t} − I of the 5-square augmented matrix X = [F g; 0 0]: [e^{Ft} − I, ∫_0^t e^{Fs} ds g; 0 0].
struct Aug5 {
  double a[5][5];
};

inline Aug5 aug_mul(const Aug5& x, const Aug5& y) {
  Aug5 r{};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      double s = 0.0;
      for (int l = 0; l < 5; ++l) s += x.a[i][l] * y.a[l][j];
      r.a[i][j] = s;
    }
  return r;
}

inline Aug5 aug_expm1(const PlatformReducedPlant& p, double t) {
  Aug5 x{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) x.a[i][j] = p.F[i][j] * t;
    x.a[i][4] = p.g[i] * t;
  }
  double norm = 0.0;  // infinity norm
  for (int i = 0; i < 5; ++i) {
    double row = 0.0;
    for (int j = 0; j < 5; ++j) row += x.a[i][j] < 0.0 ? -x.a[i][j] : x.a[i][j];
    norm = row > norm ? row : norm;
  }
  int squarings = 0;
  while (norm > 0.5 && squarings < 200) {
    norm *= 0.5;
    ++squarings;
  }
  double f = 1.0;
  for (int s = 0; s < squarings; ++s) f *= 0.5;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) x.a[i][j] *= f;
  Aug5 e = x, term = x;  // Σ_{q≥1} X^q/q!
  for (int q = 2; q <= 13; ++q) {
    term = aug_mul(term, x);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        term.a[i][j] /= static_cast<double>(q);
        e.a[i][j] += term.a[i][j];
      }
  }
  for (int s = 0; s < squarings; ++s) {  // e^{2X} − I = E² + 2E with E = e^X − I
    Aug5 sq = aug_mul(e, e);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) e.a[i][j] = sq.a[i][j] + 2.0 * e.a[i][j];
  }
  return e;
}

// Routh-Hurwitz: every root of c[0] + c[1] v + … + c[n] v^n strictly in the left half-plane (c[n] ≠ 0).
// Two rolling rows of the Routh array; a zero or a sign change in its first column: not stable.
inline bool routh_stable(const double* c, int n) {
  constexpr int kW = kPlatformMaxDegree / 2 + 2;
  double r0[kW]{}, r1[kW]{};
  for (int i = 0; 2 * i <= n; ++i) r0[i] = c[n - 2 * i];
  for (int i = 0; 2 * i + 1 <= n; ++i) r1[i] = c[n - 2 * i - 1];
  const bool positive = c[n] > 0.0;
  for (int row = 1; row <= n; ++row) {
    if (!(positive ? r1[0] > 0.0 : r1[0] < 0.0)) return false;
    double next[kW]{};
    for (int i = 0; i + 1 < kW; ++i) next[i] = (r1[0] * r0[i + 1] - r0[0] * r1[i + 1]) / r1[0];
    for (int i = 0; i < kW; ++i) {
      r0[i] = r1[i];
      r1[i] = next[i];
    }
  }
  return true;
}

}  // namespace detail

// The plant sampled at control period Tc [s] with latency τ [s] (τ ≤ 16 Tc).
inline PlatformDiscretized platform_discretized(const PositionGyroPlatformPlant& s, double Tc, double tau) {
  PlatformDiscretized d{};
  const PlatformReducedPlant p = platform_reduced_plant(s);
  int m = static_cast<int>(tau / Tc);
  double tp = tau - static_cast<double>(m) * Tc;
  if (tp < 1e-12 * Tc) tp = 0.0;  // a latency of whole periods (the rounding of m Tc)
  if (tp > Tc * (1.0 - 1e-12)) {
    ++m;
    tp = 0.0;
  }
  if (m > kPlatformMaxDelay) m = kPlatformMaxDelay;
  d.m = m;
  const detail::Aug5 e0 = detail::aug_expm1(p, Tc - tp);  // the part of the period after the switch
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) d.Psi[i][j] = e0.a[i][j];
    d.G0[i] = e0.a[i][4];
    d.G1[i] = 0.0;
  }
  if (tp > 0.0) {  // Φ = Φ0 Φ1: Ψ = Ψ0 + Ψ1 + Ψ0 Ψ1; Γ1 = Φ0 γ1 = γ1 + Ψ0 γ1
    const detail::Aug5 e1 = detail::aug_expm1(p, tp);
    double P[4][4];
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        double a = 0.0;
        for (int l = 0; l < 4; ++l) a += d.Psi[i][l] * e1.a[l][j];
        P[i][j] = d.Psi[i][j] + e1.a[i][j] + a;
      }
      double g = 0.0;
      for (int l = 0; l < 4; ++l) g += d.Psi[i][l] * e1.a[l][4];
      d.G1[i] = e1.a[i][4] + g;
    }
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) d.Psi[i][j] = P[i][j];
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) d.Phi[i][j] = d.Psi[i][j] + (i == j ? 1.0 : 0.0);
  return d;
}

// The sampled closed loop's characteristic polynomial in w = z − 1 (its roots ≈ λ Tc, well separated
// relative to their size, where those in z crowd near 1): q[0] + q[1] w + … + q[n] w^n, n = 5 + m (returned).
// With u_j = −k e_j and the latency's m + 1 delay slots [u_{j−1} … u_{j−m−1}],
//   Q(z) = z^{m+1} det(zI − Φ) + k e_1ᵀ adj(zI − Φ)(Γ0 z + Γ1),   zI − Φ = wI − Ψ,
// det and adjugate by Faddeev-LeVerrier on Ψ: adj(wI − Ψ) = Σ_{i=1..4} M_i w^{4−i}, M_1 = I,
// M_i = Ψ M_{i−1} + p_{5−i} I, p_{4−i} = −tr(Ψ M_i)/i; z^{m+1} = (1 + w)^{m+1}, Γ0 z + Γ1 = (Γ0 + Γ1) + Γ0 w.
inline int platform_sampled_characteristic(const PlatformDiscretized& d, double k,
                                           double (&q)[kPlatformMaxDegree + 1]) {
  double p[5] = {0.0, 0.0, 0.0, 0.0, 1.0};  // det(wI − Ψ), p[i] of w^i
  double Mi[4][4]{}, Next[4][4];
  double s0[5]{}, s1[5]{};  // e_1ᵀ M_i (Γ0 + Γ1), e_1ᵀ M_i Γ0 (index i = 1..4)
  for (int i = 1; i <= 4; ++i) {
    for (int r = 0; r < 4; ++r)
      for (int col = 0; col < 4; ++col) {
        double a = 0.0;
        for (int l = 0; l < 4; ++l) a += d.Psi[r][l] * Mi[l][col];
        Next[r][col] = a + (r == col ? p[5 - i] : 0.0);
      }
    for (int r = 0; r < 4; ++r)
      for (int col = 0; col < 4; ++col) Mi[r][col] = Next[r][col];
    double tr = 0.0;
    for (int r = 0; r < 4; ++r)
      for (int l = 0; l < 4; ++l) tr += d.Psi[r][l] * Mi[l][r];
    p[4 - i] = -tr / static_cast<double>(i);
    for (int l = 0; l < 4; ++l) {
      s0[i] += Mi[0][l] * (d.G0[l] + d.G1[l]);
      s1[i] += Mi[0][l] * d.G0[l];
    }
  }
  const int n = 5 + d.m;
  double binom[kPlatformMaxDelay + 2]{};  // (1 + w)^{m+1}
  binom[0] = 1.0;
  for (int e = 1; e <= d.m + 1; ++e)
    for (int j = e; j >= 1; --j) binom[j] += binom[j - 1];
  for (int i = 0; i <= kPlatformMaxDegree; ++i) q[i] = 0.0;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= d.m + 1; ++j) q[i + j] += p[i] * binom[j];
  for (int i = 1; i <= 4; ++i) {  // k Σ_i (s0_i w^{4−i} + s1_i w^{5−i})
    q[4 - i] += k * s0[i];
    q[5 - i] += k * s1[i];
  }
  return n;
}

// Every root of the sampled loop inside |z| < ρ: with z = ρ z', w = (ρ − 1) + ρ w' (a shift the size of the
// roots: no loss), and the bilinear map z' = (1 + v)/(1 − v), w' = 2v/(1 − v), |z'| < 1 ⟺ Re v < 0:
// P(v) = Σ r_j (2v)^j (1 − v)^{n−j} through Routh-Hurwitz.
inline bool platform_sampled_within(const double (&q)[kPlatformMaxDegree + 1], int n, double rho) {
  double r[kPlatformMaxDegree + 1]{};  // R(w') = Q((ρ − 1) + ρ w'), Horner on polynomials
  const double a = rho - 1.0, b = rho;
  r[0] = q[n];
  for (int j = n - 1; j >= 0; --j) {
    const int deg = n - 1 - j;  // degree of r before this step
    for (int i = deg + 1; i >= 1; --i) r[i] = r[i] * a + r[i - 1] * b;
    r[0] = r[0] * a + q[j];
  }
  double P[kPlatformMaxDegree + 1]{};
  double binom[kPlatformMaxDegree + 1];  // (1 − v)^{n−j}
  double pow2 = 1.0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) binom[i] = 0.0;
    binom[0] = 1.0;
    for (int e = 1; e <= n - j; ++e)
      for (int i = e; i >= 1; --i) binom[i] -= binom[i - 1];
    for (int i = 0; i <= n - j; ++i) P[i + j] += r[j] * pow2 * binom[i];
    pow2 *= 2.0;
  }
  if (P[n] == 0.0) return false;  // a root at z' = −1 (v = ∞): on the circle
  return detail::routh_stable(P, n);
}

// The spectral radius of the sampled closed loop, to a relative 1e-12 (bisection on ρ). NaN when a parameter
// is not finite.
inline double platform_sampled_radius(const PositionGyroPlatformPlant& s, double k, double Tc, double tau) {
  const PlatformDiscretized d = platform_discretized(s, Tc, tau);
  double q[kPlatformMaxDegree + 1];
  const int n = platform_sampled_characteristic(d, k, q);
  for (int i = 0; i <= n; ++i)
    if (!std::isfinite(q[i])) return std::nan("");
  double hi = 2.0;
  for (int i = 0; i < 60 && !platform_sampled_within(q, n, hi); ++i) hi *= 2.0;
  double lo = 0.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (platform_sampled_within(q, n, mid)) hi = mid;
    else lo = mid;
  }
  return hi;
}

}  // namespace gyrostab::firmware
