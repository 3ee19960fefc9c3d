// The ship roll damper as it runs in a scene (Magnus §14.2, (14.8)): the stabilized ship (ship_in_sea.hpp:
// model + sea moment + the controller's held torque and brake) and, in the same sea, the same ship with the
// gyro locked — the unstabilized reference — each integrated by RK4 with the scene's sub-steps; and the
// sensors the controller reads: roll angle (AHRS white noise), roll rate gyro (noise density, bias),
// precession encoder (incremental, nearest count) and precession rate (noise density).
//
// State: the stabilized ship [φ, β, φ', β'] and the reference ship's, in rad and rad/s (named accessors
// below). Frames: the ship roll damper's own (tools/devices/ship_roll_damper/ship_roll_damper_signals.toml,
// docs/icd/ship_roll_damper.md): in, precession_torque_Nm = M2 [N m] and precession_brake in [0, 1] ×
// brake_full_Nms [N m s/rad] (the safe state locks the case); out, roll_rad, roll_rate_rad_s,
// precession_angle_rad, precession_rate_rad_s, precession_encoder_count.
// Random streams of the scene seed, one per consumer (seeded_rng.hpp): 1 the sea, 2 roll angle noise, 3 roll
// rate noise, 4 precession rate noise; adding a consumer never shifts another.
// Allocation-free after construction. Docs: docs/models/ship-roll-damper.md. Oracle:
// tests/oracle/ship_roll_damper_test.cpp (the model); tests/stiff/plant_composition_test.cpp (this plant in
// the shipped scenes).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gyrostab_signals/ship_roll_damper_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/ship_roll_damper.hpp"
#include "sim/motion/sea_roll_moment.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/plants/ship_in_sea.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct ShipRollDamperSensorParams {
  double roll_angle_noise_rad{1e-4};           // roll angle (AHRS) white noise, std. dev. per sample [rad]
  double roll_rate_noise_density{1e-4};        // roll rate gyro white noise [rad/s/√Hz]
  double roll_rate_bias{0.0};                  // roll rate gyro bias [rad/s]
  double precession_rate_noise_density{1e-4};  // precession rate white noise [rad/s/√Hz]
  std::int64_t encoder_counts_per_rev{65536};  // precession encoder [counts/rev]

  bool noisy() const {
    return roll_angle_noise_rad > 0.0 || roll_rate_noise_density > 0.0 || precession_rate_noise_density > 0.0 ||
           roll_rate_bias != 0.0;
  }
};

struct ShipRollDamperPlantParams {
  models::ShipRollDamperParams ship{};
  double brake_full_Nms{1e7};  // brake at precession_brake = 1 [N m s/rad]
  motion::SeaRollMomentParams sea{};
  ShipRollDamperSensorParams sensors{};
  double initial_roll{0.0};  // φ at t = 0, both ships (a roll-decay trial in calm water) [rad]
};

class ShipRollDamperPlant {
 public:
  using SensorFrame = msg::ship_roll_damper::SensorFrame;
  using ActuatorFrame = msg::ship_roll_damper::ActuatorFrame;
  using Ship = models::ShipRollDamper;
  using Dynamics = ShipInSeaOf<motion::SeaRollMoment>;
  using State = Dynamics::State;
  enum Stream : std::uint64_t { kSeaStream = 1, kRollAngleStream, kRollRateStream, kPrecessionRateStream };
  struct HeldInputs {
    double command_Nm{0.0};  // precession torque held over the tick [N m]
    double brake_Nms{0.0};   // viscous brake held over the tick [N m s/rad]
  };

