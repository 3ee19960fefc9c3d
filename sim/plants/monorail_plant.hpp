// The gyro-stabilized monorail car as it runs in a scene (Magnus §14.1, (14.1)-(14.7)): the car with its
// top-heavy gyro case on the track (car_on_track.hpp: sim/models/monorail.hpp with the analog law k = 0 — the
// firmware is the motor law — the curve's Ω3(t) and centrifugal moments, a side-wind gust, the brake, the
// ground), integrated by RK4 with the scene's sub-steps, released at (φ0, β0) at rest; and the sensors the
// controller reads: car tilt (AHRS relative to the local level: white noise, bias), car roll rate gyro (noise
// density), case-angle encoder (incremental, nearest count) and case rate gyro (noise density, bias).
//
// State: [φ, β, φ', β'] — car tilt and case angle — in rad and rad/s (named accessors below). Frames: the
// monorail's own (tools/devices/monorail/monorail_signals.toml, docs/icd/monorail.md): in, motor_torque_Nm =
// M2 [N m] and precession_brake in [0, 1] × brake_full_Nms [N m s/rad] on β' (the safe state); out, tilt_rad,
// tilt_rate_rad_s, case_encoder_count, case_angle_rad, case_rate_rad_s.
// Random streams of the scene seed, one per consumer (seeded_rng.hpp): 1 tilt, 2 tilt rate, 3 case rate;
// adding a consumer never shifts another.
// Allocation-free after construction. Docs: docs/models/monorail.md. Oracle: tests/oracle/monorail_test.cpp
// (the model); the shipped scene sim/scenes/monorail.toml runs in tests/determinism and tests/alloc.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/monorail_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/monorail.hpp"
#include "sim/motion/monorail_track.hpp"
#include "sim/plants/car_on_track.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct MonorailSensorParams {
  double tilt_noise_rad{1e-4};                 // car tilt (AHRS) white noise, std. dev. per sample [rad]
  double tilt_bias_rad{0.0};                   // car tilt bias [rad]
  double tilt_rate_noise_density{1e-4};        // car roll rate gyro [rad/s/√Hz]
  double case_rate_noise_density{1e-4};        // case rate gyro, the law's damper input [rad/s/√Hz]
  double case_rate_bias{0.0};                  // case rate gyro bias [rad/s]
  std::int64_t encoder_counts_per_rev{65536};  // case-angle encoder [counts/rev]
};

struct MonorailPlantParams {
  // k = 0: the firmware is the motor law; d: the passive damper only (the motor realises the law's d).
  models::MonorailParams car{.d = 0.0, .k = 0.0};
  double brake_full_Nms{1e4};  // brake on axis 2 at precession_brake = 1 (safe state) [N m s/rad]
  double phi0{0.0};            // initial car tilt [rad]
  double beta0{0.0};           // initial case angle [rad]
  motion::MonorailTrack track{};
  MonorailSensorParams sensors{};
};

class MonorailPlant {
 public:
  using SensorFrame = msg::monorail::SensorFrame;
  using ActuatorFrame = msg::monorail::ActuatorFrame;
  using Car = models::Monorail;
  using Dynamics = CarOnTrack;
  using State = Dynamics::State;
  enum Stream : std::uint64_t { kTiltStream = 1, kTiltRateStream, kCaseRateStream };
  struct HeldInputs {
    double command_Nm{0.0};  // motor torque held over the tick [N m]
    double brake_Nms{0.0};   // viscous brake held over the tick [N m s/rad]
  };

  MonorailPlant(const MonorailPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        car_{Car(p.car), &p.track, 0.0, 0.0},
        integ_(car_),
        driver_(integ_, t.tick_ns, t.substeps),
        encoder_({p.sensors.encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kIncremental,
                  sensors::EncoderParams::Rounding::kNearest}),
        tilt_noise_({p.sensors.tilt_noise_rad * std::sqrt(t.tick_s()), p.sensors.tilt_bias_rad, 0.0},
                    t.tick_s()),
        tilt_rate_noise_({p.sensors.tilt_rate_noise_density, 0.0, 0.0}, t.tick_s()),
        case_rate_noise_({p.sensors.case_rate_noise_density, p.sensors.case_rate_bias, 0.0}, t.tick_s()),
        rng_tilt_(t.seed, kTiltStream),
        rng_tilt_rate_(t.seed, kTiltRateStream),
        rng_case_rate_(t.seed, kCaseRateStream) {
    x_ = Car::make_state(p.phi0, p.beta0, 0.0, 0.0);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.tilt_rad = tilt_rad() + tilt_noise_.sample(rng_tilt_);
    f.tilt_rate_rad_s = tilt_rate_rad_s() + tilt_rate_noise_.sample(rng_tilt_rate_);
    const std::int64_t counts = encoder_.counts(case_angle_rad());
    f.case_encoder_count = static_cast<double>(static_cast<std::int32_t>(counts));
    f.case_angle_rad = encoder_.angle_of(counts);
    f.case_rate_rad_s = case_rate_rad_s() + case_rate_noise_.sample(rng_case_rate_);
  }

  void actuate(const ActuatorFrame& cmd) {
    car_.command_Nm = cmd.motor_torque_Nm;
    car_.brake_Nms = std::clamp(cmd.precession_brake, 0.0, 1.0) * p_.brake_full_Nms;
  }

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }

  bool finite() const { return x_.allFinite(); }

  double tilt_rad() const { return x_[Car::kTilt]; }
  double case_angle_rad() const { return x_[Car::kCase]; }
  double tilt_rate_rad_s() const { return x_[Car::kTiltRate]; }
  double case_rate_rad_s() const { return x_[Car::kCaseRate]; }
  // The car lies on its side (car_on_track.hpp: the ground holds it there).
  bool overturned() const { return std::fabs(tilt_rad()) >= 0.5 * std::numbers::pi; }
  // What the track does at time t: Ω3 [rad/s], the gust [N m], the lateral acceleration a/g [-] and, at the
  // current tilt, the centrifugal moment on the car to first order, c (a/g) cosφ [N m].
  double Omega3_rad_s(double t) const { return p_.track.curve(t); }
  double gust_moment_Nm(double t) const { return p_.track.gust(t); }
  double lateral_g(double t) const { return car_.lateral_g(t); }
  double centrifugal_moment_Nm(double t) const { return lateral_g(t) * p_.car.c * std::cos(tilt_rad()); }
  HeldInputs held_inputs() const { return {car_.command_Nm, car_.brake_Nms}; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return car_; }
  const MonorailPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 4;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"tilt_rad", "case_angle_rad", "tilt_rate_rad_s", "case_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const MonorailPlantParams& p_;
  PlantTiming t_;
  Dynamics car_;
  dynamics::Rk4<Dynamics> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Dynamics>> driver_;
  State x_;
  sensors::Encoder encoder_;
  sensors::SensorNoise tilt_noise_, tilt_rate_noise_, case_rate_noise_;
  random::SeededRng rng_tilt_, rng_tilt_rate_, rng_case_rate_;
};

}  // namespace gyrostab::plants
