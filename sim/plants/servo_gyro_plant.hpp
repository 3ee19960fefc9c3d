// The servo gyro as a gyroscopic vibrator drive, as it runs in a scene (Magnus §14.4, (14.41)-(14.44),
// Fig. 14.9): the gimballed rotor of sim/models/servo_gyro.hpp in its torque-driven mode — the firmware's
// rate loop is the motor on axis 2, so the model's ideal speed control is off — with the held motor torque
// and the safe state's brake on axis 2, integrated by RK4 with the scene's sub-steps; axis 1 carries the
// oscillator (c1, d1) that the gyroscopic torque M1^KR = −H cosβ β' (14.42) drives. Sensors: a single-turn
// absolute encoder on axis 2 (β read in [−π, π): axis 2 turns without end), a tachometer for β' (noise
// density, bias), an incremental encoder on axis 1 (α) and an axis-1 rate pick-off (noise density).
//
// State: [α, β, α', β'] in rad and rad/s (named accessors below). Frames: the servo gyro's own
// (tools/devices/servo_gyro/servo_gyro_signals.toml, docs/icd/servo_gyro.md): in, motor_torque_Nm = M2 [N m]
// and precession_brake in [0, 1] × brake_full_Nms [N m s/rad] on β'; out, alpha_rad, drive_angle_rad,
// alpha_rate_rad_s, drive_rate_rad_s, alpha_encoder_count, drive_encoder_count.
// Random streams of the scene seed, one per consumer (seeded_rng.hpp): 1 the tachometer, 2 the axis-1 rate;
// adding a consumer never shifts another.
// Allocation-free after construction. Docs: docs/models/servo-gyro.md. Oracle:
// tests/oracle/servo_gyro_test.cpp (the model); the shipped scene sim/scenes/servo-gyro.toml runs in
// tests/determinism and tests/alloc.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/servo_gyro_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/servo_gyro.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct ServoGyroSensorParams {
  double drive_rate_noise_density{1e-5};             // axis-2 tachometer, the rate loop's input [rad/s/√Hz]
  double drive_rate_bias{0.0};                       // axis-2 tachometer bias [rad/s]
  double alpha_rate_noise_density{1e-5};             // axis-1 rate, the feed-forward's input [rad/s/√Hz]
  std::int64_t drive_encoder_counts_per_rev{65536};  // axis 2, absolute single turn [counts/rev]
  std::int64_t alpha_encoder_counts_per_rev{65536};  // axis 1, incremental [counts/rev]
};

struct ServoGyroPlantParams {
  models::ServoGyroParams gyro{.rate_driven = false};  // the firmware's rate loop drives axis 2
  double brake_full_Nms{10.0};  // brake on axis 2 at precession_brake = 1 (safe state) [N m s/rad]
  ServoGyroSensorParams sensors{};
};

// The servo gyro with the held motor torque and the brake on axis 2 as a viscous torque −brake β'.
struct DrivenServoGyro {
  static constexpr int kStateSize = 4;
  using State = models::ServoGyro::State;
  mutable models::ServoGyro gyro;
  double brake_Nms{0.0};   // [N m s/rad]
  double command_Nm{0.0};  // motor torque [N m]

  void derivative(double t, const State& x, State& dx) const {
    gyro.inputs.M2 = command_Nm - brake_Nms * x[models::ServoGyro::kBetaRate];
    gyro.derivative(t, x, dx);
  }
  void project(State&) const {}
};

class ServoGyroPlant {
 public:
  using SensorFrame = msg::servo_gyro::SensorFrame;
  using ActuatorFrame = msg::servo_gyro::ActuatorFrame;
  using Gyro = models::ServoGyro;
  using Dynamics = DrivenServoGyro;
  using State = Dynamics::State;
  enum Stream : std::uint64_t { kDriveRateStream = 1, kAlphaRateStream };
  struct HeldInputs {
    double command_Nm{0.0};  // motor torque held over the tick [N m]
    double brake_Nms{0.0};   // viscous brake held over the tick [N m s/rad]
  };

  ServoGyroPlant(const ServoGyroPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        gyro_{Gyro(p.gyro), 0.0, 0.0},
        integ_(gyro_),
        driver_(integ_, t.tick_ns, t.substeps),
        drive_encoder_({p.sensors.drive_encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kAbsolute,
                        sensors::EncoderParams::Rounding::kNearest}),
        alpha_encoder_({p.sensors.alpha_encoder_counts_per_rev, 0.0,
                        sensors::EncoderParams::Mode::kIncremental,
                        sensors::EncoderParams::Rounding::kNearest}),
        drive_rate_noise_({p.sensors.drive_rate_noise_density, p.sensors.drive_rate_bias, 0.0}, t.tick_s()),
        alpha_rate_noise_({p.sensors.alpha_rate_noise_density, 0.0, 0.0}, t.tick_s()),
        rng_drive_rate_(t.seed, kDriveRateStream),
        rng_alpha_rate_(t.seed, kAlphaRateStream) {
    x_ = Gyro::make_state(0.0, 0.0, 0.0, 0.0);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    const std::int64_t drive_counts = drive_encoder_.counts(beta_rad());
    double beta = drive_encoder_.angle_of(drive_counts);
    if (beta >= std::numbers::pi) beta -= 2.0 * std::numbers::pi;
    f.drive_encoder_count = static_cast<double>(static_cast<std::int32_t>(drive_counts));
    f.drive_angle_rad = beta;
    f.drive_rate_rad_s = beta_rate_rad_s() + drive_rate_noise_.sample(rng_drive_rate_);
    const std::int64_t alpha_counts = alpha_encoder_.counts(alpha_rad());
    f.alpha_encoder_count = static_cast<double>(static_cast<std::int32_t>(alpha_counts));
    f.alpha_rad = alpha_encoder_.angle_of(alpha_counts);
    f.alpha_rate_rad_s = alpha_rate_rad_s() + alpha_rate_noise_.sample(rng_alpha_rate_);
  }

  void actuate(const ActuatorFrame& cmd) {
    gyro_.command_Nm = cmd.motor_torque_Nm;
    gyro_.brake_Nms = std::clamp(cmd.precession_brake, 0.0, 1.0) * p_.brake_full_Nms;
  }

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }

  bool finite() const { return x_.allFinite(); }

  double alpha_rad() const { return x_[Gyro::kAlpha]; }
  double beta_rad() const { return x_[Gyro::kBeta]; }
  double alpha_rate_rad_s() const { return x_[Gyro::kAlphaRate]; }
  double beta_rate_rad_s() const { return x_[Gyro::kBetaRate]; }
  // (14.42) at the current state [N m].
  double gyro_torque_axis1_Nm() const { return gyro_.gyro.gyro_torque_axis1(x_); }
  // The torque on axis 2 at the start of the tick: motor minus brake, held (zero-order) over it [N m].
  double axis2_torque_Nm() const { return gyro_.command_Nm - gyro_.brake_Nms * beta_rate_rad_s(); }
  HeldInputs held_inputs() const { return {gyro_.command_Nm, gyro_.brake_Nms}; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return gyro_; }
  const ServoGyroPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 4;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const ServoGyroPlantParams& p_;
  PlantTiming t_;
  Dynamics gyro_;
  dynamics::Rk4<Dynamics> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Dynamics>> driver_;
  State x_;
  sensors::Encoder drive_encoder_, alpha_encoder_;
  sensors::SensorNoise drive_rate_noise_, alpha_rate_noise_;
  random::SeededRng rng_drive_rate_, rng_alpha_rate_;
};

}  // namespace gyrostab::plants
