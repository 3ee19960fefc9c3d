// A local-level inertial platform being aligned on a base at rest on the rotating Earth, as a scene runs it
// (Magnus §16.5, (16.52)): the platform of sim/models/platform_alignment.hpp (its attitude q_GP integrated by
// RK4 with the scene's sub-steps from the held gyro torquing commands plus drift), the base's small motion
// (rocking about its gear with the platform a lever arm above it, and a translational sway/heave: wind gusts
// on a parked aircraft, sim/motion/prescribed_base_rotation.hpp and base_vibration.hpp), which reaches the
// platform only as specific force, and three accelerometers (sim/sensors/accelerometer.hpp: bias in the model,
// white noise here) sampled at the tick's start.
//   f_G(t) = g e3 + R_GW R_WB(t) (a_rock,B(t) + a_vib,B(t))
// W = the base's level frame (W1 = its heading, clockwise from north), R_WB from the rocking generator.
//
// State: q_GP (x, y, z, w) [-]. Frames: the platform alignment's own (tools/devices/platform_alignment/
// platform_alignment_signals.toml, docs/icd/platform_alignment.md): in, east_torquer_Nm, north_torquer_Nm =
// torquers of the east and north gyros M [N m] (ω = −M/H); zenith_torquer_V = the zenith gyro's torquer
// voltage u [V] (ω = K_Z u); out, theta_east_rad = a_N/g0, theta_north_rad = −a_E/g0 (the apparent tilts about
// the east and north axes, g0 = 9.80665 m/s²) [rad].
// Random streams of the scene seed (seeded_rng.hpp): 1, 2, 3 the east, north and up accelerometers.
// Allocation-free after construction. Docs: docs/models/platform-alignment.md. Oracle:
// tests/oracle/platform_alignment_test.cpp; the shipped scenes run in tests/determinism and tests/alloc.
#pragma once

#include <array>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/platform_alignment_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/platform_alignment.hpp"
#include "sim/motion/base_vibration.hpp"
#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/accelerometer.hpp"

namespace gyrostab::plants {

inline constexpr double kAlignmentGravityScale = 9.80665;  // g0 of the apparent tilts [m/s²]

struct AlignmentBaseMotion {
  double heading{0.0};                              // the base's heading, clockwise from north [rad]
  motion::PrescribedBaseRotation<1> rocking{};      // roll/pitch about the gear, lever arm to the platform
  motion::BaseVibration<2> vibration{};             // sway (base axis 2), heave (axis 3)

  bool still() const { return rocking.roll.count == 0 && rocking.pitch.count == 0 && rocking.yaw.count == 0 &&
                              vibration.count == 0; }
  // The specific force at the platform, G axes [m/s²], for gravity g.
  dynamics::Vec3 specific_force_G(double t, double g) const {
    if (still()) return {0.0, 0.0, g};
    const models::BaseSample b = rocking(t);
    const dynamics::Vec3& r = rocking.lever_arm_B;
    const dynamics::Vec3 a_B = b.dw_B.cross(r) + b.w_B.cross(b.w_B.cross(r)) + vibration.acceleration_B(t);
    const dynamics::Quat q_GW(Eigen::AngleAxisd(0.5 * std::numbers::pi - heading, dynamics::Vec3::UnitZ()));
    return dynamics::Vec3(0.0, 0.0, g) + q_GW * (rocking.attitude(t) * a_B);
  }
};

struct PlatformAlignmentPlantParams {
  models::PlatformAlignmentParams platform{.latitude = 50.0 * std::numbers::pi / 180.0};
  models::PlatformMisalignment initial{};  // θ_E, θ_N, ψ at t = 0 [rad]
  double gravity{9.81};                    // plumb-line gravity g [m/s²]
  double H{0.05};                          // torquer scale of the east and north gyros [N m s]
  double azimuth_torquer_scale{2e-4};      // K_Z [rad/s per V]
  double accel_noise_density{0.0};         // [m/s²/√Hz]
  AlignmentBaseMotion base{};
};

class PlatformAlignmentPlant {
 public:
  using SensorFrame = msg::platform_alignment::SensorFrame;
  using ActuatorFrame = msg::platform_alignment::ActuatorFrame;
  using Model = models::PlatformAlignment;
  using State = Model::State;
  using Inputs = Model::Inputs;
  enum Stream : std::uint64_t { kAccelEastStream = 1, kAccelNorthStream, kAccelUpStream };
  static constexpr std::array<const char*, 4> kStateNames{"q_GP_x", "q_GP_y", "q_GP_z", "q_GP_w"};

  PlatformAlignmentPlant(const PlatformAlignmentPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        model_(p.platform),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        accel_{sensors::Accelerometer(accel_params(p, t)), sensors::Accelerometer(accel_params(p, t)),
               sensors::Accelerometer(accel_params(p, t))},
        rng_{random::SeededRng(t.seed, kAccelEastStream), random::SeededRng(t.seed, kAccelNorthStream),
             random::SeededRng(t.seed, kAccelUpStream)} {
    x_ = Model::state_of(models::attitude_of(p.initial));
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    const dynamics::Vec3 a = model_.accelerometers(x_, p_.base.specific_force_G(time_s(tick), p_.gravity));
    for (int i = 0; i < 3; ++i) measured_[i] = accel_[i].measure(a[i], rng_[i]);
    f.theta_east_rad = measured_[1] / kAlignmentGravityScale;
    f.theta_north_rad = -measured_[0] / kAlignmentGravityScale;
  }

  void actuate(const ActuatorFrame& cmd) {
    model_.inputs.rate_command = {-cmd.east_torquer_Nm / p_.H, -cmd.north_torquer_Nm / p_.H,
                                  p_.azimuth_torquer_scale * cmd.zenith_torquer_V};
  }

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }

  bool finite() const { return x_.allFinite(); }

  double time_s(std::int64_t tick) const { return 1e-9 * static_cast<double>(tick * t_.tick_ns); }
  models::PlatformMisalignment misalignment() const { return Model::misalignment(x_); }
  // The last accelerometer outputs (east, north, up) [m/s²].
  const std::array<double, 3>& accelerometers() const { return measured_; }
  const Inputs& inputs() const { return model_.inputs; }
  const State& state() const { return x_; }
  const Model& model() const { return model_; }

  static constexpr int kGuardedStates = Model::kStateSize;
  static const char* state_name(int i) { return kStateNames[static_cast<std::size_t>(i)]; }
  double state_value(int i) const { return x_[i]; }

 private:
  static sensors::AccelerometerParams accel_params(const PlatformAlignmentPlantParams& p, const PlantTiming& t) {
    sensors::AccelerometerParams a;
    a.sample_period = t.tick_s();
    a.g = p.gravity;
    a.noise.white_density = p.accel_noise_density;  // the bias is the model's
    return a;
  }

  PlatformAlignmentPlantParams p_;
  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  std::array<sensors::Accelerometer, 3> accel_;
  std::array<random::SeededRng, 3> rng_;
  std::array<double, 3> measured_{};
};

}  // namespace gyrostab::plants
