// The base motion a scene chooses, as one callable t ↦ models::BaseSample: a harmonic roll about one base axis
// (models::HarmonicBaseRotation), yaw/pitch/roll each with a rate and one harmonic and a lever arm
// (prescribed_base_rotation.hpp), or a recorded motion (recorded_motion.hpp); a translational vibration of the
// suspension point (base_vibration.hpp) may be added to the first two. Chosen at scene read time; a switch per
// call instead of one plant instantiation per kind (the models are templated on the base, the plants are not).
// Units as in the generators: rad, rad/s, m, m/s². Allocation-free, stateless, deterministic.
// Test: tests/unit/recorded_motion_test.cpp (recorded against prescribed), tests/unit/base_motion_generators_test.cpp.
// Docs: docs/models/suspension-motion.md
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "sim/models/base_motion.hpp"
#include "sim/motion/base_vibration.hpp"
#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/motion/recorded_motion.hpp"

namespace gyrostab::motion {

enum class BaseMotionKind : std::uint8_t { kHarmonicRoll, kPrescribed, kRecorded };

struct SceneBaseMotion {
  BaseMotionKind kind{BaseMotionKind::kHarmonicRoll};
  models::HarmonicBaseRotation harmonic{dynamics::Vec3::UnitX(), 0.0, 0.6, dynamics::Vec3::UnitZ()};
  PrescribedBaseRotation<1> prescribed{};
  BaseVibration<2> vibration{};  // heave (base axis 3) and sway (base axis 2); count 0: none
  RecordedMotion recorded{};

  models::BaseSample operator()(double t) const {
    models::BaseSample b;
    switch (kind) {
      case BaseMotionKind::kHarmonicRoll: b = harmonic(t); break;
      case BaseMotionKind::kPrescribed: b = prescribed(t); break;
      case BaseMotionKind::kRecorded: return recorded(t);
    }
    // Skipped when there is none, so a scene without vibration gives the bits it gave before it existed.
    if (vibration.count > 0) b.up_B += vibration.acceleration_B(t) / prescribed.g;
    return b;
  }

  // q_WB(t): the attitude, for the motion record (tools/motion_record_command.cpp) and tests.
  dynamics::Quat attitude(double t) const {
    switch (kind) {
      case BaseMotionKind::kHarmonicRoll:
        return dynamics::Quat(Eigen::AngleAxisd(harmonic.amplitude * std::sin(harmonic.frequency * t), harmonic.axis_B));
      case BaseMotionKind::kPrescribed: return prescribed.attitude(t);
      case BaseMotionKind::kRecorded: break;
    }
    return recorded.attitude(t);
  }

  // g [m/s²] that turns up_B into the specific force.
  double g() const { return kind == BaseMotionKind::kRecorded ? recorded.g() : prescribed.g; }

  // max |ω̇_B| per base axis over [0, duration] [rad/s²]: what a start-up check treats as a torque I ω̇.
  // Exact for the harmonic roll (Φ ν²); otherwise sampled on 4096 intervals (the generators' harmonics are far
  // slower than that grid at the scenes' durations) and, for a record, at its nodes too.
  dynamics::Vec3 peak_angular_accel_B(double duration_s) const {
    if (kind == BaseMotionKind::kHarmonicRoll) {
      return harmonic.axis_B.cwiseAbs() * (harmonic.amplitude * harmonic.frequency * harmonic.frequency);
    }
    dynamics::Vec3 m = dynamics::Vec3::Zero();
    constexpr int kN = 4096;
    for (int k = 0; k <= kN; ++k) m = m.cwiseMax((*this)(duration_s * k / kN).dw_B.cwiseAbs());
    if (kind == BaseMotionKind::kRecorded && recorded.record() != nullptr) {
      for (const dynamics::Vec3& d : recorded.record()->dw_B) m = m.cwiseMax(d.cwiseAbs());
    }
    return m;
  }
};

}  // namespace gyrostab::motion
