// The gyro vertical on an aircraft as it runs in a scene (Magnus §12.3, (12.35)-(12.51)): the instrument
// (sim/models/gyro_vertical.hpp on the master equation (10.22), full or precession form) in the track frame
// (forward, right, down) of a vehicle flying over the rotating Earth (sim/motion/earth_vehicle.hpp: straight
// legs, coordinated turns, accelerations; fed per tick by vehicle_frame_feed.hpp, with the plumb line as the
// vertical at rest: instrument_frames.hpp), integrated by RK4 with the scene's sub-steps; and its sensors:
// the erection sensor (tilt from the apparent vertical), the gimbal rate pick-offs (white noise), and a turn
// indicator — a P rate gyro with its own dynamics (sim/sensors/rate_integrating_gyro.hpp, (15.1)-(15.6)) on
// the aircraft's normal axis. Aircraft attitude: coordinated flight, bank φ = α_L (the apparent vertical's
// roll angle, (12.43)), pitch 0.
//
// State: [α, β (rad), α', β' (rad/s)] of the rotor axis relative to the frame (precession form: the rates
// are computed, not states). Frames: the gyro vertical's own (tools/devices/gyro_vertical/
// gyro_vertical_signals.toml, docs/icd/gyro_vertical.md): in, torquer1_Nm, torquer2_Nm = torquer commands
// M1, M2 [N m]; out, erection_e1_rad, erection_e2_rad = erection signal e = (α − α_L, β − β_L) [rad],
// alpha_rate_rad_s, beta_rate_rad_s = α', β' [rad/s], turn_indicator_rad_s = the turn indicator [rad/s],
// indicated_bank_rad = bank − α, indicated_pitch_rad = −β (the indicated attitude) [rad].
// Random streams of the scene seed (seeded_rng.hpp): 1, 2 erection sensor axes 1, 2; 3, 4 rate pick-offs.
// Allocation-free after construction. Docs: docs/models/gyro-vertical.md. Oracle:
// tests/oracle/gyro_vertical_test.cpp (the model); this plant in the shipped scene through
// tests/determinism/scene_determinism_test.cpp and tests/alloc/scene_alloc_test.cpp.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/gyro_vertical_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyro_vertical.hpp"
#include "sim/motion/vehicle_motion.hpp"
#include "sim/plants/instrument_frames.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/plants/vehicle_frame_feed.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/rate_integrating_gyro.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct GyroVerticalSensorParams {
  double erection_noise_density{0.0};  // erection sensor white noise [rad/√Hz]
  double rate_noise_density{0.0};      // gimbal rate pick-off white noise [rad/s/√Hz]
};

struct GyroVerticalPlantParams {
  motion::VehicleMotionParams vehicle{.start = {.latitude = std::numbers::pi / 180.0 * 50.0}};
  // No pendulous moment unless the scene gives one: the erection is the correction law's.
  models::GyroVerticalParams gyro{.c = 0.0};
  double alpha0{0.0}, beta0{0.0};  // initial tilt [rad]
  // A P rate gyro, ω_n = sqrt(c2/B) = 100 rad/s, ζ = d2/(2 sqrt(c2 B)) = 0.5; sample_period = the tick.
  sensors::SingleAxisGyroParams turn_indicator{.d2 = 2e-3, .c2 = 0.2};
  GyroVerticalSensorParams sensors{};
};

class GyroVerticalPlant {
 public:
  using SensorFrame = msg::gyro_vertical::SensorFrame;
  using ActuatorFrame = msg::gyro_vertical::ActuatorFrame;
  using Model = models::GyroVertical;
  using State = Model::State;
  using Inputs = models::GyroVerticalInputs;
  enum Stream : std::uint64_t { kErection1Stream = 1, kErection2Stream, kRate1Stream, kRate2Stream };

