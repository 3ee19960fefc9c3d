// The single-axis platform with a position gyro as it runs in a scene (Magnus §16.2.2, (16.6)-(16.10),
// Fig. 16.2): the model of sim/models/position_gyro_platform.hpp with the held torquer commands of the
// firmware (platform torquer M1^KP, gyro torquer M2^K), a disturbance torque M1^SP stepped on at a tick and
// held, the base's sinusoidal roll carried by the bearing's friction, integrated by RK4 with the scene's
// sub-steps; and the pick-off δ − α (white noise).
// Start: at rest, every angle 0.
//
// State: [δ (rad), δ' (rad/s), α (rad), α' (rad/s), β (rad), β' (rad/s)].
// Frames: the position-gyro platform's own (tools/devices/position_gyro_platform/
// position_gyro_platform_signals.toml, docs/icd/position_gyro_platform.md): in, platform_torquer_Nm = M1^KP,
// gyro_torquer_Nm = M2^K [N m] (no brake: the safe state's zero torques leave the platform free); out,
// pickoff_rad = δ − α (the pick-off, with noise) [rad]; platform_rad = δ, platform_rate_rad_s = δ' (the
// platform, absolute); inner_gimbal_rad = β; gyro_frame_rate_rad_s = α', inner_gimbal_rate_rad_s = β'
// (absolute α', not against the platform).
// Random streams of the scene seed (seeded_rng.hpp): 1 the pick-off.
// Allocation-free after construction. Docs: docs/models/position-gyro-platform.md. Oracle:
// tests/oracle/position_gyro_platform_test.cpp; the shipped scene runs in tests/determinism and tests/alloc.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/position_gyro_platform_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/position_gyro_platform.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct PositionGyroPlatformPlantParams {
  models::PositionGyroPlatformParams platform{};
  double disturbance_Nm{0.0};          // M1^SP from disturbance_tick on [N m]
  std::int64_t disturbance_tick{0};    // first tick with the disturbance
  double base_amplitude_rad{0.0};      // the base's roll φ = φ0 sin(ω_b t): φ0 [rad]
  double base_frequency_hz{0.0};       // ω_b/2π [Hz]
  double pickoff_noise_density{0.0};   // white noise of the pick-off [rad/√Hz]
};

class PositionGyroPlatformPlant {
 public:
  using SensorFrame = msg::position_gyro_platform::SensorFrame;
  using ActuatorFrame = msg::position_gyro_platform::ActuatorFrame;
  using Model = models::PositionGyroPlatform;
  using State = Model::State;
  using Inputs = Model::Inputs;
  enum Stream : std::uint64_t { kPickoffStream = 1 };

  PositionGyroPlatformPlant(const PositionGyroPlatformPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        model_(p.platform),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        noise_({p.pickoff_noise_density, 0.0, 0.0}, t.tick_s()),
        rng_(t.seed, kPickoffStream) {
    const double w = 2.0 * std::numbers::pi * p.base_frequency_hz;
    model_.inputs.base_omega = w;
    model_.inputs.base_rate_amplitude = p.base_amplitude_rad * w;
    x_ = State::Zero();
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.pickoff_rad = pickoff_rad() + noise_.sample(rng_);
    f.platform_rad = x_[Model::kDelta];
    f.platform_rate_rad_s = x_[Model::kDeltaRate];
    f.inner_gimbal_rad = x_[Model::kBeta];
    f.gyro_frame_rate_rad_s = x_[Model::kAlphaRate];
    f.inner_gimbal_rate_rad_s = x_[Model::kBetaRate];
  }

  void actuate(const ActuatorFrame& cmd) {
    model_.inputs.platform_torque = cmd.platform_torquer_Nm;
    model_.inputs.gyro_torque = cmd.gyro_torquer_Nm;
  }

  // The disturbance of tick `tick` (held over it); then integrate [k, k + 1).
  void begin_tick(std::int64_t tick) {
    model_.inputs.disturbance = tick >= p_.disturbance_tick ? p_.disturbance_Nm : 0.0;
  }
  void integrate(std::int64_t tick) { driver_.advance_tick(tick, x_); }
  void advance(std::int64_t tick) {
    begin_tick(tick);
    integrate(tick);
  }

  bool finite() const { return x_.allFinite(); }

  double pickoff_rad() const { return Model::pickoff(x_); }
  double platform_rad() const { return x_[Model::kDelta]; }
  double platform_rate_rad_s() const { return x_[Model::kDeltaRate]; }
  double gyro_frame_rad() const { return x_[Model::kAlpha]; }
  double beta_rad() const { return x_[Model::kBeta]; }
  // The base's roll angle at time t [rad].
  double base_rad(double t) const {
    return p_.base_amplitude_rad * std::sin(2.0 * std::numbers::pi * p_.base_frequency_hz * t);
  }
  const State& state() const { return x_; }
  const Model& model() const { return model_; }
  const Inputs& inputs() const { return model_.inputs; }

  static constexpr int kGuardedStates = Model::kStateSize;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"delta_rad", "delta_rate_rad_s", "alpha_rad", "alpha_rate_rad_s", "beta_rad",
                                 "beta_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const PositionGyroPlatformPlantParams& p_;
  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  sensors::SensorNoise noise_;
  random::SeededRng rng_;
};

}  // namespace gyrostab::plants
