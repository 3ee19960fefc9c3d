// Ship roll damper controller (Magnus §14.2, (14.8)): the passive precession brake or the active precession
// control on the gyro case axis 2, inside the common controller runtime (fault monitor, scheduler, header,
// safe state: firmware/app/controller_runtime.hpp).
//
// Laws: firmware/control/precession_brake.hpp (kPassiveBrake: M2 = −d2 β') and
// firmware/control/active_precession_control.hpp (kActive: roll-rate feedback, soft limit, end-stop
// braking, saturation; sign and stability argument there).
// Reads (SensorFrame): carrier_rate_rad_s[kRoll] = φ' [rad/s] (active only), gimbal_angle_rad[kAxis2] = β
// [rad] (active only), gimbal_rate_rad_s[kAxis2] = β' [rad/s]; with the drive enabled also
// motor_current_A[kAxis2] [A].
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis2] = M2 [N m] (the plant's d2 must be 0: the brake is this
// torque); gimbal_torque_Nm[kAxis1] = 0; precession_brake = 0 (released; 1 only in the safe state);
// motor_voltage_V[kAxis2] [V] from the current loop when the drive is enabled, else 0; status bits
// kAxis2TorqueSaturated, kBeyondSoftLimit, kEndStopBraking (law_status_bits.hpp) + the runtime's.
// Rates: the law runs every control_divisor base ticks with dt = T_c (the laws here are static in time
// except the braking direction); the drive on axis 2 every drive_divisor ticks.
// Docs: docs/models/ship-roll-damper.md#firmware-laws
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/active_precession_control.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/precession_brake.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

enum class ShipRollDamperMode : std::uint8_t {
  kPassiveBrake,  // M2 = −d2 β' (Hahnkamm's brake)
  kActive,        // active precession control
};

struct ShipRollDamperConfig {
  RuntimeConfig runtime{};
  DriveConfig drive{};  // current loop on axis 2 (optional)
  ShipRollDamperMode mode{ShipRollDamperMode::kActive};
  PrecessionBrakeParams brake{};    // kPassiveBrake
  ActivePrecessionParams active{};  // kActive
};

// The law adapter: contract fields ↔ the ship-damper laws.
class ShipRollDamperLaw {
 public:
  static constexpr std::uint32_t kDriveAxes = 1u << msg::kAxis2;

  explicit ShipRollDamperLaw(const ShipRollDamperConfig& c)
      : mode_(c.mode), brake_(c.brake), active_(c.active) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    cmd.gimbal_torque_Nm[msg::kAxis1] = 0.0;
    cmd.precession_brake = 0.0;
    if (mode_ == ShipRollDamperMode::kPassiveBrake) {
      const Clipped m = precession_brake_torque(brake_, in.gimbal_rate_rad_s[msg::kAxis2]);
      cmd.gimbal_torque_Nm[msg::kAxis2] = m.value;
      if (m.clipped) cmd.status |= bit(LawStatusBit::kAxis2TorqueSaturated);
      return;
    }
    const ActivePrecessionInputs x{in.carrier_rate_rad_s[msg::kRoll], in.gimbal_angle_rad[msg::kAxis2],
                                   in.gimbal_rate_rad_s[msg::kAxis2]};
    const ActivePrecessionOutput o = active_precession_step(active_, state_, x);
    cmd.gimbal_torque_Nm[msg::kAxis2] = o.torque_Nm;
    if (o.saturated) cmd.status |= bit(LawStatusBit::kAxis2TorqueSaturated);
    if (o.beyond_soft_limit) cmd.status |= bit(LawStatusBit::kBeyondSoftLimit);
    if (o.braking) cmd.status |= bit(LawStatusBit::kEndStopBraking);
  }
  void reset() { state_ = {}; }

  ShipRollDamperMode mode() const { return mode_; }
  const ActivePrecessionState& active_state() const { return state_; }

 private:
  ShipRollDamperMode mode_;
  PrecessionBrakeParams brake_;
  ActivePrecessionParams active_;
  ActivePrecessionState state_{};
};

template <MonotonicClock Clock = NullClock>
class BasicShipRollDamperController : public ControllerRuntime<ShipRollDamperLaw, Clock> {
 public:
  using Config = ShipRollDamperConfig;

  // Runtime (tick, divisors, drive), then the law of the configured mode at the control period. O(1).
  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, c.drive, ShipRollDamperLaw::kDriveAxes);
    if (!r.ok) return r;
    const double T = c.runtime.control_period_s();
    return c.mode == ShipRollDamperMode::kPassiveBrake ? check_precession_brake(c.brake, T)
                                                       : check_active_precession(c.active, T);
  }

  explicit BasicShipRollDamperController(const Config& c, Clock clock = Clock{})
      : ControllerRuntime<ShipRollDamperLaw, Clock>(c.runtime, c.drive, ShipRollDamperLaw::kDriveAxes,
                                                    ShipRollDamperLaw(c), check(c), clock) {}
};

using ShipRollDamperController = BasicShipRollDamperController<>;

}  // namespace gyrostab::firmware
