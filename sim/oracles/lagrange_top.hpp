// Closed forms for the heavy symmetric top on a fixed point (Lagrange case), used as test oracles.
// Docs: docs/models/rigid-bodies.md#heavy-symmetric-top
//
// Book: Magnus §3.3.2. With u = cos θ (θ: figure axis from the upward
// vertical), spin ω3 = ω0, vertical momentum H0 and energy E0 (3.36)-(3.38), u obeys (3.46)-(3.47)
//   u'² = U(u) = ((2E0 - Cω0²)/A - (2Gs/A) u)(1 - u²) - (H0/A - (Cω0/A) u)²
//        = (2Gs/A)(u - u1)(u - u2)(u - u3),      u1 ≤ u ≤ u2 ≤ 1 ≤ u3   (standing top, Gs > 0)
// solved by (3.48)-(3.52): u = u1 + (u2 - u1) sn²(τ, k), k² = (u2 - u1)/(u3 - u1),
// τ = √(Gs(u3 - u1)/(2A)) (t - t0); nutation period T_S = K(k) √(8A/(Gs(u3 - u1))).
//
// Provided here:
//   * spin parameter a = C²ω0²/(4GsA) and the rest-spin release roots (3.53)-(3.54):
//       u1 = a - √(a² - 2a u0 + 1),  u2 = u0,  u3 = a + √(a² - 2a u0 + 1);
//   * the roots for any start with θ'(0) = 0 and azimuth rate ψ'0 [D]: U(u) = (u0 - u) Q(u0 - u) with Q
//     quadratic (u0 is always a root), which contains (3.54) (ψ'0 = 0) and regular precession (double root);
//   * u(t) from the upper turning point u2 at t = 0: u = u1 + (u2 - u1) cd²(τ, k) (cd = sn(τ + K));
//   * the exact mean precession rate of the rest-spin release over whole nutation periods [D]:
//       ψ' = Cω0 (u0 - u) / (A (1 - u²)) from (3.40) with H0 = Cω0u0, and with partial fractions
//       mean ψ' = (Cω0/A)/(2K) [ (1+u0)/(1+u1) Π(n₊, k) - (1-u0)/(1-u1) Π(n₋, k) ],
//       n₋ = (u2 - u1)/(1 - u1), n₊ = -(u2 - u1)/(1 + u1), Π(n, k) = ∫0^{π/2} dφ/((1 - n sin²φ)√(1 - k²
//       sin²φ));
//   * the regular-precession rates (3.57)-(3.60): A cosθ0 ψ'² - Cω0 ψ' + Gs = 0, slow root formed as
//     2Gs/(Cω0(1 + √d)) to avoid cancellation (and to give Gs/(Cω0), (3.61), at θ0 = π/2);
//   * the sleeping top (3.67)-(3.70): stable iff a ≥ 1; for a < 1 it falls to cos θ = 2a - 1; after an
//     upright start with transverse rate ω_t the exact turning points are u = 1 and the roots of
//       2g u² - (ω_t² + 4ag) u - (ω_t² + 2g - 4ag) = 0,   g = Gs/A          [D, the roots the OCR lost
//       from (3.69)]
//     whose smaller root is the lowest cos θ reached (≈ 2a - 1 for a < 1, just below 1 for a > 1).
//
// Units: A, C [kg m²], Gs [N m], rates [rad/s], time [s]. Standing top only (Gs > 0).
// Held to: tests/oracle/heavy_symmetric_top_test.cpp (reference cases L1-L3, and the integrators against it).
#pragma once

#include <algorithm>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_3.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace gyrostab::oracles {

struct LagrangeTopParams {
  double A{1.0};   // transverse moment about the fixed point [kg m²]
  double C{0.5};   // axial moment [kg m²]
  double Gs{1.0};  // weight × centre-of-mass height on the figure axis [N m], > 0 (standing)
};

// Roots of the cubic U(u), ascending: u1 ≤ u2 ≤ 1 ≤ u3. The motion keeps u in [u1, u2].
struct TurningPoints {
  double u1{};
  double u2{};
  double u3{};
};