  GyroVerticalPlant(const GyroVerticalPlantParams& p, const PlantTiming& t)
      : t_(t),
        model_(p.gyro),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        feed_(p.vehicle, t.tick_ns,
              PlumbFrame{&motion::EarthVehicleSample::track, frame_forward_right_down,
                         p.vehicle.earth.rotation_rate}),
        indicator_(p.turn_indicator),
        erection_noise_{sensors::SensorNoise({p.sensors.erection_noise_density, 0.0, 0.0}, t.tick_s()),
                        sensors::SensorNoise({p.sensors.erection_noise_density, 0.0, 0.0}, t.tick_s())},
        rate_noise_{sensors::SensorNoise({p.sensors.rate_noise_density, 0.0, 0.0}, t.tick_s()),
                    sensors::SensorNoise({p.sensors.rate_noise_density, 0.0, 0.0}, t.tick_s())},
        rng_{random::SeededRng(t.seed, kErection1Stream), random::SeededRng(t.seed, kErection2Stream),
             random::SeededRng(t.seed, kRate1Stream), random::SeededRng(t.seed, kRate2Stream)} {
    x_ = Model::make_state(p.alpha0, p.beta0);
    model_.inputs.frame.hold(feed_.frame());
    const sensors::GyroCaseMotion m = case_motion(feed_.frame());
    indicator_.reset_steady(m);
    case_ = m;
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    const double t = static_cast<double>(tick) * t_.tick_s();
    double e1, e2, a_rate, b_rate;
    model_.erection_signal(t, x_, e1, e2);
    model_.rates(t, x_, a_rate, b_rate);
    f.erection_e1_rad = e1 + erection_noise_[0].sample(rng_[0]);
    f.erection_e2_rad = e2 + erection_noise_[1].sample(rng_[1]);
    f.alpha_rate_rad_s = a_rate + rate_noise_[0].sample(rng_[2]);
    f.beta_rate_rad_s = b_rate + rate_noise_[1].sample(rng_[3]);
    f.turn_indicator_rad_s = indicator_.indicated();
    f.indicated_bank_rad = apparent_vertical().alpha_L - alpha_rad();
    f.indicated_pitch_rad = -beta_rad();
  }

  void actuate(const ActuatorFrame& cmd) {
    model_.inputs.M1 = cmd.torquer1_Nm;
    model_.inputs.M2 = cmd.torquer2_Nm;
  }

  // Integrates [k, k + 1) in three parts, so that a meter can watch the integration alone: the frame's
  // motion over the tick, the instrument, then the turn indicator and the move to the next tick's frame.
  void begin_tick(std::int64_t tick) { feed_.begin_tick(tick, model_.inputs.frame); }
  void integrate(std::int64_t tick) { driver_.advance_tick(tick, x_); }
  void end_tick() {
    const sensors::GyroCaseMotion m1 = case_motion(feed_.next_frame());
    indicator_.update(case_, m1);
    case_ = m1;
    feed_.end_tick(model_.inputs.frame);
  }
  void advance(std::int64_t tick) {
    begin_tick(tick);
    integrate(tick);
    end_tick();
  }

  bool finite() const { return x_.allFinite(); }

  double alpha_rad() const { return x_[Model::kAlpha]; }
  double beta_rad() const { return x_[Model::kBeta]; }
  // The frame at the current tick's start: its turn rate Ω3 (> 0 right) and the apparent vertical.
  const models::FrameSample& frame() const { return feed_.frame(); }
  double turn_rate_rad_s() const { return feed_.frame().Omega.z(); }
  models::ApparentVertical apparent_vertical() const { return models::apparent_vertical(feed_.frame().f); }
  double turn_indicator_rad_s() const { return indicator_.indicated(); }
  const State& state() const { return x_; }
  const Model& model() const { return model_; }
  const Inputs& inputs() const { return model_.inputs; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 4;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  // The turn indicator's case motion (15.5): input axis = aircraft normal (down), output = longitudinal,
  // spin = lateral (right), with the aircraft banked by φ = α_L about the forward axis.
  static sensors::GyroCaseMotion case_motion(const models::FrameSample& w) {
    const double bank = models::apparent_vertical(w.f).alpha_L;
    const double cb = std::cos(bank), sb = std::sin(bank);
    sensors::GyroCaseMotion m;
    m.Omega1 = -sb * w.Omega.y() + cb * w.Omega.z();  // body down
    m.Omega3 = cb * w.Omega.y() + sb * w.Omega.z();   // body right
    m.Omega2_dot = w.Omega_dot.x();
    return m;
  }

  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  VehicleFrameFeed<PlumbFrame> feed_;  // the track frame
  sensors::SingleAxisGyro indicator_;
  sensors::GyroCaseMotion case_{};
  std::array<sensors::SensorNoise, 2> erection_noise_, rate_noise_;
  std::array<random::SeededRng, 4> rng_;
};

}  // namespace gyrostab::plants
