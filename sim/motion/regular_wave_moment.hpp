// Regular wave moment on a ship, Magnus 14.2 (14.9): E(t) = E0 cos(ω t + ψ), the external roll torque of the
// ship roll damper (14.8)  A φ'' + d1 φ' + c φ + H β' = E(t); its steady response is (14.10)-(14.11).
//
// Parameters: E0 amplitude [N m], ω wave encounter frequency [rad/s], ψ phase [rad] (0 in the book).
// From one regular wave of amplitude a [m] in deep water, the effective-wave-slope model (wave_transfer.hpp)
// gives E0 = c κ (ω²/g) a: from_wave(). Stateless; one cos per call. Test:
// tests/unit/base_motion_generators_test.cpp.
// Docs: docs/models/suspension-motion.md#waves
#pragma once

#include <cmath>

#include "sim/motion/wave_transfer.hpp"

namespace gyrostab::motion {

struct RegularWaveMoment {
  double E0{1.0};     // [N m]
  double omega{0.5};  // [rad/s]
  double phase{0.0};  // [rad]

  // E0 = c κ (ω²/g) a for roll stiffness c [N m/rad], effective-slope coefficient κ [-], wave amplitude a
  // [m].
  static RegularWaveMoment from_wave(double c, double kappa, double wave_amplitude, double omega,
                                     double g = kStandardGravity) {
    return {c * kappa * omega * omega / g * wave_amplitude, omega, 0.0};
  }

  double operator()(double t) const { return E0 * std::cos(omega * t + phase); }     // E [N m]
  double rate(double t) const { return -E0 * omega * std::sin(omega * t + phase); }  // dE/dt [N m/s]
};

}  // namespace gyrostab::motion
