// Gyro pendulum (Schuler-tuned vertical) controller: monitor only. Magnus §12.3.3 (12.59)-(12.68) and
// Chelnokov §2: the tuned instrument is unperturbable BECAUSE nothing acts on it but its own pendulous and
// gyroscopic torques — any correction torque would reintroduce the accelerations it is tuned against. So the
// law commands zero torque on both axes every control tick; the controller runtime still screens each
// sensor frame (fault monitor: ranges, staleness, hold-last-good, latched safe state) and publishes one
// actuator frame per tick with the header and counters (controller_runtime.hpp), as for every device.
// Frames: the gyro pendulum's own (tools/devices/gyro_pendulum/gyro_pendulum_signals.toml,
// docs/icd/gyro_pendulum.md; plant: sim/plants/gyro_pendulum_plant.hpp). Reads nothing: alpha_rad, beta_rad =
// the case's tilt α, β from the geocentric vertical (an observer's pick-off), alpha_rate_rad_s,
// beta_rate_rad_s = α', β' and rotor_speed_rad_s are for the monitor and the log.
// Writes torque_F1_Nm = torque_F2_Nm = 0 (the safe state's values too: an instrument has no brake).
// No drive, no state, no heap; cross-compiles for the Cortex-M4F target.
// Docs: docs/models/gyro-pendulum.md
#pragma once

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "gyrostab_signals/gyro_pendulum_frames.hpp"

namespace gyrostab::firmware {

struct GyroPendulumConfig {
  RuntimeConfigOf<msg::gyro_pendulum::SensorFrame> runtime{};
};

class GyroPendulumLaw {
 public:
  using SensorFrame = msg::gyro_pendulum::SensorFrame;
  using ActuatorFrame = msg::gyro_pendulum::ActuatorFrame;

  explicit GyroPendulumLaw(const GyroPendulumConfig& /*c*/) {}

  void control(const SensorFrame& /*in*/, ActuatorFrame& cmd) {
    cmd.torque_F1_Nm = 0.0;
    cmd.torque_F2_Nm = 0.0;
  }
  void reset() {}  // stateless
};

template <MonotonicClock Clock = NullClock>
class BasicGyroPendulumController : public ControllerRuntime<GyroPendulumLaw, Clock> {
  using Base = ControllerRuntime<GyroPendulumLaw, Clock>;

 public:
  using Config = GyroPendulumConfig;

  static ConfigCheck check(const Config& c) { return check_runtime(c.runtime, DriveConfig{}, 0u); }

  explicit BasicGyroPendulumController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, GyroPendulumLaw(c), check(c), clock) {}
};

using GyroPendulumController = BasicGyroPendulumController<>;

}  // namespace gyrostab::firmware
