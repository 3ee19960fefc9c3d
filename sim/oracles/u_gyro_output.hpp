// The book's U-gyro output (Magnus, Kreisel §15.4, (15.29)) and what a spring-restrained frame makes of it:
// the oracle of tests/oracle/u_gyro_test.cpp and the reference figures of the U-gyro scene.
//   (15.29)  M2 = H Ω [1 − ε cos 2γ],   ε = (A^R − B^R)/C^R,   H = C^R γ'
// The frame B̄ β'' + d2 β' + c2 β = M2, with B̄ the output-axis inertia averaged over a revolution, answers the
// mean with β0 = H Ω / c2 ((15.4), Ω3 = 0) and the twice-spin part with
//   β2 = ε H Ω / |c2 − B̄ (2γ')² + i 2γ' d2|.
// The inertia's own variation, I2 = B̄ − δ cos 2γ with δ = (A^R − B^R)/2, makes harmonics 0 and 4γ out of the
// 2γ motion; the 4γ part returns to 2γ at second order in δ. Harmonic balance of d/dt(I2 β') + d2 β' + c2 β,
// with D_m = c2 − B̄ m²ω² + i m ω d2 at ω = 2γ', gives (the mean exactly H Ω / c2)
//   β2 = ε H Ω / |D_1 − δ² ω⁴ / D_2|        (the next term is of order δ⁴ ω⁸ / (D_1 D_2² D_3)),
// so the first-order β2 above is off by about |δ² ω⁴ / (D_1 D_2)| (docs/models/u-gyro.md).
// Docs: docs/models/u-gyro.md
#pragma once

#include <cmath>
#include <complex>

#include "sim/models/u_gyro.hpp"

namespace gyrostab::oracles {

// (15.29) [N m].
inline double u_gyro_output_torque(const models::UGyroParams& p, double Omega, double gamma) {
  return p.H() * Omega * (1.0 - p.asymmetry() * std::cos(2.0 * gamma));
}

// The frame's receptance at ω [rad/N m]: 1/(c2 − B̄ ω² + i ω d2).
inline std::complex<double> u_gyro_frame_response(const models::UGyroParams& p, double omega) {
  return 1.0 / std::complex<double>(p.c2 - p.mean_output_inertia() * omega * omega, omega * p.d2);
}

// β0 = H Ω / c2 [rad].
inline double u_gyro_mean_output(const models::UGyroParams& p, double Omega) { return p.H() * Omega / p.c2; }

// |β2| = |ε| H Ω |G(2γ')| [rad].
inline double u_gyro_twice_spin_output(const models::UGyroParams& p, double Omega) {
  return std::fabs(p.asymmetry() * p.H() * Omega) * std::abs(u_gyro_frame_response(p, 2.0 * p.spin));
}

// β2 with the inertia's variation to second order [rad].
inline double u_gyro_twice_spin_output_coupled(const models::UGyroParams& p, double Omega) {
  const double w = 2.0 * p.spin, delta = 0.5 * (p.AR - p.BR);
  const std::complex<double> D1 = 1.0 / u_gyro_frame_response(p, w), D2 = 1.0 / u_gyro_frame_response(p, 2.0 * w);
  return std::fabs(p.asymmetry() * p.H() * Omega) / std::abs(D1 - delta * delta * w * w * w * w / D2);
}

// The first-order β2's relative error from the inertia's variation, |δ² ω⁴ / (D_1 D_2)| [-].
inline double u_gyro_inertia_coupling(const models::UGyroParams& p) {
  const double w = 2.0 * p.spin, delta = 0.5 * (p.AR - p.BR);
  return delta * delta * w * w * w * w * std::abs(u_gyro_frame_response(p, w) * u_gyro_frame_response(p, 2.0 * w));
}

}  // namespace gyrostab::oracles
