// Exact flow of the linear, damped gyroscopic pair with constant forcing:
//   q' = v,   v' = K v + r,   K = [[-p, -a], [b, -q]]      (q, v, r ∈ R², K, r constant over τ)
// For a gimbal gyro: a = H cosβ/I(β), b = H cosβ/B (nutation coupling, Magnus (10.4)), p = d1/I(β),
// q = d2/B (viscous bearing damping (11.1)).
//
// Write K = m I + N with m = -(p + q)/2 and N = [[(q - p)/2, -a], [b, (p - q)/2]], so N² = δ I with
// δ = (p - q)²/4 - ab (< 0 for a spinning rotor: δ = -μ², μ the damped nutation frequency). Then
//   e^{Kσ} = e^{mσ} (C(σ) I + S(σ) N),   C = cos μσ, S = sin(μσ)/μ   (cosh/sinh when δ > 0),
// and with S2 = ∫0^τ (τ - σ) e^{Kσ} dσ = k0 I + k1 N,  k0 + i μ k1 = τ² φ2((m + iμ) τ),
//   S1 = ∫0^τ e^{Kσ} dσ = τ I + K S2,   e^{Kτ} = I + K S1,
//   v(τ) = e^{Kτ} v0 + S1 r,   q(τ) = q0 + S1 v0 + S2 r,
// where φ2(w) = (e^w - 1 - w)/w². Only one complex exponential per flow; series where the closed forms
// cancel (|w| small, and the nearly critically damped case δ ≈ 0 with real roots).
// Allocation-free, no branches on the caller's side. Checked against a matrix exponential in
// tests/unit/damped_gyroscopic_flow_test.cpp.
// Docs: docs/models/integrators.md#methods
#pragma once

#include <cmath>
#include <complex>

