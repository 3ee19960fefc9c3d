// The directional (heading) gyro on an aircraft as it runs in a scene (Magnus §12.2, (12.21)-(12.34)): the
// instrument (sim/models/directional_gyro.hpp: exact gimbal kinematics, precession theory) in the case of an
// aircraft flying over the rotating Earth (sim/motion/earth_vehicle.hpp: great-circle legs, coordinated
// turns, accelerations; fed per tick by vehicle_frame_feed.hpp from the track frame with the plumb line as
// the vertical at rest: instrument_frames.hpp), integrated by RK4 with the scene's sub-steps; and its
// sensors: the heading pick-off, the inner-gimbal pick-off, the compass (the reference ψ_soll) and a turn-rate
// signal.
// Aircraft attitude: coordinated flight, pitch 0, bank φ = atan2(−f_T2, f_T3) from the specific force in the
// track frame (forward, left, up) — the apparent vertical's roll angle, (12.43) α_L = atan(vω/g) in a level
// turn; the case (body) rate = the track frame's rate turned by the bank plus the bank rate about the
// longitudinal axis. Within a tick the bank is linear between the tick's ends (its rate the difference over
// the tick, so the attitude at the tick ends is exact); the track frame's rate is linear as in every vehicle
// instrument. At a manoeuvre corner the bank jumps (the generator's turns start at full rate): the case rolls
// by the jump about its longitudinal axis while the rotor keeps its direction in space — the gimbal angles
// are re-solved from the rotor axis (the kinematic response to an instantaneous roll; a real roll-in takes
// seconds and ends in the same place to first order in the roll-in time).
//
// State: [α, β] (rad), α unwrapped. Frames: the directional gyro's own (tools/devices/directional_gyro/
// directional_gyro_signals.toml, docs/icd/directional_gyro.md): in, outer_torquer_Nm = M1 (outer, normal
// axis), inner_torquer_Nm = M2 (inner axis) [N m]; out,
//   indicated_heading_rad = ψ_ind = α + card, wrapped to [−π, π): the heading indication; the card is set
//     at t = 0 so that ψ_ind(0) = ψ(0) + heading_error0 [rad]
//   inner_gimbal_rad = β [rad];  outer_gimbal_rate_rad_s, inner_gimbal_rate_rad_s = α', β' [rad/s]
//   compass_heading_rad = ψ_soll = true heading + compass white noise, wrapped [rad]; bank_rad = bank [rad]
//   case_roll_rate_rad_s, case_pitch_rate_rad_s, case_yaw_rate_rad_s = the case rate in body axes (forward,
//     right, down) [rad/s]
// Random streams of the scene seed (seeded_rng.hpp): 1 the compass.
// Guard: |β| ≥ 89° (gimbal lock, where the precession theory's 1/cos β diverges) makes the state non-finite,
// so the run stops there with the state named (tools/loop/state_guard.hpp).
// Allocation-free after construction. Docs: docs/models/directional-gyro.md. Oracle:
// tests/oracle/directional_gyro_test.cpp; the shipped scenes through tests/determinism/ and tests/alloc/.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "gyrostab_signals/directional_gyro_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/directional_gyro.hpp"
#include "sim/motion/vehicle_motion.hpp"
#include "sim/plants/instrument_frames.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/plants/vehicle_frame_feed.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct DirectionalGyroSensorParams {
  double compass_noise_density{0.0};  // compass white noise [rad/√Hz]
};

struct DirectionalGyroPlantParams {
  motion::VehicleMotionParams vehicle{.start = {.latitude = std::numbers::pi / 180.0 * 50.0}};
  models::DirectionalGyroParams gyro{};
  double alpha0{0.0}, beta0{0.0};  // initial gimbal angles (0, 0: rotor along the longitudinal axis) [rad]
  double heading_error0{0.0};      // indication − true heading at t = 0 (the card's misset) [rad]
  DirectionalGyroSensorParams sensors{};
};

