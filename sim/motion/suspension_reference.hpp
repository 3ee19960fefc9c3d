// What a pendulum/gyro model hung at the moving suspension point O needs from the motion generators, in one
// struct: the reference trihedron Z (Z3 = geocentric vertical, up) with its absolute angular velocity ω°_Z
// and ω°_Z' (Chelnokov (1.7)), the absolute acceleration w_Z and specific force a_Z = w_Z − g_Z of O
// (Chelnokov (1.6), (1.9)), the same specific force and the vertical in inertial axes, and GM/r³ (the
// gravity-gradient strength, g/R on the Earth's surface; Magnus (12.57), Chelnokov's U').
// Adapters: EarthReference (sim/motion/earth_vehicle.hpp, any of its trihedra), KeplerReference
// (sim/motion/kepler_orbit.hpp, orbital trihedron), and SampledReference, which holds one sample per step
// and interpolates linearly in between (what the scenes use: the generator costs more than the models).
// Units: rad/s, rad/s², m/s², 1/s². Frames as in earth_vehicle.hpp (x_I = q_IZ x_Z). Allocation-free.
// Docs: docs/models/suspension-motion.md#suspension-reference
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"
#include "sim/motion/earth_vehicle.hpp"
#include "sim/motion/kepler_orbit.hpp"

namespace gyrostab::motion {

struct SuspensionSample {
  dynamics::Quat q_IZ{dynamics::Quat::Identity()};  // reference trihedron Z
  dynamics::Vec3 w_Z{dynamics::Vec3::Zero()};       // ω°_Z: absolute angular velocity of Z, Z axes [rad/s]
  dynamics::Vec3 dw_Z{dynamics::Vec3::Zero()};      // ω°_Z' [rad/s²]
  dynamics::Vec3 a_Z{dynamics::Vec3::Zero()};       // absolute acceleration of O (Chelnokov w) [m/s²]
  dynamics::Vec3 f_Z{dynamics::Vec3::UnitZ()};      // specific force a_abs − g_grav (Chelnokov a) [m/s²]
  dynamics::Vec3 v_Z{dynamics::Vec3::Zero()};       // absolute velocity of O [m/s]
  dynamics::Vec3 f_I{dynamics::Vec3::UnitZ()};      // specific force, inertial axes [m/s²]
  dynamics::Vec3 up_I{dynamics::Vec3::UnitZ()};     // geocentric vertical, inertial axes [-]
  double gm_r3{0.0};                                // GM/r³ at O [1/s²]
};

inline SuspensionSample suspension_from(const Trihedron& Z, double gm_r3) {
  SuspensionSample s;
  s.q_IZ = Z.q_IZ;
  s.w_Z = Z.w_IZ_Z;
  s.dw_Z = Z.dw_IZ_Z;
  s.a_Z = Z.a_Z;
  s.f_Z = Z.f_Z;
  s.v_Z = Z.v_Z;
  s.f_I = Z.q_IZ * Z.f_Z;
  s.up_I = Z.q_IZ * dynamics::Vec3::UnitZ();
  s.gm_r3 = gm_r3;
  return s;
}

enum class ReferenceTrihedron { kGeographic, kTrack, kAzimuthFree, kDarboux };

inline const Trihedron& pick_trihedron(const EarthVehicleSample& s, ReferenceTrihedron which) {
  switch (which) {
    case ReferenceTrihedron::kGeographic: return s.geographic;
    case ReferenceTrihedron::kTrack: return s.track;
    case ReferenceTrihedron::kDarboux: return s.darboux;
    case ReferenceTrihedron::kAzimuthFree: break;
  }
  return s.azimuth_free;
}

// The vehicle's motion, sampled exactly at every call (tests; ~40 trig calls per call). Call begin_step(t)
// before each integrator step: every stage of the step then samples the segment that contains t, so a
// step ending on a manoeuvre corner sees the left limit there (the accelerations jump at corners);
// without it (segment = −1) each call picks the segment of its own time.
template <class Vehicle>
struct EarthReference {
  const Vehicle* vehicle{nullptr};
  ReferenceTrihedron trihedron{ReferenceTrihedron::kAzimuthFree};
  int segment{-1};

  void begin_step(double t) { segment = vehicle->segment_at(t); }

  SuspensionSample operator()(double t) const {
    const EarthVehicleSample s = segment < 0 ? vehicle->sample(t) : vehicle->sample_in_segment(segment, t);
    const EarthParams& e = vehicle->earth();
    return suspension_from(pick_trihedron(s, trihedron), e.gravity / e.radius);
  }
};

struct KeplerReference {
  const KeplerOrbit* orbit{nullptr};
  SuspensionSample operator()(double t) const {
    const KeplerSample s = orbit->sample(t);
    return suspension_from(s.orbital, orbit->params().gm / (s.radius * s.radius * s.radius));
  }
};

// One sample at each end of the current step [t0, t0 + h], linear in between (q_IZ: the start's; up_I
// renormalized). Error of the interpolated inputs: h²/8 × their second derivative (e.g. a 250 m/s vehicle
// turning at 0.05 rad/s, h = 0.1 s: |f''| = v r³ = 0.03 m/s² → 4e-5 m/s²).
struct SampledReference {
  double t0{0.0};
  double h{0.0};  // 0: hold s0
  SuspensionSample s0{}, s1{};

  void hold(const SuspensionSample& s) {
    s0 = s;
    s1 = s;
    h = 0.0;
  }
  SuspensionSample operator()(double t) const {
    if (!(h > 0.0)) return s0;
    const double w = (t - t0) / h;
    SuspensionSample s = s0;
    s.w_Z += w * (s1.w_Z - s0.w_Z);
    s.dw_Z += w * (s1.dw_Z - s0.dw_Z);
    s.a_Z += w * (s1.a_Z - s0.a_Z);
    s.f_Z += w * (s1.f_Z - s0.f_Z);
    s.v_Z += w * (s1.v_Z - s0.v_Z);
    s.f_I += w * (s1.f_I - s0.f_I);
    s.up_I += w * (s1.up_I - s0.up_I);
    s.up_I.normalize();
    s.gm_r3 += w * (s1.gm_r3 - s0.gm_r3);
    return s;
  }
};

}  // namespace gyrostab::motion
