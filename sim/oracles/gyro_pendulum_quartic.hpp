// Closed forms for the linear gimbal gyro pendulum with a horizontal outer axis, Magnus (10.11)-(10.17):
//   A α'' + H β' - Gs α = M1,   B β'' - H α' - Gs β = M2
// and its pure modes, used as test oracles and by the demo.
// Docs: docs/models/gimbal-gyro.md#nutation-precession-and-the-characteristic-equation
#pragma once

#include <cmath>

namespace gyrostab::oracles {

struct PendulumFrequencies {
  double nutation;    // ω^N [rad/s]
  double precession;  // ω^P [rad/s]
};

// Roots of the exact characteristic equation (10.14): AB λ⁴ + [H² - Gs(A + B)] λ² + G²s² = 0, λ = iω.
inline PendulumFrequencies gyro_pendulum_frequencies(double A, double B, double H, double Gs) {
  const double c = H * H - Gs * (A + B);
  const double disc = std::sqrt(1.0 - 4.0 * A * B * Gs * Gs / (c * c));
  const double k = c / (2.0 * A * B);
  // ω_P² = (Gs)²/(AB ω_N²) avoids the cancellation in k (1 - disc) when ω_P ≪ ω_N.
  const double wn2 = k * (1.0 + disc);
  return {std::sqrt(wn2), std::abs(Gs) / std::sqrt(A * B * wn2)};
}

// Initial rates that excite only the mode of frequency ω from α(0) = α0, β(0) = 0, α'(0) = 0:
// β'(0) = H ω² α0 / (B ω² + Gs) (from the second row of (10.11) with λ = iω).
inline double pure_mode_beta_rate(double B, double H, double Gs, double omega, double alpha0) {
  return H * omega * omega * alpha0 / (B * omega * omega + Gs);
}

}  // namespace gyrostab::oracles