// Bank (right wing down > 0) of coordinated flight from the specific force in track axes (forward, left, up).
inline double coordinated_bank(const dynamics::Vec3& f_T) {
  return std::atan2(-f_T.y(), f_T.z());
}

// The case's absolute rate in case axes (up, right, forward) from the track frame's w_T (forward, left, up),
// the bank φ and its rate φ' [rad/s]: body (forward, right, down) = the level (forward, right, down) rolled by φ.
inline dynamics::Vec3 case_rate_of(const dynamics::Vec3& w_T, double bank, double bank_rate) {
  const double c = std::cos(bank), s = std::sin(bank);
  const double v2 = -w_T.y(), v3 = -w_T.z();  // level right, down
  const double b1 = w_T.x() + bank_rate, b2 = c * v2 + s * v3, b3 = -s * v2 + c * v3;
  return {-b3, b2, b1};
}

class DirectionalGyroPlant {
 public:
  using SensorFrame = msg::directional_gyro::SensorFrame;
  using ActuatorFrame = msg::directional_gyro::ActuatorFrame;
  using Model = models::DirectionalGyro;
  using State = Model::State;
  using Inputs = models::DirectionalGyroInputs;
  enum Stream : std::uint64_t { kCompassStream = 1 };
  static constexpr double kGimbalLockGuard = 89.0 * std::numbers::pi / 180.0;

  DirectionalGyroPlant(const DirectionalGyroPlantParams& p, const PlantTiming& t)
      : t_(t),
        model_(p.gyro),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        feed_(p.vehicle, t.tick_ns,
              PlumbFrame{&motion::EarthVehicleSample::track, frame_as_is, p.vehicle.earth.rotation_rate}),
        compass_noise_(sensors::SensorNoise({p.sensors.compass_noise_density, 0.0, 0.0}, t.tick_s())),
        rng_(t.seed, kCompassStream) {
    x_ = Model::make_state(p.alpha0, p.beta0);
    bank_ = coordinated_bank(feed_.frame().f);
    card_ = feed_.motion().heading + p.heading_error0 - p.alpha0;
    model_.inputs.case_rate.hold(case_rate_of(feed_.frame().Omega, bank_, 0.0));
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    const double t = static_cast<double>(tick) * t_.tick_s();
    State dx;
    model_.derivative(t, x_, dx);
    f.indicated_heading_rad = indicated_heading_rad();
    f.inner_gimbal_rad = beta_rad();
    f.outer_gimbal_rate_rad_s = dx[Model::kAlpha];
    f.inner_gimbal_rate_rad_s = dx[Model::kBeta];
    f.compass_heading_rad = wrap_heading(true_heading_rad() + compass_noise_.sample(rng_));
    f.bank_rad = bank_;
    const dynamics::Vec3 w = model_.inputs.case_rate.w0;  // case axes (up, right, forward)
    f.case_roll_rate_rad_s = w.z();
    f.case_pitch_rate_rad_s = w.y();
    f.case_yaw_rate_rad_s = -w.x();
  }

  void actuate(const ActuatorFrame& cmd) {
    model_.inputs.M1 = cmd.outer_torquer_Nm;
    model_.inputs.M2 = cmd.inner_torquer_Nm;
  }

  // Integrates [k, k + 1) in three parts, so that a meter can watch the integration alone: the case's motion
  // over the tick, the instrument, then the move to the next tick's case (and the roll at a corner).
  void begin_tick(std::int64_t tick) {
    feed_.begin_tick(tick, frame_);
    bank_end_ = coordinated_bank(feed_.next_frame().f);
    bank_rate_ = (bank_end_ - bank_) / t_.tick_s();
    models::CaseRateInputs& in = model_.inputs.case_rate;
    in.t0 = frame_.t0;
    in.h = frame_.h;
    in.w0 = case_rate_of(feed_.frame().Omega, bank_, bank_rate_);
    in.w1 = case_rate_of(feed_.next_frame().Omega, bank_end_, bank_rate_);
  }
  void integrate(std::int64_t tick) {
    driver_.advance_tick(tick, x_);
    if (!(std::fabs(x_[Model::kBeta]) < kGimbalLockGuard)) x_[Model::kBeta] = std::numeric_limits<double>::quiet_NaN();
  }
  void end_tick() {
    const bool corner = feed_.end_tick(frame_);
    bank_ = bank_end_;
    if (corner) {
      const double bank = coordinated_bank(feed_.frame().f);
      roll_case(bank - bank_end_);
      bank_ = bank;
    }
    model_.inputs.case_rate.hold(case_rate_of(feed_.frame().Omega, bank_, bank_rate_));
  }
  void advance(std::int64_t tick) {
    begin_tick(tick);
    integrate(tick);
    end_tick();
  }

