// The CMG-steered spacecraft as it runs in a scene (Magnus §14.4, (14.45); the gyrostat of §4.1): the model
// of sim/models/cmg_cluster_spacecraft.hpp with its gimbal rate servos (the CMG electronics: PI with the
// motor torque limit, poles at −ω_s) following the held rate commands, integrated by RK4 with the scene's
// sub-steps. Sensors: the attitude as 3-2-1 angles (star tracker, exact), the body rate (gyro package: white
// noise density), the gimbal angles from absolute single-turn encoders (read in [−π, π)).
//
// Frames: the cluster's own (tools/devices/cmg_cluster/cmg_cluster_signals.toml, docs/icd/cmg_cluster.md): out,
// attitude_rad = (roll, pitch, yaw) of q_WB [rad]; body_rate_rad_s = ω [rad/s]; delta_rad[i] = δ_i [rad]
// (encoder); delta_rate_rad_s[i] = δ_i' [rad/s] (the rate loop's feedback, exact); in,
// gimbal_rate_command_rad_s[i] = ν_c,i [rad/s] (the safe state's zero rates hold the gimbals: the cluster has
// no brake). Units beyond the cluster's count read 0 and their commands are ignored.
// Random streams of the scene seed (seeded_rng.hpp): 1 the body-rate noise.
// Allocation-free after construction. Docs: docs/models/cmg-cluster.md. Oracle: tests/oracle/cmg_cluster_test.cpp.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/cmg_cluster_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/cmg_cluster_spacecraft.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

static_assert(sizeof(msg::cmg_cluster::SensorFrame::delta_rad) == models::kMaxCmgs * sizeof(double) &&
                  sizeof(msg::cmg_cluster::ActuatorFrame::gimbal_rate_command_rad_s) ==
                      models::kMaxCmgs * sizeof(double),
              "the model's units are the frames'");

struct CmgClusterSensorParams {
  double rate_noise_density{1e-6};                  // body-rate white noise [rad/s/√Hz]
  std::int64_t gimbal_encoder_counts_per_rev{1 << 20};  // absolute single-turn [counts/rev]
};

struct CmgClusterPlantParams {
  models::CmgClusterParams model{};
  double initial_delta[models::kMaxCmgs]{};  // δ_i at t = 0 [rad]
  dynamics::Vec3 initial_rate{dynamics::Vec3::Zero()};  // ω at t = 0 [rad/s]
  CmgClusterSensorParams sensors{};
};

// 3-2-1 angles (roll, pitch, yaw) of q_WB [rad].
inline dynamics::Vec3 euler321_of(const dynamics::Quat& q) {
  const double x = q.x(), y = q.y(), z = q.z(), w = q.w();
  const double sp = std::fmax(-1.0, std::fmin(1.0, 2.0 * (w * y - z * x)));
  return {std::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y)), std::asin(sp),
          std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))};
}

class CmgClusterPlant {
 public:
  using SensorFrame = msg::cmg_cluster::SensorFrame;
  using ActuatorFrame = msg::cmg_cluster::ActuatorFrame;
  using Model = models::CmgClusterSpacecraft;
  using Dynamics = Model;
  using State = Model::State;
  enum Stream : std::uint64_t { kRateStream = 1 };
  struct HeldInputs {
    double rate_command[models::kMaxCmgs]{};
  };

  CmgClusterPlant(const CmgClusterPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        model_(p.model),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        encoder_({p.sensors.gimbal_encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kAbsolute,
                  sensors::EncoderParams::Rounding::kNearest}),
        rate_noise_({p.sensors.rate_noise_density, 0.0, 0.0}, t.tick_s()),
        rng_rate_(t.seed, kRateStream) {
    x_ = Model::make_state(p.initial_rate, dynamics::Quat::Identity(), p.initial_delta);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    const dynamics::Vec3 e = euler321_of(attitude());
    for (int k = 0; k < 3; ++k) {
      f.attitude_rad[k] = e[k];
      f.body_rate_rad_s[k] = x_[Model::kOmega + k] + rate_noise_.sample(rng_rate_);
    }
    for (int i = 0; i < models::kMaxCmgs; ++i) {
      const bool unit = i < p_.model.geometry.count;
      f.delta_rad[i] = unit ? gimbal_reading(i) : 0.0;
      f.delta_rate_rad_s[i] = unit ? x_[Model::kGimbalRate + i] : 0.0;
    }
  }

  void actuate(const ActuatorFrame& cmd) {
    double* nu = model_.inputs.rate_command;
    for (int i = 0; i < models::kMaxCmgs; ++i) nu[i] = i < p_.model.geometry.count ? cmd.gimbal_rate_command_rad_s[i] : 0.0;
  }

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }

  bool finite() const { return x_.allFinite(); }

  dynamics::Quat attitude() const { return dynamics::Quat(x_.segment<4>(Model::kQuat)); }
  dynamics::Vec3 body_rate() const { return x_.segment<3>(Model::kOmega); }
  double delta(int i) const { return x_[Model::kDelta + i]; }
  double gimbal_rate(int i) const { return x_[Model::kGimbalRate + i]; }
  double singularity_measure() const { return model_.singularity_measure(x_); }
  dynamics::Vec3 cmg_momentum_body() const { return model_.cmg_momentum_body(x_); }
  dynamics::Vec3 momentum_world() const { return model_.momentum_world(x_); }
  double motor_torque(int i) const { return model_.motor_torque(x_, i); }
  HeldInputs held_inputs() const {
    HeldInputs h;
    for (int i = 0; i < models::kMaxCmgs; ++i) h.rate_command[i] = model_.inputs.rate_command[i];
    return h;
  }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return model_; }
  const CmgClusterPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp): ω, q and the gimbal angles and rates.
  static constexpr int kGuardedStates = 15;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"omega_x_rad_s", "omega_y_rad_s", "omega_z_rad_s", "q_x", "q_y", "q_z", "q_w",
                                 "delta_1_rad", "delta_2_rad", "delta_3_rad", "delta_4_rad", "delta_rate_1_rad_s",
                                 "delta_rate_2_rad_s", "delta_rate_3_rad_s", "delta_rate_4_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  double gimbal_reading(int i) const {
    if (i >= p_.model.geometry.count) return 0.0;
    double d = encoder_.measure(delta(i));
    if (d >= std::numbers::pi) d -= 2.0 * std::numbers::pi;
    return d;
  }

  const CmgClusterPlantParams& p_;
  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  sensors::Encoder encoder_;
  sensors::SensorNoise rate_noise_;
  random::SeededRng rng_rate_;
};

}  // namespace gyrostab::plants
