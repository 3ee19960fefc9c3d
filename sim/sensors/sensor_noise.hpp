// Additive errors of a sampled sensor: white noise, constant bias and a bias random walk, drawn from the
// caller's seeded generator (random/seeded_rng.hpp). Continuous-time densities in the IEEE Std 952 / Kalibr
// "IMU noise model" convention, turned into per-sample standard deviations for the sample period T:
//
//   e_k = b_k + σ_w ξ_k,         σ_w = N / √T        N  white-noise density [unit/√Hz] (a rate gyro's angle
//   random
//                                                       walk [rad/s/√Hz]: the integrated angle spreads as
//                                                       N√t)
//   b_{k+1} = b_k + σ_b ζ_k,     σ_b = K √T          K  bias random-walk density [unit/s/√Hz] (rate random
//   walk) b_0 = b                                          b  constant (turn-on) bias [unit]
//
// ξ, ζ ~ N(0, 1) independent. Draw order per sample (determinism): ξ_k if N > 0, then ζ_k if K > 0 — a zero
// density draws nothing. Hot path: ≤ 2 Gaussians per sample, allocation-free.
// Test: tests/unit/sensors_test.cpp (σ_w against N/√T within a chi-square bound, bias increments against
// K√T).
// Docs: docs/models/rate-gyros.md#measurement-chain
#pragma once

#include <cmath>

#include "sim/random/seeded_rng.hpp"

namespace gyrostab::sensors {

struct SensorNoiseParams {
  double white_density{0.0};     // N [unit/√Hz]
  double bias{0.0};              // b [unit]
  double bias_random_walk{0.0};  // K [unit/s/√Hz]
};

class SensorNoise {
 public:
  SensorNoise(const SensorNoiseParams& p, double sample_period)
      : white_sd_(p.white_density / std::sqrt(sample_period)),
        bias_step_sd_(p.bias_random_walk * std::sqrt(sample_period)),
        bias_(p.bias) {}

  // The error to add to sample k; advances the bias to k + 1.
  double sample(random::SeededRng& rng) {
    double e = bias_;
    if (white_sd_ > 0.0) e += white_sd_ * rng.gaussian();
    if (bias_step_sd_ > 0.0) bias_ += bias_step_sd_ * rng.gaussian();
    return e;
  }

  double bias() const { return bias_; }                  // b_k for the next sample [unit]
  double white_sd() const { return white_sd_; }          // σ_w [unit]
  double bias_step_sd() const { return bias_step_sd_; }  // σ_b [unit]

 private:
  double white_sd_;
  double bias_step_sd_;
  double bias_;
};

}  // namespace gyrostab::sensors
