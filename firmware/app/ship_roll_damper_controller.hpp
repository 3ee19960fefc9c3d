// Ship roll damper controller (Magnus §14.2, (14.8)): the passive precession brake or the active precession
// control on the gyro case axis 2, inside the common controller runtime (fault monitor, scheduler, header,
// safe state: firmware/app/controller_runtime.hpp).
//
// Laws: firmware/control/precession_brake.hpp (kPassiveBrake: M2 = −d2 β') and
// firmware/control/active_precession_control.hpp (kActive: roll-rate feedback, soft limit, end-stop
// braking, saturation; sign and stability argument there).
// Frames: the ship roll damper's own (tools/devices/ship_roll_damper/ship_roll_damper_signals.toml,
// docs/icd/ship_roll_damper.md).
// Reads roll_rate_rad_s = φ' [rad/s] (active only), precession_angle_rad = β [rad] (active only),
// precession_rate_rad_s = β' [rad/s].
// Writes precession_torque_Nm = M2 [N m] (the plant's d2 must be 0: the brake is this torque);
// precession_brake = 0 (released; 1 only in the safe state); status bits kAxis2TorqueSaturated,
// kBeyondSoftLimit, kEndStopBraking (law_status_bits.hpp) + the runtime's.
// Rates: the law runs every control_divisor base ticks with dt = T_c (the laws here are static in time
// except the braking direction). The precession motor is torque-driven (no current loop: the ship's gyro has
// no winding-current sensor).
// Docs: docs/models/ship-roll-damper.md#firmware-laws
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/active_precession_control.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/precession_brake.hpp"
#include "gyrostab_signals/ship_roll_damper_frames.hpp"

namespace gyrostab::firmware {

enum class ShipRollDamperMode : std::uint8_t {
  kPassiveBrake,  // M2 = −d2 β' (Hahnkamm's brake)
  kActive,        // active precession control
};

struct ShipRollDamperConfig {
  RuntimeConfigOf<msg::ship_roll_damper::SensorFrame> runtime{};
  ShipRollDamperMode mode{ShipRollDamperMode::kActive};
  PrecessionBrakeParams brake{};    // kPassiveBrake
  ActivePrecessionParams active{};  // kActive
};

// The law adapter: contract fields ↔ the ship-damper laws.
class ShipRollDamperLaw {
 public:
  using SensorFrame = msg::ship_roll_damper::SensorFrame;
  using ActuatorFrame = msg::ship_roll_damper::ActuatorFrame;

  explicit ShipRollDamperLaw(const ShipRollDamperConfig& c)
      : mode_(c.mode), brake_(c.brake), active_(c.active) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    cmd.precession_brake = 0.0;
    if (mode_ == ShipRollDamperMode::kPassiveBrake) {
      const Clipped m = precession_brake_torque(brake_, in.precession_rate_rad_s);
      cmd.precession_torque_Nm = m.value;
      if (m.clipped) cmd.status |= bit(LawStatusBit::kAxis2TorqueSaturated);
      return;
    }
    const ActivePrecessionInputs x{in.roll_rate_rad_s, in.precession_angle_rad, in.precession_rate_rad_s};
    const ActivePrecessionOutput o = active_precession_step(active_, state_, x);
    cmd.precession_torque_Nm = o.torque_Nm;
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

  // Runtime (tick, divisors), then the law of the configured mode at the control period. O(1).
  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    const double T = c.runtime.control_period_s();
    return c.mode == ShipRollDamperMode::kPassiveBrake ? check_precession_brake(c.brake, T)
                                                       : check_active_precession(c.active, T);
  }

  explicit BasicShipRollDamperController(const Config& c, Clock clock = Clock{})
      : ControllerRuntime<ShipRollDamperLaw, Clock>(c.runtime, DriveConfig{}, 0u, ShipRollDamperLaw(c), check(c),
                                                    clock) {}
};

using ShipRollDamperController = BasicShipRollDamperController<>;

}  // namespace gyrostab::firmware
