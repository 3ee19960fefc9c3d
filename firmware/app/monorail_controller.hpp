// Monorail controller (Magnus §14.1, (14.2)): the motor + damper law M2 = k φ − d β' on the gyro case axis 2,
// with the start-up gain-window check of (14.5), inside the common controller runtime (fault monitor,
// scheduler, header, safe state: firmware/app/controller_runtime.hpp).
//
// Law: firmware/control/monorail_motor_law.hpp (refuses k outside d(c + Aω_P²)/H < k < d(c + Aω_N²)/H
// with the computed bounds in ConfigCheck::lower/upper).
// Reads (SensorFrame): carrier_angle_rad[kRoll] = φ car tilt [rad], gimbal_rate_rad_s[kAxis2] = β'
// [rad/s]; with the drive enabled also motor_current_A[kAxis2] [A].
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis2] = M2 [N m] (the plant's analog law k must be 0);
// gimbal_torque_Nm[kAxis1] = 0; precession_brake = 0 (1 only in the safe state — for a monorail the
// "safe" locked case is no longer gyro-stabilized: the car must then rest on its stands, as in any
// monorail fault); motor_voltage_V[kAxis2] from the current loop when the drive is enabled;
// status bit kAxis2TorqueSaturated + the runtime's.
// Rates: the law every control_divisor base ticks (stateless, no dt), the drive every drive_divisor ticks.
// Docs: docs/models/monorail.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/monorail_motor_law.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct MonorailConfig {
  RuntimeConfig runtime{};
  DriveConfig drive{};  // current loop on axis 2 (optional)
  MonorailMotorParams law{};
};

class MonorailLaw {
 public:
  static constexpr std::uint32_t kDriveAxes = 1u << msg::kAxis2;

  explicit MonorailLaw(const MonorailConfig& c) : law_(c.law) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) const {
    const Clipped m =
        monorail_motor_torque(law_, in.carrier_angle_rad[msg::kRoll], in.gimbal_rate_rad_s[msg::kAxis2]);
    cmd.gimbal_torque_Nm[msg::kAxis1] = 0.0;
    cmd.gimbal_torque_Nm[msg::kAxis2] = m.value;
    cmd.precession_brake = 0.0;
    if (m.clipped) cmd.status |= bit(LawStatusBit::kAxis2TorqueSaturated);
  }
  void reset() {}

 private:
  MonorailMotorParams law_;
};

template <MonotonicClock Clock = NullClock>
class BasicMonorailController : public ControllerRuntime<MonorailLaw, Clock> {
 public:
  using Config = MonorailConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, c.drive, MonorailLaw::kDriveAxes);
    if (!r.ok) return r;
    return check_monorail_motor(c.law, c.runtime.control_period_s());
  }

  explicit BasicMonorailController(const Config& c, Clock clock = Clock{})
      : ControllerRuntime<MonorailLaw, Clock>(c.runtime, c.drive, MonorailLaw::kDriveAxes, MonorailLaw(c),
                                              check(c), clock) {}
};

using MonorailController = BasicMonorailController<>;

}  // namespace gyrostab::firmware
