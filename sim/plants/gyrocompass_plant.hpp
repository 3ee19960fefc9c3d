// The pendulous gyrocompass as it runs in a scene (Magnus ch. 13, (13.7)-(13.39)): the compass
// (sim/models/gyrocompass.hpp on the master equation (10.22), full or precession form, with the optional
// swing of the rolling error (13.29)-(13.36)) in the geographic frame (up, east, north) of a vehicle on the
// rotating Earth (sim/motion/earth_vehicle.hpp: at rest for the fixed-base compass, or a ship crossing
// latitudes; fed per tick by vehicle_frame_feed.hpp, with the plumb line as the vertical at rest:
// instrument_frames.hpp), integrated by RK4 with the scene's sub-steps; and its sensors: the level sensor
// (elevation above the apparent horizon, white noise) and the follow-up pick-off.
// Start: the initial offsets (α0, β0), from the closed loop's steady state of the initial motion when
// start_settled — for the controller's level gains f, c_e (M1 = −f β_lvl, M2 = −c_e β_lvl, precession form):
//   β0 = (HΩ1 + c β_L)/(HΩ3 + c),  α0 = −(HΩ2 + f(β0 − β_L))/(HΩ3),  c = mechanical + electrical.
//
// State: [α, β (rad), α', β' (rad/s), γ (rad), γ' (rad/s)] — azimuth (positive west) and elevation of the
// rotor axis, and the swing about it (precession form: the rates are computed, not states). Frames: the
// gyrocompass's own (tools/devices/gyrocompass/gyrocompass_signals.toml, docs/icd/gyrocompass.md): in,
// vertical_torquer_Nm = torquer about the vertical M1, east_torquer_Nm = about the east axis M2 [N m]; out,
// level_rad = level signal β − β_L [rad], follow_up_rad = follow-up pick-off −(ψ + α) and
// indicated_heading_rad = ψ + α, both in [−π, π] [rad]; azimuth_rate_rad_s, elevation_rate_rad_s = α', β'
// [rad/s].
// Random streams of the scene seed (seeded_rng.hpp): 1 the level sensor.
// Allocation-free after construction. Docs: docs/models/gyrocompass.md. Oracle:
// tests/oracle/gyrocompass_test.cpp (the model); this plant in the shipped scenes through
// tests/determinism/scene_determinism_test.cpp and tests/alloc/scene_alloc_test.cpp.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/gyrocompass_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyrocompass.hpp"
#include "sim/motion/vehicle_motion.hpp"
#include "sim/plants/instrument_frames.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/plants/vehicle_frame_feed.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct GyrocompassPlantParams {
  motion::VehicleMotionParams vehicle{.start = {.latitude = std::numbers::pi / 180.0 * 50.0}};
  models::GyrocompassParams gyro{};
  double alpha0{0.0}, beta0{0.0};   // initial offsets (from the steady state if start_settled) [rad]
  bool start_settled{true};         // start at the closed loop's steady state of the initial motion
  double level_noise_density{0.0};  // level sensor white noise [rad/√Hz]
  double law_f{0.0}, law_c_e{0.0};  // the controller's level gains, for the settled start [N m/rad]
};

class GyrocompassPlant {
 public:
  using Model = models::Gyrocompass;
  using SensorFrame = msg::gyrocompass::SensorFrame;
  using ActuatorFrame = msg::gyrocompass::ActuatorFrame;
  using State = Model::State;
  using Inputs = models::GyrocompassInputs;
  enum Stream : std::uint64_t { kLevelStream = 1 };

  GyrocompassPlant(const GyrocompassPlantParams& p, const PlantTiming& t)
      : t_(t),
        model_(p.gyro),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        feed_(p.vehicle, t.tick_ns,
              PlumbFrame{&motion::EarthVehicleSample::geographic, frame_up_east_north,
                         p.vehicle.earth.rotation_rate}),
        level_noise_({p.level_noise_density, 0.0, 0.0}, t.tick_s()),
        rng_level_(t.seed, kLevelStream) {
    model_.inputs.frame.hold(feed_.frame());
    model_.inputs.heading = feed_.motion().heading;
    x_ = Model::make_state(p.alpha0, p.beta0);
    if (p.start_settled) {
      double a, b;
      steady_state(p, feed_.frame(), a, b);
      x_[Model::kAlpha] += a;
      x_[Model::kBeta] += b;
    }
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    const double t = static_cast<double>(tick) * t_.tick_s();
    double a_rate, b_rate;
    model_.rates(t, x_, a_rate, b_rate);
    f.level_rad = model_.level_signal(t, x_) + level_noise_.sample(rng_level_);
    const double heading = feed_.motion().heading;
    f.follow_up_rad = std::remainder(-(heading + alpha_rad()), 2.0 * std::numbers::pi);
    f.azimuth_rate_rad_s = a_rate;
    f.elevation_rate_rad_s = b_rate;
    f.indicated_heading_rad = std::remainder(heading + alpha_rad(), 2.0 * std::numbers::pi);
  }

  void actuate(const ActuatorFrame& cmd) {
    model_.inputs.M1 = cmd.vertical_torquer_Nm;
    model_.inputs.M2 = cmd.east_torquer_Nm;
  }

  // Integrates [k, k + 1) in three parts, so that a meter can watch the integration alone: the frame's
  // motion over the tick, the compass, then the move to the next tick's frame and heading.
  void begin_tick(std::int64_t tick) { feed_.begin_tick(tick, model_.inputs.frame); }
  void integrate(std::int64_t tick) { driver_.advance_tick(tick, x_); }
  void end_tick() {
    feed_.end_tick(model_.inputs.frame);
    model_.inputs.heading = feed_.motion().heading;
  }
  void advance(std::int64_t tick) {
    begin_tick(tick);
    integrate(tick);
    end_tick();
  }

  bool finite() const { return x_.allFinite(); }

  double alpha_rad() const { return x_[Model::kAlpha]; }
  double beta_rad() const { return x_[Model::kBeta]; }
  double swing_rad() const { return x_[Model::kSwing]; }
  // The level sensor's signal without noise at time t [rad].
  double level_rad(double t) const { return model_.level_signal(t, x_); }
  // The frame and the vehicle at the current tick's start.
  const models::FrameSample& frame() const { return feed_.frame(); }
  const motion::EarthVehicleSample& motion() const { return feed_.motion(); }
  const State& state() const { return x_; }
  const Model& model() const { return model_; }
  const Inputs& inputs() const { return model_.inputs; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 6;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"alpha_rad",       "beta_rad",  "alpha_rate_rad_s",
                                 "beta_rate_rad_s", "gamma_rad", "gamma_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  static void steady_state(const GyrocompassPlantParams& p, const models::FrameSample& w, double& alpha,
                           double& beta) {
    const double H = p.gyro.gyro.H, c = p.gyro.c + p.law_c_e, fd = p.law_f;
    const double bL = models::apparent_horizon_tilt(w.f);
    beta = (H * w.Omega.x() + c * bL) / (H * w.Omega.z() + c);
    alpha = -(H * w.Omega.y() + fd * (beta - bL)) / (H * w.Omega.z());
  }

  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  VehicleFrameFeed<PlumbFrame> feed_;  // the geographic frame
  sensors::SensorNoise level_noise_;
  random::SeededRng rng_level_;
};

}  // namespace gyrostab::plants