namespace gyrostab::dynamics {

namespace detail {

// φ2(w) = Σ w^k/(k+2)!, for complex w.
// |w| < 0.5: the series to degree n, split into even and odd parts in z = w² (two independent Horner chains,
// half the latency of one; the flow is on the integrator's critical path), n chosen from |w| so that the
// truncation is below 1e-18 of φ2 and of its imaginary part (which k1 divides by μ): n = 9, 11, 13, 15 up to
// |w| = 0.05, 0.15, 0.25, 0.5. Worst relative error over 1e6 random |w| < 0.5 against a long-double sum:
// 3.2e-16, and 4.0e-16 in the imaginary part (tests/unit/damped_gyroscopic_flow_test.cpp checks 2e-15).
inline std::complex<double> phi2(std::complex<double> w) {
  static constexpr double c[16] = {1.0 / 2,          1.0 / 6,           1.0 / 24,           1.0 / 120,
                                   1.0 / 720,        1.0 / 5040,        1.0 / 40320,        1.0 / 362880,
                                   1.0 / 3628800,    1.0 / 39916800,    1.0 / 479001600,    1.0 / 6227020800.0,
                                   1.0 / 87178291200.0, 1.0 / 1307674368000.0, 1.0 / 20922789888000.0,
                                   1.0 / 355687428096000.0};  // 1/(k+2)!
  const double x = w.real(), y = w.imag();
  const double r2 = x * x + y * y;
  if (r2 < 0.25) {
    const int n = r2 < 0.0025 ? 9 : (r2 < 0.0225 ? 11 : (r2 < 0.0625 ? 13 : 15));  // odd: the last index
    const double zr = x * x - y * y, zi = 2.0 * x * y;
    double er = c[n - 1], ei = 0.0, or_ = c[n], oi = 0.0;  // E(z) = Σ c_2j z^j, O(z) = Σ c_2j+1 z^j
    for (int k = n - 3; k >= 0; k -= 2) {
      const double er1 = er * zr - ei * zi + c[k];
      ei = er * zi + ei * zr;
      er = er1;
      const double or1 = or_ * zr - oi * zi + c[k + 1];
      oi = or_ * zi + oi * zr;
      or_ = or1;
    }
    return {er + x * or_ - y * oi, ei + x * oi + y * or_};  // E + w O
  }
  return (std::exp(w) - 1.0 - w) / (w * w);
}

// d/dx φ2(x) for real x: Σ_{k≥1} k x^{k-1}/(k+2)!  or  (x e^x - 2 e^x + 2 + x)/x³.
inline double phi2_prime(double x) {
  if (std::abs(x) < 0.5) {
    double sum = 0.0, term = 1.0 / 6.0;  // k = 1: 1/3!
    for (int k = 1; k < 18; ++k) {
      sum += term;
      term *= x * static_cast<double>(k + 1) / (static_cast<double>(k) * static_cast<double>(k + 3));
    }
    return sum;
  }
  const double e = std::exp(x);
  return (x * e - 2.0 * e + 2.0 + x) / (x * x * x);
}

}  // namespace detail

struct GyroscopicPair {
  double a, b;  // coupling: v0' ∋ -a v1, v1' ∋ +b v0
  double p, q;  // damping rates: v0' ∋ -p v0, v1' ∋ -q v1
};

// Advance (q0, q1, v0, v1) by τ under the frozen pair and forcing (r0, r1). In and out may alias.
inline void damped_gyroscopic_flow(const GyroscopicPair& k, double tau, double r0, double r1, const double* in,
                                   double* out) {
  const double m = -0.5 * (k.p + k.q);
  const double n00 = 0.5 * (k.q - k.p);  // N = [[n00, -a], [b, -n00]]
  const double delta = n00 * n00 - k.a * k.b;
  double k0, k1;  // S2 = k0 I + k1 N
  const double tau2 = tau * tau;
  if (delta <= 0.0) {
    const double mu = std::sqrt(-delta);
    const std::complex<double> f = detail::phi2(std::complex<double>(m * tau, mu * tau));
    k0 = tau2 * f.real();
    // Im φ2 is O(μτ) and is computed without cancellation, so the division is exact to round-off.
    k1 = mu > 0.0 ? tau2 * f.imag() / mu : tau2 * tau * detail::phi2_prime(m * tau);
  } else {
    const double kappa = std::sqrt(delta);
    if (kappa * tau < 1e-5) {
      // Nearly critical: the divided difference is φ2'(mτ) τ to O((κτ)²) ≲ 1e-10.
      k0 = tau2 * detail::phi2(std::complex<double>(m * tau, 0.0)).real();
      k1 = tau2 * tau * detail::phi2_prime(m * tau);
    } else {
      const double fp = detail::phi2(std::complex<double>((m + kappa) * tau, 0.0)).real();
      const double fm = detail::phi2(std::complex<double>((m - kappa) * tau, 0.0)).real();
      k0 = 0.5 * tau2 * (fp + fm);
      k1 = 0.5 * tau2 * (fp - fm) / kappa;
    }
  }
  // Matrices as [[x00, x01], [x10, x11]].
  const double s2_00 = k0 + k1 * n00, s2_01 = -k1 * k.a, s2_10 = k1 * k.b, s2_11 = k0 - k1 * n00;
  // K = [[-p, -a], [b, -q]]; S1 = τ I + K S2; E = I + K S1.
  const double s1_00 = tau - k.p * s2_00 - k.a * s2_10;
  const double s1_01 = -k.p * s2_01 - k.a * s2_11;
  const double s1_10 = k.b * s2_00 - k.q * s2_10;
  const double s1_11 = tau + k.b * s2_01 - k.q * s2_11;
  const double e00 = 1.0 - k.p * s1_00 - k.a * s1_10;
  const double e01 = -k.p * s1_01 - k.a * s1_11;
  const double e10 = k.b * s1_00 - k.q * s1_10;
  const double e11 = 1.0 + k.b * s1_01 - k.q * s1_11;
  const double q0 = in[0], q1 = in[1], v0 = in[2], v1 = in[3];
  out[0] = q0 + s1_00 * v0 + s1_01 * v1 + s2_00 * r0 + s2_01 * r1;
  out[1] = q1 + s1_10 * v0 + s1_11 * v1 + s2_10 * r0 + s2_11 * r1;
  out[2] = e00 * v0 + e01 * v1 + s1_00 * r0 + s1_01 * r1;
  out[3] = e10 * v0 + e11 * v1 + s1_10 * r0 + s1_11 * r1;
}

}  // namespace gyrostab::dynamics