  bool finite() const { return x_.allFinite(); }

  double alpha_rad() const { return x_[Model::kAlpha]; }
  double beta_rad() const { return x_[Model::kBeta]; }
  // The heading indication (card + α), wrapped; and unwrapped (for drift meters) [rad].
  double indicated_heading_rad() const { return wrap_heading(card_ + x_[Model::kAlpha]); }
  double indicated_heading_unwrapped_rad() const { return card_ + x_[Model::kAlpha]; }
  double true_heading_rad() const { return feed_.motion().heading; }
  double bank_rad() const { return bank_; }
  const motion::EarthVehicleSample& motion() const { return feed_.motion(); }
  // The case rate (up, right, forward) at the current tick's start [rad/s].
  const dynamics::Vec3& case_rate() const { return model_.inputs.case_rate.w0; }
  // The rotor axis in local-level axes (north, east, down) at the current tick's start.
  dynamics::Vec3 rotor_axis_ned() const {
    const dynamics::Vec3 e = models::directional_gyro_rotor_axis(x_[Model::kAlpha], x_[Model::kBeta]);
    const double cb = std::cos(bank_), sb = std::sin(bank_);
    const double f = e.z(), r = e.y(), d = -e.x();               // body (forward, right, down)
    const double lr = cb * r - sb * d, ld = sb * r + cb * d;     // level (forward, right, down)
    const double ch = std::cos(true_heading_rad()), sh = std::sin(true_heading_rad());
    return {ch * f - sh * lr, sh * f + ch * lr, ld};
  }
  const State& state() const { return x_; }
  const Model& model() const { return model_; }
  const Inputs& inputs() const { return model_.inputs; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 2;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"alpha_rad", "beta_rad"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  static double wrap_heading(double a) {
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    const double w = a - kTwoPi * std::floor((a + std::numbers::pi) / kTwoPi);
    return w >= std::numbers::pi ? w - kTwoPi : w;
  }
  // The case rolls by d about its longitudinal axis (case axis 3); the rotor keeps its direction in space.
  void roll_case(double d) {
    const dynamics::Vec3 e = models::directional_gyro_rotor_axis(x_[Model::kAlpha], x_[Model::kBeta]);
    // Body (forward, right, down) components after the roll: Rx(d)^T; case up = −down.
    const double c = std::cos(d), s = std::sin(d);
    const double r = e.y(), dn = -e.x();
    const dynamics::Vec3 e_new(-(-s * r + c * dn), c * r + s * dn, e.z());
    double alpha, beta;
    models::directional_gyro_angles_of(e_new, alpha, beta);
    x_[Model::kAlpha] += std::remainder(alpha - x_[Model::kAlpha], 2.0 * std::numbers::pi);
    x_[Model::kBeta] = beta;
  }

  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  VehicleFrameFeed<PlumbFrame> feed_;  // the track frame
  models::FrameInputs frame_{};        // the track frame over the tick (what the feed fills)
  double bank_{0.0}, bank_end_{0.0}, bank_rate_{0.0};  // [rad], [rad/s]
  double card_{0.0};                                   // the card's setting [rad]
  sensors::SensorNoise compass_noise_;
  random::SeededRng rng_;
};

}  // namespace gyrostab::plants