  ShipRollDamperPlant(const ShipRollDamperPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        sea_(p.sea, t.tick_s() / t.substeps, random::SeededRng(t.seed, kSeaStream), p.ship.c, p.ship.turn_rate),
        ship_{Ship(p.ship), &sea_, 0.0, 0.0},
        reference_{Ship(locked(p.ship)), &sea_, 0.0, 0.0},
        integ_(ship_),
        ref_integ_(reference_),
        driver_(integ_, t.tick_ns, t.substeps),
        ref_driver_(ref_integ_, t.tick_ns, t.substeps),
        encoder_({p.sensors.encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kIncremental,
                  sensors::EncoderParams::Rounding::kNearest}),
        roll_angle_noise_({p.sensors.roll_angle_noise_rad * std::sqrt(t.tick_s()), 0.0, 0.0}, t.tick_s()),
        roll_rate_noise_({p.sensors.roll_rate_noise_density, p.sensors.roll_rate_bias, 0.0}, t.tick_s()),
        precession_rate_noise_({p.sensors.precession_rate_noise_density, 0.0, 0.0}, t.tick_s()),
        rng_angle_(t.seed, kRollAngleStream),
        rng_rate_(t.seed, kRollRateStream),
        rng_precession_(t.seed, kPrecessionRateStream) {
    x_.setZero();
    x_ref_.setZero();
    x_[Ship::kRoll] = p.initial_roll;
    x_ref_[Ship::kRoll] = p.initial_roll;
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.roll_rad = roll_rad() + roll_angle_noise_.sample(rng_angle_);
    f.roll_rate_rad_s = roll_rate_rad_s() + roll_rate_noise_.sample(rng_rate_);
    const std::int64_t counts = encoder_.counts(precession_rad());
    f.precession_encoder_count = static_cast<double>(static_cast<std::int32_t>(counts));
    f.precession_angle_rad = encoder_.angle_of(counts);
    f.precession_rate_rad_s = precession_rate_rad_s() + precession_rate_noise_.sample(rng_precession_);
  }

  void actuate(const ActuatorFrame& cmd) {
    ship_.command_Nm = cmd.precession_torque_Nm;
    // The bearing's own d2 is in the model (it applies −d2 β'); only the controller's brake here.
    ship_.brake_Nms = std::clamp(cmd.precession_brake, 0.0, 1.0) * p_.brake_full_Nms;
  }

  // Integrates [k, k + 1): the stabilized ship, then the reference in the same sea.
  void advance_stabilized(std::int64_t tick) { driver_.advance_tick(tick, x_); }
  void advance_reference(std::int64_t tick) { ref_driver_.advance_tick(tick, x_ref_); }
  void advance(std::int64_t tick) {
    advance_stabilized(tick);
    advance_reference(tick);
  }

  bool finite() const { return x_.allFinite() && x_ref_.allFinite(); }

  double roll_rad() const { return x_[Ship::kRoll]; }
  double precession_rad() const { return x_[Ship::kPrecession]; }
  double roll_rate_rad_s() const { return x_[Ship::kRollRate]; }
  double precession_rate_rad_s() const { return x_[Ship::kPrecessionRate]; }
  double reference_roll_rad() const { return x_ref_[Ship::kRoll]; }
  double wave_moment_Nm(double t) const { return sea_(t); }
  double wave_moment_rms_Nm() const { return sea_.rms(); }
  // The gyro's loads on the hull now (models/ship_roll_damper.hpp: mount_loads), with the held drive and brake
  // and the bearing's friction as the precession axis's torque.
  models::ShipMountLoads mount_loads() const {
    const double v = x_[Ship::kPrecessionRate];
    const double axis = ship_.command_Nm - (ship_.brake_Nms + p_.ship.total_d2()) * v;
    return ship_.ship.mount_loads(x_, axis);
  }
  HeldInputs held_inputs() const { return {ship_.command_Nm, ship_.brake_Nms}; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return ship_; }
  const ShipRollDamperPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp): the stabilized ship, then the locked reference.
  static constexpr int kGuardedStates = 8;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"roll_rad",           "precession_rad",           "roll_rate_rad_s",
                                 "precession_rate_rad_s", "reference_roll_rad",     "reference_precession_rad",
                                 "reference_roll_rate_rad_s", "reference_precession_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return i < 4 ? x_[i] : x_ref_[i - 4]; }

 private:
  static models::ShipRollDamperParams locked(models::ShipRollDamperParams p) {
    p.locked = true;
    return p;
  }

  const ShipRollDamperPlantParams& p_;
  PlantTiming t_;
  motion::SeaRollMoment sea_;
  Dynamics ship_, reference_;
  dynamics::Rk4<Dynamics> integ_, ref_integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Dynamics>> driver_, ref_driver_;
  State x_, x_ref_;
  sensors::Encoder encoder_;
  sensors::SensorNoise roll_angle_noise_, roll_rate_noise_, precession_rate_noise_;
  random::SeededRng rng_angle_, rng_rate_, rng_precession_;
};

}  // namespace gyrostab::plants
