// Gyrocompass controller (Magnus §13.2-13.3, (13.7)-(13.28)): damping torque about the vertical and
// electrical pendulosity about the east axis from the level sensor, inside the common controller runtime
// (fault monitor, scheduler, header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/gyrocompass_law.hpp — M1 = −f β_lvl (13.8), M2 = −c_e β_lvl; c_e typically set for
// Schuler tuning (13.26) at a design latitude (schuler_tuned_pendulosity).
// Reads (SensorFrame; plant: sim/plants/gyrocompass_plant.hpp):
//   gimbal_angle_rad[kAxis2] = β_lvl = β − β_L   level sensor: elevation of the rotor axis's north end
//                                                above the apparent horizon (the "β + b^N/g" of (13.21)) [rad]
//   (also filled, not read by the law: gimbal_angle_rad[kAxis1] = follow-up angle, the rotor axis's
//   azimuth relative to the ship's bow, = −(ψ + α) wrapped [rad]; gimbal_rate_rad_s[kAxis1/2] = α', β';
//   carrier_angle_rad[kYaw] = indicated heading ψ + α wrapped to (−π, π] [rad].)
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = M1 (about the vertical), gimbal_torque_Nm[kAxis2] = M2
// (about the east axis) [N m]; precession_brake = 0 (no brake; in the safe state the runtime's 1 is ignored
// by the plant: zero torque, the sphere keeps only its mechanical pendulosity); status
// kInstrumentTorqueLimited + the runtime's.
// Docs: docs/models/gyrocompass.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/gyrocompass_law.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct GyrocompassConfig {
  RuntimeConfig runtime{};
  GyrocompassLawParams law{};
};

class GyrocompassDeviceLaw {
 public:
  explicit GyrocompassDeviceLaw(const GyrocompassConfig& c) : p_(c.law) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    const GyrocompassTorques t = gyrocompass_torques(p_, in.gimbal_angle_rad[msg::kAxis2]);
    cmd.gimbal_torque_Nm[msg::kAxis1] = t.M1;
    cmd.gimbal_torque_Nm[msg::kAxis2] = t.M2;
    cmd.precession_brake = 0.0;
    if (t.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() {}  // stateless

  const GyrocompassLawParams& params() const { return p_; }

 private:
  GyrocompassLawParams p_;
};

template <MonotonicClock Clock = NullClock>
class BasicGyrocompassController : public ControllerRuntime<GyrocompassDeviceLaw, Clock> {
  using Base = ControllerRuntime<GyrocompassDeviceLaw, Clock>;

 public:
  using Config = GyrocompassConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_gyrocompass_law(c.law, c.runtime.control_period_s());
  }

  explicit BasicGyrocompassController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, GyrocompassDeviceLaw(c), check(c), clock) {}
};

using GyrocompassController = BasicGyrocompassController<>;

}  // namespace gyrostab::firmware
