// Closed forms of Magnus §15.5 (vibration effects on rate gyros; coning error), (15.30)-(15.42): the oracle
// of tests/oracle/coning_test.cpp and the reference figures of the coning scenes.
//
// Vibration of the gyro case: Ω1 = Ω10 cos νt about the input axis, Ω3 = Ω30 cos(νt − ε) about the spin axis
// (ε = 0: planar, the book's (15.36); ε ≠ 0: conical). The effective input axis tilts by β1 = Re(G(iν) Ω̂1),
// G(s) = H/(B s² + d2 s + c2); the tilt times the rate about the spin axis is a torque −H Ω3 β1 with mean
// −½ H Ω10 Ω30 Re(G e^{iε}), which the instrument reads as a rate (P: through c2/H, exactly at DC; I: through
// d2/H on β'):
//   ω̄_err = −½ Ω10 Ω30 [Re(G(iν) e^{iε}) + (A_g − C_g) cos ε / H]                                    (a)
// P, quasi-static (G = H/c2), planar:  ω̄_err = −H Ω10 Ω30/(2 c2)   (15.39)
//   Ω10 = Ω0 cos δ, Ω30 = Ω0 sin δ:    −H Ω0² sin 2δ/(4 c2)          (15.40);  Ω0 = Φ ν:  −H Φ² ν² sin 2δ/(4 c2)  (15.41)
// I, ideal (B = 0, G = H/(i d2 ν)):    ω̄_err = −H Ω10 Ω30 sin ε/(2 d2 ν): zero when planar (15.42); the
// area the effective axis sweeps per cycle against the case rotation γ̃ = ∫Ω3 dt is A = −ω̄_err · 2π/ν.
// Neglected in (a): terms of fourth order in the vibration, relative size (H Ω0/c2)² (P) or (H Ω0/(d2 ν))²
// (I), i.e. β1² (docs/models/coning.md).
//
// Goodman–Robinson (15.30)-(15.35): a frame whose axis 3' runs once round a closed cone of spherical area A
// (encircling the reference pole n times, n = 0 or ±1) in time T turns about 3' (Euler angle φ) by
//   Δφ = ∫ω3' dt + A − 2π n;   slaved to ω3' ≡ 0:  Δφ = A − 2π n.
// A level platform at rest on the Earth at latitude λ over a sidereal day: A = 2π(1 − sin λ), n = 1:
//   Δφ = −2π sin λ (15.35).
// Docs: docs/models/coning.md
#pragma once

#include <cmath>
#include <complex>
#include <numbers>

#include "sim/sensors/single_axis_gyro_coning.hpp"

