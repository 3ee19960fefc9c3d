// Directional (heading) gyro controller (Magnus §12.2, (12.22)-(12.24)): drift compensation, heading
// correction toward the compass and inter-gimbal correction, inside the common controller runtime (fault
// monitor, scheduler, header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/directional_gyro_corrections.hpp — M2 = (12.22) compensation (set for a configured
// latitude and ground speed, at the gyro's own indicated heading) + H κ (ψ − ψ_soll) (12.23),
// M1 = −k β (12.24); the turn cut-out; a torque limit.
// Reads (SensorFrame; plant: sim/plants/directional_gyro_plant.hpp):
//   gimbal_angle_rad[kAxis1] = ψ   the heading indication: the outer-gimbal pick-off read on the card
//                                  (outer-gimbal angle against the case + the card's setting), (−π, π] [rad]
//   gimbal_angle_rad[kAxis2] = β   inner-gimbal pick-off [rad]
//   carrier_angle_rad[kYaw] = ψ_soll   the external heading reference (compass), (−π, π] [rad]
//   carrier_rate_rad_s[kYaw] = turn rate about the vehicle's normal axis (the cut-out's input) [rad/s]
//   (also filled, not read: gimbal_rate_rad_s = α', β'; carrier_angle_rad[kRoll] = bank; carrier rates.)
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = M1 (outer, normal axis), gimbal_torque_Nm[kAxis2] = M2
// (inner axis) [N m]; precession_brake = 0 (an instrument has no brake; in the safe state the runtime sets 1,
// which the plant ignores: zero torque leaves a free gyro); status kCorrectionCutOut,
// kInstrumentTorqueLimited + the runtime's.
// No drive (torque-mode torquers). Rates: the law every control_divisor base ticks.
// Docs: docs/models/directional-gyro.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/directional_gyro_corrections.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct DirectionalGyroConfig {
  RuntimeConfig runtime{};
  DirectionalGyroCorrectionParams law{};
};

class DirectionalGyroLaw {
 public:
  explicit DirectionalGyroLaw(const DirectionalGyroConfig& c) : p_(c.law) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    const DirectionalGyroSignals s{in.gimbal_angle_rad[msg::kAxis1], in.gimbal_angle_rad[msg::kAxis2],
                                   in.carrier_angle_rad[msg::kYaw], in.carrier_rate_rad_s[msg::kYaw]};
    const DirectionalGyroTorques t = directional_gyro_corrections(p_, s);
    cmd.gimbal_torque_Nm[msg::kAxis1] = t.M1;
    cmd.gimbal_torque_Nm[msg::kAxis2] = t.M2;
    cmd.precession_brake = 0.0;
    if (t.cut_out) cmd.status |= bit(LawStatusBit::kCorrectionCutOut);
    if (t.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() {}  // stateless

  const DirectionalGyroCorrectionParams& params() const { return p_; }

 private:
  DirectionalGyroCorrectionParams p_;
};

template <MonotonicClock Clock = NullClock>
class BasicDirectionalGyroController : public ControllerRuntime<DirectionalGyroLaw, Clock> {
  using Base = ControllerRuntime<DirectionalGyroLaw, Clock>;

 public:
  using Config = DirectionalGyroConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_directional_gyro_corrections(c.law, c.runtime.control_period_s());
  }

  explicit BasicDirectionalGyroController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, DirectionalGyroLaw(c), check(c), clock) {}
};

using DirectionalGyroController = BasicDirectionalGyroController<>;

}  // namespace gyrostab::firmware
