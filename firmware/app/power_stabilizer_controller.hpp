// Power gyro stabilizer controller (Magnus §14.3): the two-axis loops (14.19) with rate damping, or the
// single-axis back-EMF voltage law (14.27), with the Hurwitz gain check (14.25)/(14.30) — all in
// firmware/control/power_stabilizer_loops.hpp (PowerStabilizerLoops, by a colleague; wrapped, not changed) —
// inside the common controller runtime (fault monitor, scheduler, header, safe state:
// firmware/app/controller_runtime.hpp).
//
// Reads (SensorFrame): gimbal_angle_rad[kAxis1] = α, [kAxis2] = β [rad], gimbal_rate_rad_s[kAxis1] = α',
// [kAxis2] = β' [rad/s]; with the drive enabled (torque mode only) also motor_current_A[kAxis1..2] [A].
// Writes (ActuatorFrame): torque mode — gimbal_torque_Nm[kAxis1] = M1^K, [kAxis2] = M2^K [N m], and with the
// drive enabled motor_voltage_V[kAxis1..2] from the current loops; voltage mode — motor_voltage_V[kAxis1] =
// u_cmd [V] (the drive must be disabled: the law itself outputs the voltage); precession_brake = 0 (1 only in
// the safe state); status bits PowerStabilizerStatusBit 16-20 + the runtime's (law_status_bits.hpp).
// ConfigCheck for refused gains: reason = GainCheck::reason, value = the gain margin σ_max (< 1 when
// refused), upper = k_max_equal (torque mode) or r_max (voltage mode); the full GainCheck via gain_check().
// Rates: the loops every control_divisor base ticks (stateless, no dt); the drives every drive_divisor.
// Docs: docs/models/power-stabilizer.md
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/power_stabilizer_loops.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct PowerStabilizerControllerConfig {
  RuntimeConfig runtime{};
  DriveConfig drive{};  // current loops on both axes (torque mode only)
  PowerStabilizerConfig loops{};
};

class PowerStabilizerLaw {
 public:
  static constexpr std::uint32_t kDriveAxes = (1u << msg::kAxis1) | (1u << msg::kAxis2);

  explicit PowerStabilizerLaw(const PowerStabilizerControllerConfig& c) : loops_(c.loops) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) const { loops_.compute(in, cmd); }
  void reset() {}
  const PowerStabilizerLoops& loops() const { return loops_; }

 private:
  PowerStabilizerLoops loops_;
};

template <MonotonicClock Clock = NullClock>
class BasicPowerStabilizerController : public ControllerRuntime<PowerStabilizerLaw, Clock> {
 public:
  using Config = PowerStabilizerControllerConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, c.drive, PowerStabilizerLaw::kDriveAxes);
    if (!r.ok) return r;
    if (c.drive.enabled && c.loops.output != PowerStabilizerOutput::kTorque) {
      return ConfigCheck::refused(
          "power stabilizer: the current-loop drive needs the torque mode (the voltage law is its own "
          "drive)");
    }
    const GainCheck g = check_power_stabilizer_gains(c.loops);
    if (g.accepted) return ConfigCheck::accepted();
    const double upper = c.loops.output == PowerStabilizerOutput::kTorque ? g.k_max_equal : g.r_max;
    return ConfigCheck::refused(g.reason, g.gain_scale_max, 0.0, upper);
  }

  explicit BasicPowerStabilizerController(const Config& c, Clock clock = Clock{})
      : ControllerRuntime<PowerStabilizerLaw, Clock>(c.runtime, c.drive, PowerStabilizerLaw::kDriveAxes,
                                                     PowerStabilizerLaw(c), check(c), clock) {}

  const GainCheck& gain_check() const { return this->device().loops().gain_check(); }
};

using PowerStabilizerController = BasicPowerStabilizerController<>;

}  // namespace gyrostab::firmware
