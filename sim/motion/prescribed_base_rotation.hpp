// Prescribed rotation of the base (suspension) from yaw, pitch and roll angles that are each a constant, a
// constant rate and a sum of ≤ K harmonics: a ship rolling and pitching in a sea of several periods, a
// turning ship (constant yaw rate Ω3, Magnus 14.1-14.2 curve running), angular vibration of the case (15.5,
// small amplitudes). Generalizes models::HarmonicBaseRotation (one harmonic about one axis), which it
// reproduces for roll only. Returns models::BaseSample (base_motion.hpp) for the gimbal and device models.
//
// Attitude (Magnus §12.1, (12.2)-(12.3): a^F = Rz(ψ) Ry(ϑ) Rx(φ)):  R_WB = Rz(ψ) Ry(θ) Rx(φ), base = world
// axes at zero angles, world axis 3 up.
// Each angle  a(t) = a0 + ȧ0 t + Σₖ Aₖ sin(νₖ t + ψₖ), with analytic a', a''.
//   ω_B = (φ' − ψ' sθ,  θ' cφ + ψ' cθ sφ,  −θ' sφ + ψ' cθ cφ)                             [rad/s]
//   ω̇_B = (φ'' − ψ'' sθ − ψ'θ' cθ,
//          θ'' cφ − θ'φ' sφ + ψ'' cθ sφ − ψ'θ' sθ sφ + ψ'φ' cθ cφ,
//          −θ'' sφ − θ'φ' cφ + ψ'' cθ cφ − ψ'θ' sθ cφ − ψ'φ' cθ sφ)                      [rad/s²]
//   up_B = R_WBᵀ e₃ + a_B/g = (−sθ, cθ sφ, cθ cφ) + (ω̇_B × r_B + ω_B × (ω_B × r_B))/g      [-]
// where r_B [m] is the lever arm from the centre of rotation to the suspension point (e.g. a gyro h above the
// roll axis sees the horizontal acceleration hφ'' of Magnus 13.3.3); r_B = 0 puts the suspension on the axis.
//
// Parameters: angles in [rad], rates [rad/s], frequencies [rad/s], lever arm [m], g [m/s²].
// Assumptions: the centre of rotation does not translate (add heave/sway with base_vibration.hpp); θ away
// from ±90° is not required (no Euler-rate inversion is done). Stateless, allocation-free, 3K+6 sin/cos per
// call. Test: tests/unit/base_motion_generators_test.cpp (ω_B and ω̇_B against finite differences of the
// attitude).
// Docs: docs/models/suspension-motion.md#base-at-rest-and-prescribed-rotation
#pragma once

#include <array>
#include <cmath>

#include "sim/models/base_motion.hpp"
#include "sim/motion/wave_transfer.hpp"

namespace gyrostab::motion {

struct AngleHarmonic {
  double amplitude{0.0};  // A [rad]
  double frequency{0.0};  // ν [rad/s]
  double phase{0.0};      // ψ [rad]
};

// a(t) = offset + rate·t + Σ A sin(ν t + ψ) over the first `count` harmonics.
template <int K = 4>
struct PrescribedAngle {
  double offset{0.0};  // [rad]
  double rate{0.0};    // [rad/s]
  std::array<AngleHarmonic, K> harmonics{};
  int count{0};

  struct Value {
    double angle, rate, accel;  // [rad], [rad/s], [rad/s²]
  };
  Value operator()(double t) const {
    Value v{offset + rate * t, rate, 0.0};
    for (int k = 0; k < count; ++k) {
      const AngleHarmonic& h = harmonics[k];
      const double s = std::sin(h.frequency * t + h.phase), c = std::cos(h.frequency * t + h.phase);
      v.angle += h.amplitude * s;
      v.rate += h.amplitude * h.frequency * c;
      v.accel -= h.amplitude * h.frequency * h.frequency * s;
    }
    return v;
  }
};

template <int K = 4>
struct PrescribedBaseRotation {
  PrescribedAngle<K> yaw{}, pitch{}, roll{};  // ψ about world 3, θ about the yawed 2, φ about base 1
  dynamics::Vec3 lever_arm_B{dynamics::Vec3::Zero()};  // r_B [m]
  double g{kStandardGravity};                          // [m/s²]

  models::BaseSample operator()(double t) const {
    const auto y = yaw(t), p = pitch(t), r = roll(t);
    const double sf = std::sin(r.angle), cf = std::cos(r.angle);
    const double st = std::sin(p.angle), ct = std::cos(p.angle);
    models::BaseSample b;
    b.w_B = {r.rate - y.rate * st, p.rate * cf + y.rate * ct * sf, -p.rate * sf + y.rate * ct * cf};
    b.dw_B = {r.accel - y.accel * st - y.rate * p.rate * ct,
              p.accel * cf - p.rate * r.rate * sf + y.accel * ct * sf - y.rate * p.rate * st * sf +
                  y.rate * r.rate * ct * cf,
              -p.accel * sf - p.rate * r.rate * cf + y.accel * ct * cf - y.rate * p.rate * st * cf -
                  y.rate * r.rate * ct * sf};
    b.up_B = {-st, ct * sf, ct * cf};
    if (!lever_arm_B.isZero(0.0)) {
      const dynamics::Vec3 a_B = b.dw_B.cross(lever_arm_B) + b.w_B.cross(b.w_B.cross(lever_arm_B));
      b.up_B += a_B / g;
    }
    return b;
  }

  // q_WB(t): the attitude itself, for logs and tests.
  dynamics::Quat attitude(double t) const {
    using Eigen::AngleAxisd;
    return dynamics::Quat(AngleAxisd(yaw(t).angle, dynamics::Vec3::UnitZ()) *
                          AngleAxisd(pitch(t).angle, dynamics::Vec3::UnitY()) *
                          AngleAxisd(roll(t).angle, dynamics::Vec3::UnitX()));
  }
};

}  // namespace gyrostab::motion
