// Translational harmonic vibration of the base (vertical and horizontal), entering the gyro through the
// specific force: Magnus 11.4.3 (11.53) a_i = s_i0 Ω² cos Ωt (anisoelastic drift), Chelnokov's vertical-line
// vibration of the pivot (Chelnokov §4; docs/models/suspension-motion.md). Base rotation is supplied
// separately; VibratingBase adds the two.
//
//   a_B(t) = Σₖ sₖ νₖ² cos(νₖ t + ψₖ)          acceleration of the suspension point, base axes [m/s²]
//            (displacement −Σ sₖ cos(νₖ t + ψₖ) [m]; sₖ is a vector: its direction picks vertical/horizontal)
//   up_B   = up_B(rotation) + a_B/g             specific force / g of models::BaseSample [-]
//
// Parameters per harmonic: displacement amplitude vector s [m] in base axes, ν [rad/s], ψ [rad]; g [m/s²].
// Assumptions: the vibration is along base-fixed directions and its displacement is small, so the transport
// terms of a rotating base (2ω × ṡ, ω̇ × s, ω × (ω × s), all ∝ s) are neglected; no angular vibration
// (use prescribed_base_rotation.hpp). Stateless, allocation-free, K sin/cos per call.
// Test: tests/unit/base_motion_generators_test.cpp (a_B = second derivative of the displacement; up_B
// offset).
// Docs: docs/models/suspension-motion.md#vibration
#pragma once

#include <array>
#include <cmath>

#include "sim/models/base_motion.hpp"
#include "sim/motion/wave_transfer.hpp"

namespace gyrostab::motion {

struct VibrationHarmonic {
  dynamics::Vec3 amplitude_B{dynamics::Vec3::Zero()};  // s [m]
  double frequency{0.0};                               // ν [rad/s]
  double phase{0.0};                                   // ψ [rad]
};

template <int K = 3>
struct BaseVibration {
  std::array<VibrationHarmonic, K> harmonics{};
  int count{0};

  dynamics::Vec3 displacement_B(double t) const {  // [m]
    dynamics::Vec3 x = dynamics::Vec3::Zero();
    for (int k = 0; k < count; ++k)
      x -= harmonics[k].amplitude_B * std::cos(harmonics[k].frequency * t + harmonics[k].phase);
    return x;
  }
  dynamics::Vec3 acceleration_B(double t) const {  // [m/s²]
    dynamics::Vec3 a = dynamics::Vec3::Zero();
    for (int k = 0; k < count; ++k) {
      const VibrationHarmonic& h = harmonics[k];
      a += h.amplitude_B * (h.frequency * h.frequency * std::cos(h.frequency * t + h.phase));
    }
    return a;
  }
};

// A rotating base (any callable t ↦ models::BaseSample: FixedBase, HarmonicBaseRotation,
// PrescribedBaseRotation) with a translational vibration of its suspension point.
template <class Rotation = models::FixedBase, int K = 3>
struct VibratingBase {
  Rotation rotation{};
  BaseVibration<K> vibration{};
  double g{kStandardGravity};  // [m/s²]

  models::BaseSample operator()(double t) const {
    models::BaseSample b = rotation(t);
    b.up_B += vibration.acceleration_B(t) / g;
    return b;
  }
};

}  // namespace gyrostab::motion
