// Position-gyro platform controller (Magnus §16.2.2, (16.6)-(16.10), Fig. 16.2): the amplifier from the gyro's
// pick-off to the platform's torquer, M1^KP = −k(δ − α), and the gyro torquer's slew command M2^K = −H ω_cmd,
// inside the common controller runtime (fault monitor, scheduler, header, safe state:
// controller_runtime.hpp).
//
// Law: firmware/control/position_gyro_platform_law.hpp (its check refuses a gain in the unstable band of
// (16.9) with the band's edges, an undamped gyro, and a sampled loop whose discrete closed loop has a
// spectral radius ≥ 1 at the control period and latency).
// Reads (SensorFrame; plant: sim/plants/position_gyro_platform_plant.hpp): gimbal_angle_rad[kAxis1] = δ − α,
// the pick-off between platform and outer gimbal [rad]. (Also filled, not read: carrier_angle_rad[kRoll] = δ,
// carrier_rate_rad_s[kRoll] = δ', gimbal_angle_rad[kAxis2] = β, gimbal_rate_rad_s[kAxis1] = α',
// gimbal_rate_rad_s[kAxis2] = β'.)
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = M1^KP platform torquer, [kAxis2] = M2^K gyro torquer
// [N m]; precession_brake = 0 (the safe state's zero torques leave the platform free on its bearing);
// status kInstrumentTorqueLimited + the runtime's. No drive.
// Docs: docs/models/position-gyro-platform.md#firmware-law
#pragma once

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/position_gyro_platform_law.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct PositionGyroPlatformConfig {
  RuntimeConfig runtime{};
  PositionGyroPlatformParams law{};
};

class PositionGyroPlatformLaw {
 public:
  explicit PositionGyroPlatformLaw(const PositionGyroPlatformConfig& c) : p_(c.law) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    const PositionGyroPlatformCommand c = position_gyro_platform_step(p_, in.tick, in.gimbal_angle_rad[msg::kAxis1]);
    cmd.gimbal_torque_Nm[msg::kAxis1] = c.platform_torque_Nm;
    cmd.gimbal_torque_Nm[msg::kAxis2] = c.gyro_torque_Nm;
    cmd.precession_brake = 0.0;
    if (c.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() {}  // stateless

 private:
  PositionGyroPlatformParams p_;
};

template <MonotonicClock Clock = NullClock>
class BasicPositionGyroPlatformController : public ControllerRuntime<PositionGyroPlatformLaw, Clock> {
  using Base = ControllerRuntime<PositionGyroPlatformLaw, Clock>;

 public:
  using Config = PositionGyroPlatformConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_position_gyro_platform(c.law, c.runtime.control_period_s(), c.runtime.tick_period_s());
  }

  explicit BasicPositionGyroPlatformController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, PositionGyroPlatformLaw(c), check(c), clock) {}
};

using PositionGyroPlatformController = BasicPositionGyroPlatformController<>;

}  // namespace gyrostab::firmware
