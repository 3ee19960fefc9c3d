// The servo gyro's measurement over the steady drive (Magnus §14.4, (14.42)-(14.44)): sums against the drive
// angle β — the motor's phase, not the clock's. With α = α_A cos(β − φ), M1^KR = −H cosβ β' and (14.43)
// M2^K = ½ H Ω α_A (sin(2β − φ) − sin φ), the Fourier sums over whole revolutions give α_A, φ, the amplitude
// of M1 and the mean and 2β-harmonic of M2 exactly for sinusoids sampled uniformly in β (to O(rate ripple)
// otherwise), while the sensor noise in M2 averages out. Allocation-free; read by tools/devices/servo_gyro/servo_gyro_run.cpp.
// Test: none of its own yet; the figures of sim/scenes/servo-gyro.toml run in tests/determinism.
#pragma once

#include <cmath>
#include <cstdint>

namespace gyrostab::analysis {

struct DriveSums {
  std::int64_t n{0};
  double alpha_cos{0.0}, alpha_sin{0.0};            // Σ α cosβ, Σ α sinβ [rad]
  double m1_cos{0.0}, m1_sin{0.0};                  // Σ M1 cosβ, Σ M1 sinβ [N m]
  double m2_mean{0.0}, m2_cos2{0.0}, m2_sin2{0.0};  // Σ M2, Σ M2 cos2β, Σ M2 sin2β [N m]
  double m1_peak{0.0}, m2_peak{0.0};                // max |M1^KR|, max |M2| [N m]
  double rate{0.0}, rate_error_peak{0.0};           // Σ β', max |β' − Ω| [rad/s]
  double motor_power{0.0}, dissipation{0.0};        // Σ M2 β', Σ (d1 α'² + d2 β'²) [W]

  // One tick: the state reached [rad, rad/s], M1 there and the axis-2 torque held over the tick [N m], the
  // rate reference Ω [rad/s] and the damping d1, d2 [N m s/rad].
  void add(double alpha, double beta, double alpha_rate, double beta_rate, double M1, double M2, double Omega,
           double d1, double d2) {
    const double cb = std::cos(beta), sb = std::sin(beta);
    const double c2 = cb * cb - sb * sb, s2 = 2.0 * sb * cb;
    ++n;
    alpha_cos += alpha * cb;
    alpha_sin += alpha * sb;
    m1_cos += M1 * cb;
    m1_sin += M1 * sb;
    m2_mean += M2;
    m2_cos2 += M2 * c2;
    m2_sin2 += M2 * s2;
    m1_peak = std::fmax(m1_peak, std::fabs(M1));
    m2_peak = std::fmax(m2_peak, std::fabs(M2));
    rate += beta_rate;
    rate_error_peak = std::fmax(rate_error_peak, std::fabs(beta_rate - Omega));
    motor_power += M2 * beta_rate;
    dissipation += d1 * alpha_rate * alpha_rate + d2 * beta_rate * beta_rate;
  }
};

}  // namespace gyrostab::analysis
