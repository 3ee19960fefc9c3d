// The servo gyro's measurement over the steady drive (Magnus §14.4, (14.42)-(14.44)): fits against the drive
// angle β — the motor's phase, not the clock's. With α = α_A cos(β − φ), M1^KR = −H cosβ β' and (14.43)
// M2^K = ½ H Ω α_A (sin(2β − φ) − sin φ), least-squares fits of a mean and the β harmonic of α and M1 and of a
// mean and the 2β harmonic of M2 (harmonic_fit.hpp) give α_A, φ, the amplitude of M1 and the mean and 2β
// harmonic of M2 with no leak of a mean into a harmonic, whatever the window and the sampling in β; the sensor
// noise in M2 averages out. Allocation-free; read by tools/devices/servo_gyro/servo_gyro_run.cpp.
// Test: tests/unit/harmonic_fit_test.cpp (a mean 10³ times the harmonic over non-whole revolutions); the figures
// of sim/scenes/servo-gyro.toml run in tests/determinism.
#pragma once

#include <cmath>
#include <cstdint>

#include "sim/analysis/harmonic_fit.hpp"

namespace gyrostab::analysis {

struct DriveSums {
  std::int64_t n{0};
  HarmonicFit alpha_fit{}, m1_fit{}, m2_fit{};      // α, M1 against β; M2 against 2β
  double m1_peak{0.0}, m2_peak{0.0};                // max |M1^KR|, max |M2| [N m]
  double rate{0.0}, rate_error_peak{0.0};           // Σ β', max |β' − Ω| [rad/s]
  double motor_power{0.0}, dissipation{0.0};        // Σ M2 β', Σ (d1 α'² + d2 β'²) [W]

  // One tick: the state reached [rad, rad/s], M1 there and the axis-2 torque held over the tick [N m], the
  // rate reference Ω [rad/s] and the damping d1, d2 [N m s/rad].
  void add(double alpha, double beta, double alpha_rate, double beta_rate, double M1, double M2, double Omega,
           double d1, double d2) {
    ++n;
    alpha_fit.add(beta, alpha);
    m1_fit.add(beta, M1);
    m2_fit.add(2.0 * beta, M2);
    m1_peak = std::fmax(m1_peak, std::fabs(M1));
    m2_peak = std::fmax(m2_peak, std::fabs(M2));
    rate += beta_rate;
    rate_error_peak = std::fmax(rate_error_peak, std::fabs(beta_rate - Omega));
    motor_power += M2 * beta_rate;
    dissipation += d1 * alpha_rate * alpha_rate + d2 * beta_rate * beta_rate;
  }
};

}  // namespace gyrostab::analysis