namespace gyrostab::oracles {

// G(iν) = H/(c2 − B ν² + i d2 ν) [rad per rad/s].
inline std::complex<double> coning_gyro_response(const sensors::ConingGyroParams& p, double nu) {
  const sensors::SingleAxisGyroParams& g = p.gyro;
  return g.H / std::complex<double>(g.c2 - g.B * nu * nu, g.d2 * nu);
}

// (a) with the input-axis amplitude scaled by the complex factor S (1: open loop; the closed loop's
// sensitivity at ν otherwise) [rad/s].
inline double coning_rate_first_order(const sensors::ConingGyroParams& p, double Omega10, double Omega30, double nu,
                                      double epsilon, std::complex<double> S = 1.0) {
  const std::complex<double> e{std::cos(epsilon), std::sin(epsilon)};
  return -0.5 * Omega10 * Omega30 *
         (std::real(coning_gyro_response(p, nu) * S * e) + p.inertia_difference * std::real(S * e) / p.gyro.H);
}

// (15.39) [rad/s].
inline double coning_rate_p_book(double H, double c2, double Omega10, double Omega30) {
  return -H * Omega10 * Omega30 / (2.0 * c2);
}
// (15.41): Φ angular amplitude [rad], ν [rad/s], δ the vibration axis from the input axis towards the spin
// axis [rad].
inline double coning_rate_p_book_amplitude(double H, double c2, double Phi, double nu, double delta) {
  return -H * Phi * Phi * nu * nu * std::sin(2.0 * delta) / (4.0 * c2);
}
// The ideal I-gyro [rad/s].
inline double coning_rate_i_ideal(double H, double d2, double Omega10, double Omega30, double nu, double epsilon) {
  return -H * Omega10 * Omega30 * std::sin(epsilon) / (2.0 * d2 * nu);
}

// Sensitivity S(iν) = 1/(1 + L) of the platform loop: L(s) = Ĝ(s) (k_p + k_i/s) e^{−s τ}/(s (1 + τ_d s)), Ĝ the
// gyro's normalized response (P: c2/(B s² + d2 s + c2), I: d2/(B s + d2)), k_p [1/s], k_i [1/s²] the loop's
// gains on the indicated angle, τ_d the drive's time constant [s], τ the sampling delay [s].
inline std::complex<double> coning_loop_sensitivity(const sensors::ConingGyroParams& p, double kp, double ki,
                                                    double tau_drive, double delay, double nu) {
  const std::complex<double> s{0.0, nu};
  const sensors::SingleAxisGyroParams& g = p.gyro;
  const std::complex<double> Ghat = g.c2 > 0.0 ? g.c2 / (g.B * s * s + g.d2 * s + g.c2) : g.d2 / (g.B * s + g.d2);
  const std::complex<double> L = Ghat * (kp + ki / s) * std::exp(-s * delay) / (s * (1.0 + tau_drive * s));
  return 1.0 / (1.0 + L);
}

// The same sensitivity for the loop as the firmware runs it (docs/sampled-data.md), at the vibration's own
// frequency (the aliases at ν ± 2πk/T are left out: the loop's gain there is below k_p T/(2π) ≈ 1e-4): the
// gyro's reading sampled every T; the indicated angle θ_k = θ_{k−1} + scale β_k T (P-gyro: T z/(z − 1)) or
// θ = scale β (I-gyro); the PI of drive_loops.hpp, u_k = k_p e_k + I_k, I_{k+1} = I_k + k_i T e_k:
// k_p + k_i T/(z − 1); the command held over a period (its fundamental (1 − e^{−iνT})/(iνT)) and applied
// `latency` periods later (the law's period T); z = e^{iνT}. For the P-gyro the sum's T z/(z − 1) and the hold combine to 1/(iν)
// exactly: the half-period lag that the delay (L + ½) T of coning_loop_sensitivity gives the whole loop acts on
// the integral term only.
inline std::complex<double> coning_loop_sensitivity_sampled(const sensors::ConingGyroParams& p, double kp, double ki,
                                                            double tau_drive, double T, double latency, double nu) {
  const std::complex<double> s{0.0, nu};
  const std::complex<double> z = std::exp(s * T);
  const sensors::SingleAxisGyroParams& g = p.gyro;
  const bool p_gyro = g.c2 > 0.0;
  const std::complex<double> Ghat = p_gyro ? g.c2 / (g.B * s * s + g.d2 * s + g.c2) : g.d2 / (g.B * s + g.d2);
  const std::complex<double> hold = (1.0 - 1.0 / z) / (s * T);
  // From the platform's rate to the indicated angle: the P-gyro's sum of its rate reading, or the I-gyro's
  // own integration (continuous, ahead of the sampler).
  const std::complex<double> to_angle = p_gyro ? T * z / (z - 1.0) : 1.0 / s;
  const std::complex<double> C = kp + ki * T / (z - 1.0);
  const std::complex<double> L =
      Ghat * to_angle * C * std::exp(-s * (latency * T)) * hold / (1.0 + tau_drive * s);
  return 1.0 / (1.0 + L);
}

// Goodman–Robinson: Δφ = A − 2π n for a frame slaved to ω3' ≡ 0 [rad].
inline double goodman_robinson_turn(double area, int n) { return area - 2.0 * std::numbers::pi * n; }
// Spherical area of the cap of half-angle ϑ0 [sr].
inline double cap_area(double theta0) { return 2.0 * std::numbers::pi * (1.0 - std::cos(theta0)); }
// (15.35): a level platform at latitude λ over a sidereal day, azimuth relative to the Earth [rad].
inline double earth_platform_azimuth_turn(double latitude) { return -2.0 * std::numbers::pi * std::sin(latitude); }

}  // namespace gyrostab::oracles
