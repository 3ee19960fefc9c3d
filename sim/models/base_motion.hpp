// Prescribed motion of the suspension (the base that carries the outer gimbal bearing).
//
// A base motion supplies, at time t and in base axes: the base's absolute angular velocity Ω_B and its
// rate dΩ_B/dt [rad/s, rad/s²], and the specific force f_B divided by g (dimensionless; (0,0,1) for a base
// at rest with its axis 3 up). Gravity and base acceleration act on the gyro only through f_B.
// Conventions follow Magnus §10.2 (10.21)-(10.22): Ω = (Ω1, Ω2, Ω3) in the base (outer-gimbal) frame.
// Docs: docs/models/suspension-motion.md#base-at-rest-and-prescribed-rotation
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

struct BaseSample {
  dynamics::Vec3 w_B{dynamics::Vec3::Zero()};      // absolute angular velocity of the base, base axes [rad/s]
  dynamics::Vec3 dw_B{dynamics::Vec3::Zero()};     // its time derivative [rad/s²]
  dynamics::Vec3 up_B{dynamics::Vec3::UnitZ()};    // specific force / g, base axes [-]
};

// A base at rest; `up_B` fixes where "up" is, e.g. (cos δ, 0, sin δ) for Magnus's outer axis tilted by δ
// from the vertical (10.7).
struct FixedBase {
  dynamics::Vec3 up_B{dynamics::Vec3::UnitZ()};
  BaseSample operator()(double /*t*/) const { return {dynamics::Vec3::Zero(), dynamics::Vec3::Zero(), up_B}; }
};

// Harmonic rotation of the base about a fixed base axis n: angle φ(t) = Φ sin(ν t) (a ship rolling in a
// regular sea). The world "up" seen from the base turns back by φ: up_B = R(n, -φ) up_W.
struct HarmonicBaseRotation {
  dynamics::Vec3 axis_B{dynamics::Vec3::UnitX()};  // unit axis n in base axes
  double amplitude{0.1};                           // Φ [rad]
  double frequency{0.5};                           // ν [rad/s]
  dynamics::Vec3 up_W{dynamics::Vec3::UnitZ()};    // "up" in base axes when φ = 0

  BaseSample operator()(double t) const {
    // No roll: the base is at rest; the sin/cos and the rotation are skipped (a scene without base motion
    // does not pay for it per derivative evaluation), the sample equals the one computed with Φ = 0.
    if (amplitude == 0.0) return {dynamics::Vec3::Zero(), dynamics::Vec3::Zero(), up_W};
    const double s = std::sin(frequency * t), c = std::cos(frequency * t);
    const double phi = amplitude * s;
    BaseSample b;
    b.w_B = axis_B * (amplitude * frequency * c);
    b.dw_B = axis_B * (-amplitude * frequency * frequency * s);
    b.up_B = Eigen::AngleAxisd(-phi, axis_B) * up_W;
    return b;
  }
};

}  // namespace gyrostab::models