namespace lagrange_detail {
inline void require_standing(const LagrangeTopParams& p) {
  if (!(p.A > 0.0 && p.C > 0.0 && p.Gs > 0.0)) {
    throw std::invalid_argument("lagrange_top: needs A > 0, C > 0 and Gs > 0 (standing top)");
  }
}
inline TurningPoints sorted(double x, double y, double z) {
  if (x > y) std::swap(x, y);
  if (y > z) std::swap(y, z);
  if (x > y) std::swap(x, y);
  return {x, y, z};
}
}  // namespace lagrange_detail

// a = C²ω0²/(4GsA), the dimensionless spin of (3.54) and (3.70).
inline double spin_parameter(const LagrangeTopParams& p, double omega0) {
  return p.C * p.C * omega0 * omega0 / (4.0 * p.Gs * p.A);
}

// Released from rest-spin at cos θ0 = u0: θ' = 0, ψ' = 0, ω3 = ω0. (3.54).
inline TurningPoints rest_spin_turning_points(const LagrangeTopParams& p, double u0, double omega0) {
  lagrange_detail::require_standing(p);
  const double a = spin_parameter(p, omega0);
  const double r = std::sqrt(a * a - 2.0 * a * u0 + 1.0);
  return {a - r, u0, a + r};
}

// Any start with θ'(0) = 0 at cos θ0 = u0 with azimuth rate ψ'0 and spin ω0 [D]. With v = u0 - u,
// U = v Q(v), Q(v) = -β v² + (2u0β - ψ'0² s² - c²) v + s² (2u0 ψ'0² + β - 2cψ'0),
// β = 2Gs/A, c = Cω0/A, s² = 1 - u0².
inline TurningPoints tilted_start_turning_points(const LagrangeTopParams& p, double u0, double omega0,
                                                 double psi_dot0) {
  lagrange_detail::require_standing(p);
  const double beta = 2.0 * p.Gs / p.A, c = p.C * omega0 / p.A, s2 = 1.0 - u0 * u0;
  const double q2 = -beta;
  const double q1 = 2.0 * u0 * beta - psi_dot0 * psi_dot0 * s2 - c * c;
  const double q0 = s2 * (2.0 * u0 * psi_dot0 * psi_dot0 + beta - 2.0 * c * psi_dot0);
  // Roots of q2 v² + q1 v + q0 without cancellation.
  const double disc = std::sqrt(std::max(0.0, q1 * q1 - 4.0 * q2 * q0));
  const double big = -0.5 * (q1 + std::copysign(disc, q1));
  const double v_a = big / q2;
  const double v_b = big != 0.0 ? q0 / big : 0.0;
  return lagrange_detail::sorted(u0, u0 - v_a, u0 - v_b);
}

// k² = (u2 - u1)/(u3 - u1), (3.48).
inline double nutation_modulus_squared(const TurningPoints& r) {
  return (r.u2 - r.u1) / (r.u3 - r.u1);
}

// T_S = K(k) √(8A/(Gs(u3 - u1))) [s]: the period of θ (and of ψ', φ').
inline double nutation_period(const LagrangeTopParams& p, const TurningPoints& r) {
  const double k = std::sqrt(nutation_modulus_squared(r));
  return boost::math::ellint_1(k) * std::sqrt(8.0 * p.A / (p.Gs * (r.u3 - r.u1)));
}

// u(t) = cos θ(t) for a motion that is at the upper turning point u2 at t = 0 (e.g. the rest-spin release).
inline double cos_tilt_from_upper_turning_point(const LagrangeTopParams& p, const TurningPoints& r,
                                                double t) {
  const double k = std::sqrt(nutation_modulus_squared(r));
  const double tau = std::sqrt(p.Gs * (r.u3 - r.u1) / (2.0 * p.A)) * t;
  double cn = 0.0, dn = 0.0;
  boost::math::jacobi_elliptic(k, tau, &cn, &dn);
  const double cd = cn / dn;
  return r.u1 + (r.u2 - r.u1) * cd * cd;
}

