// Gyro pendulum (Schuler-tuned vertical) controller: monitor only. Magnus §12.3.3 (12.59)-(12.68) and
// Chelnokov §2: the tuned instrument is unperturbable BECAUSE nothing acts on it but its own pendulous and
// gyroscopic torques — any correction torque would reintroduce the accelerations it is tuned against. So the
// law commands zero torque on both axes every control tick; the controller runtime still screens each
// SensorFrame (fault monitor: ranges, staleness, hold-last-good, latched safe state) and publishes one
// ActuatorFrame per tick with the header and counters (controller_runtime.hpp), as for every device.
// Reads (SensorFrame; plant: sim/plants/gyro_pendulum_plant.hpp): gimbal_angle_rad[kAxis1], [kAxis2] =
// the case's tilt α, β from the geocentric vertical (an observer's pick-off, for the monitor and the log),
// gimbal_rate_rad_s = α', β', rotor_speed_rad_s. The law reads none of them.
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = gimbal_torque_Nm[kAxis2] = 0, precession_brake = 0
// (the runtime's safe state sets 1, which the plant ignores: an instrument has no brake).
// No drive, no state, no heap; cross-compiles for the Cortex-M4F target.
// Docs: docs/models/gyro-pendulum.md
#pragma once

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct GyroPendulumConfig {
  RuntimeConfig runtime{};
};

class GyroPendulumLaw {
 public:
  explicit GyroPendulumLaw(const GyroPendulumConfig& /*c*/) {}

  void control(const msg::SensorFrame& /*in*/, msg::ActuatorFrame& cmd) {
    cmd.gimbal_torque_Nm[msg::kAxis1] = 0.0;
    cmd.gimbal_torque_Nm[msg::kAxis2] = 0.0;
    cmd.precession_brake = 0.0;
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
