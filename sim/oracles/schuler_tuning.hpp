// Closed forms for Schuler-tuned pendulums and gyro pendulums on a moving pivot — Magnus §12.3.3
// (12.57)-(12.68) and Chelnokov §2, §4 (docs/models/gyro-pendulum.md). Test oracles and the
// scene's "book" figures.
// Docs: docs/models/gyro-pendulum.md
#pragma once

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

namespace gyrostab::oracles {

inline double schuler_rate(double g, double R) { return std::sqrt(g / R); }                   // ω_S [rad/s]
inline double schuler_period(double g, double R) { return 2.0 * std::numbers::pi / schuler_rate(g, R); }  // [s]

// (12.57) k = m g s − (3g/R)(C − A) [N m/rad]; m s = m l [kg m].
inline double pendulous_stiffness(double ms, double A, double C, double g, double R, bool gradient = true) {
  return ms * g - (gradient ? 3.0 * g / R * (C - A) : 0.0);
}

// Period of the physical pendulum (H = 0) about the vertical of a pivot at rest: T = 2π sqrt(A/k),
// which for the tuned m s = A/R is (12.60) T = 2π sqrt(R/g) sqrt(A/(4A − 3C)); +∞ when k ≤ 0
// (4A = 3C: neutral; 3C > 4A: the vertical is unstable).
inline double pendulum_period(double A, double k) {
  return k > 0.0 ? 2.0 * std::numbers::pi * std::sqrt(A / k) : std::numeric_limits<double>::infinity();
}
inline double tuned_pendulum_period(double A, double C, double g, double R) {
  const double d = 4.0 * A - 3.0 * C;
  return d > 0.0 ? schuler_period(g, R) * std::sqrt(A / d) : std::numeric_limits<double>::infinity();
}

// (12.61): roots of A ω² − H ω − k = 0 (z = Z e^(iωt)): ω^N = H/(2A)[1 + sqrt(1 + 4Ak/H²)] and
// ω^P = −k/(A ω^N) (the product of the roots, free of the cancellation of the "−" root).
struct GyroPendulumRoots {
  double nutation;    // ω^N [rad/s]
  double precession;  // ω^P [rad/s] (< 0 for k > 0: against the rotor's sense)
};
inline GyroPendulumRoots gyro_pendulum_roots(double A, double H, double k) {
  const double wn = H / (2.0 * A) * (1.0 + std::sqrt(1.0 + 4.0 * A * k / (H * H)));
  return {wn, -k / (A * wn)};
}

// (12.66): s² m² R² g − s m R g (3C − 2A) − [H² R − 3 g A (C − A)] = 0, the positive root [m]: the pendulum
// offset that nulls the precession-mode response to slow accelerations (ω^P ≈ −k/H).
inline double tuned_gyro_pendulum_offset(double m, double A, double C, double H, double g, double R) {
  const double a = m * m * R * R * g, b = -m * R * g * (3.0 * C - 2.0 * A), c = -(H * H * R - 3.0 * g * A * (C - A));
  const double disc = std::sqrt(b * b - 4.0 * a * c);
  return b < 0.0 ? (-b + disc) / (2.0 * a) : -2.0 * c / (b + disc);
}
// (12.67) s ≈ H/(m sqrt(R g)).
inline double tuned_gyro_pendulum_offset_approx(double m, double H, double g, double R) {
  return H / (m * std::sqrt(R * g));
}

// (12.65): the velocity-dependent steady error z = H w/(A R ω^N ω^P) = −H w/(k R) [rad].
inline std::complex<double> velocity_error(double H, double k, double R, std::complex<double> w) {
  return -H * w / (k * R);
}

// Chelnokov (2.14) in the Newtonian field, azimuth-free trihedron (ω°² = v²/R²), k = l m R:
// [1 + 3(I1 − I3)/(l m R)] g/R > v²/R²  ⇔  v < v_crit [m/s].  (d' = 0, I1 = I3: v_crit = sqrt(g R).)
inline double chelnokov_critical_speed(double g, double R, double I1, double I3, double lm) {
  const double f = 1.0 + 3.0 * (I1 - I3) / (lm * R);
  return f > 0.0 ? std::sqrt(g * R * f) : 0.0;
}

// Kepler case (§4): z(t) = z(0) cos(Ωt/2) + (2/Ω) z'(0) sin(Ωt/2), componentwise.
inline double kepler_oscillator(double z0, double dz0, double Omega, double t) {
  return z0 * std::cos(0.5 * Omega * t) + (Omega != 0.0 ? 2.0 / Omega * dz0 * std::sin(0.5 * Omega * t) : dz0 * t);
}

}  // namespace gyrostab::oracles
