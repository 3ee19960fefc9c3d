// Single-axis accelerometer: the specific force along its input axis (what a pendulum or a proof mass feels,
// gravity included: g up_B of models::BaseSample; Magnus 16's platform accelerometers b = v' − g(α − ϑ)),
// through a bandwidth, with scale-factor error, bias (constant + random walk), white noise and a digital
// output.
//
//   y_k = Q( (1 + s_f) L(g n_B · up_B)_k + e_k )        [m/s²]
//     L  exact discrete low-pass (sensor_lowpass.hpp); e  bias + white noise σ_w = N/√T (sensor_noise.hpp);
//     Q  saturation and LSB rounding (output_quantizer.hpp)
//
// Parameters: n_B unit input axis, T [s], g [m/s²], s_f [-], filter (f_bw [Hz], ζ), N [m/s²/√Hz] (velocity
// random walk), b [m/s²], K [m/s³/√Hz], LSB and full scale [m/s²]. Defaults: an ideal accelerometer.
// Assumptions: at the suspension point (lever arms are in the base motion), no cross-axis or rectification
// terms. Hot path: allocation-free, ≤ 2 Gaussians from the caller's generator.
// Test: tests/unit/sensors_test.cpp (reads g n·up at rest, bias), tests/alloc/motion_alloc_test.cpp.
// Docs: docs/models/rate-gyros.md#measurement-chain
#pragma once

#include "sim/models/base_motion.hpp"
#include "sim/motion/wave_transfer.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/output_quantizer.hpp"
#include "sim/sensors/sensor_lowpass.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::sensors {

struct AccelerometerParams {
  dynamics::Vec3 input_axis_B{dynamics::Vec3::UnitZ()};  // n_B [-]
  double sample_period{1e-3};                            // T [s]
  double g{motion::kStandardGravity};                    // [m/s²]
  double scale_factor_error{0.0};                        // s_f [-]
  LowpassParams bandwidth{};                             // f_bw [Hz], ζ [-]
  SensorNoiseParams noise{};                             // N [m/s²/√Hz], b [m/s²], K [m/s³/√Hz]
  OutputQuantizer output{};                              // LSB, full scale [m/s²]
};

class Accelerometer {
 public:
  explicit Accelerometer(const AccelerometerParams& p = {})
      : p_(p), filter_(p.bandwidth, p.sample_period), noise_(p.noise, p.sample_period) {}

  void reset(double specific_force) { filter_.reset(specific_force); }

  // One sample from the true specific force along the input axis [m/s²].
  double measure(double specific_force, random::SeededRng& rng) {
    const double y = (1.0 + p_.scale_factor_error) * filter_.update(specific_force);
    return p_.output(y + noise_.sample(rng));
  }
  double measure(const models::BaseSample& base, random::SeededRng& rng) {
    return measure(p_.g * p_.input_axis_B.dot(base.up_B), rng);
  }

  const AccelerometerParams& params() const { return p_; }
  const SensorNoise& noise() const { return noise_; }

 private:
  AccelerometerParams p_;
  SensorLowpass filter_;
  SensorNoise noise_;
};

}  // namespace gyrostab::sensors