// Exact mean azimuth (precession) rate ψ' [rad/s] of the rest-spin release over whole nutation periods [D].
inline double rest_spin_mean_precession_rate(const LagrangeTopParams& p, double u0, double omega0) {
  const TurningPoints r = rest_spin_turning_points(p, u0, omega0);
  const double k = std::sqrt(nutation_modulus_squared(r));
  const double n_minus = (r.u2 - r.u1) / (1.0 - r.u1);
  const double n_plus = -(r.u2 - r.u1) / (1.0 + r.u1);
  const double K = boost::math::ellint_1(k);
  const double bracket = (1.0 + u0) / (1.0 + r.u1) * boost::math::ellint_3(k, n_plus) -
                         (1.0 - u0) / (1.0 - r.u1) * boost::math::ellint_3(k, n_minus);
  return p.C * omega0 / p.A * bracket / (2.0 * K);
}

// The two azimuth rates ψ' that keep θ = θ0 (regular precession), (3.57)-(3.60).
struct RegularPrecessionRates {
  double slow;  // ψ'2 ≈ Gs/(Cω0) for a fast top: the gravity precession
  double fast;  // ψ'1 ≈ Cω0/(A cos θ0): the nutation-like root; +inf at θ0 = π/2
};

// Empty when the spin is below ω0*² = 4GsA cos θ0 / C² (no real roots).
inline std::optional<RegularPrecessionRates> regular_precession_rates(const LagrangeTopParams& p,
                                                                      double theta0, double omega0) {
  lagrange_detail::require_standing(p);
  const double c = std::cos(theta0);
  const double d = 1.0 - 4.0 * p.Gs * p.A * c / (p.C * p.C * omega0 * omega0);
  if (d < 0.0) return std::nullopt;
  const double root = std::sqrt(d);
  const double slow = 2.0 * p.Gs / (p.C * omega0 * (1.0 + root));
  const double fast =
      c != 0.0 ? p.C * omega0 / (2.0 * p.A * c) * (1.0 + root) : std::numeric_limits<double>::infinity();
  return RegularPrecessionRates{slow, fast};
}

// Sleeping (upright) top, (3.67)-(3.70): stable iff C²ω0² ≥ 4GsA, i.e. a ≥ 1.
inline double sleeping_top_critical_spin(const LagrangeTopParams& p) {
  return 2.0 * std::sqrt(p.Gs * p.A) / p.C;
}
inline bool sleeping_top_is_stable(const LagrangeTopParams& p, double omega0) {
  return spin_parameter(p, omega0) >= 1.0;
}
// Lowest cos θ reached after an infinitesimal kick: 2a - 1 for a < 1, 1 (stays up) for a ≥ 1.
inline double sleeping_top_fall_cos_tilt(double a) {
  return a < 1.0 ? 2.0 * a - 1.0 : 1.0;
}

// Exact turning points after an upright start (u0 = 1) with spin ω0 and transverse body rate ω_t [D]:
// {1, roots of 2g u² - (ω_t² + 4ag) u - (ω_t² + 2g - 4ag)}, sorted. u1 is the lowest cos θ reached.
inline TurningPoints kicked_sleeping_top_turning_points(const LagrangeTopParams& p, double omega0,
                                                        double transverse_rate) {
  lagrange_detail::require_standing(p);
  const double g = p.Gs / p.A, a = spin_parameter(p, omega0), w2 = transverse_rate * transverse_rate;
  const double sum = w2 + 4.0 * a * g;  // 2g × (sum of roots), > 0
  const double disc = std::sqrt(sum * sum + 8.0 * g * (w2 + 2.0 * g - 4.0 * a * g));
  const double big = (sum + disc) / (4.0 * g);
  const double small = -(w2 + 2.0 * g - 4.0 * a * g) / (2.0 * g) / big;  // product / big
  return lagrange_detail::sorted(1.0, small, big);
}

}  // namespace gyrostab::oracles
