// Single-axis rate gyro as the controller sees it: the inertial angular velocity of its case about the input
// axis n_B, through the instrument's bandwidth, with scale-factor error, bias (constant + random walk), white
// noise and a digital output stage. The dynamics behind the bandwidth are Magnus's P-gyro (15.1)-(15.4):
// B β'' + d2 β' + c2 β = H Ω1 reads β ≈ (H/c2) Ω1 through a second-order filter, ωn = √(c2/B) (10-60 Hz).
//
//   y_k = Q( (1 + s_f) L(n_B · ω_B)_k + e_k )
//     L  exact discrete low-pass of first or second order (sensor_lowpass.hpp)     [rad/s]
//     e  bias b_k + white noise σ_w ξ_k, σ_w = N/√T (sensor_noise.hpp)            [rad/s]
//     Q  saturation at ± full scale and rounding to the LSB (output_quantizer.hpp)   [rad/s]
//
// Parameters: n_B unit input axis (case = base axes), T sample period [s], s_f [-], the filter (f_bw [Hz],
// ζ), N [rad/s/√Hz], b [rad/s], K [rad/s²/√Hz], LSB and full scale [rad/s]. Defaults: an ideal gyro (no
// filter, no errors). Assumptions: no g-sensitivity, no cross-axis coupling, case rigidly on the base. Hot
// path: measure() is allocation-free, ≤ 2 Gaussians from the caller's generator (draw order: sensor_noise).
// Test: tests/unit/sensors_test.cpp (DC gain 1, −3 dB at f_bw, σ_w = N/√T, bias), determinism and alloc
// tests.
// Docs: docs/models/rate-gyros.md#measurement-chain
#pragma once

#include "sim/models/base_motion.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/output_quantizer.hpp"
#include "sim/sensors/sensor_lowpass.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::sensors {

struct RateGyroParams {
  dynamics::Vec3 input_axis_B{dynamics::Vec3::UnitX()};  // n_B [-]
  double sample_period{1e-3};                            // T [s]
  double scale_factor_error{0.0};                        // s_f [-]
  LowpassParams bandwidth{};                             // f_bw [Hz], ζ [-]
  SensorNoiseParams noise{};                             // N [rad/s/√Hz], b [rad/s], K [rad/s²/√Hz]
  OutputQuantizer output{};                              // LSB, full scale [rad/s]
};

class RateGyro {
 public:
  explicit RateGyro(const RateGyroParams& p = {})
      : p_(p), filter_(p.bandwidth, p.sample_period), noise_(p.noise, p.sample_period) {}

  // Steady state at a true rate [rad/s] (no transient at start-up).
  void reset(double rate) { filter_.reset(rate); }

  // One sample from the true rate about the input axis [rad/s].
  double measure(double rate, random::SeededRng& rng) {
    const double y = (1.0 + p_.scale_factor_error) * filter_.update(rate);
    return p_.output(y + noise_.sample(rng));
  }
  // One sample from the base motion (the case's angular velocity).
  double measure(const models::BaseSample& base, random::SeededRng& rng) {
    return measure(p_.input_axis_B.dot(base.w_B), rng);
  }

  const RateGyroParams& params() const { return p_; }
  const SensorLowpass& filter() const { return filter_; }
  const SensorNoise& noise() const { return noise_; }

 private:
  RateGyroParams p_;
  SensorLowpass filter_;
  SensorNoise noise_;
};

}  // namespace gyrostab::sensors
