// Monorail controller (Magnus §14.1, (14.2)): the motor + damper law M2 = k φ − d β' on the gyro case axis 2,
// with the start-up gain-window check of (14.5), inside the common controller runtime (fault monitor,
// scheduler, header, safe state: firmware/app/controller_runtime.hpp).
//
// Law: firmware/control/monorail_motor_law.hpp (refuses k outside d(c + Aω_P²)/H < k < d(c + Aω_N²)/H
// with the computed bounds in ConfigCheck::lower/upper).
// Frames: the monorail's own (tools/devices/monorail/monorail_signals.toml, docs/icd/monorail.md).
// Reads tilt_rad = φ car tilt [rad], case_rate_rad_s = β' [rad/s].
// Writes motor_torque_Nm = M2 [N m] (the plant's analog law k must be 0); precession_brake = 0 (1 only in the
// safe state — for a monorail the "safe" locked case is no longer gyro-stabilized: the car must then rest on
// its stands, as in any monorail fault); status bit kAxis2TorqueSaturated + the runtime's.
// Rates: the law every control_divisor base ticks (stateless, no dt). The case motor is torque-driven (no
// current loop: the car has no winding-current sensor).
// Docs: docs/models/monorail.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/monorail_motor_law.hpp"
#include "gyrostab_signals/monorail_frames.hpp"

namespace gyrostab::firmware {

struct MonorailConfig {
  RuntimeConfigOf<msg::monorail::SensorFrame> runtime{};
  MonorailMotorParams law{};
};

class MonorailLaw {
 public:
  using SensorFrame = msg::monorail::SensorFrame;
  using ActuatorFrame = msg::monorail::ActuatorFrame;

  explicit MonorailLaw(const MonorailConfig& c) : law_(c.law) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) const {
    const Clipped m = monorail_motor_torque(law_, in.tilt_rad, in.case_rate_rad_s);
    cmd.motor_torque_Nm = m.value;
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
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_monorail_motor(c.law, c.runtime.control_period_s());
  }

  explicit BasicMonorailController(const Config& c, Clock clock = Clock{})
      : ControllerRuntime<MonorailLaw, Clock>(c.runtime, DriveConfig{}, 0u, MonorailLaw(c), check(c), clock) {}
};

using MonorailController = BasicMonorailController<>;

}  // namespace gyrostab::firmware
