// Power gyro stabilizer controller (Magnus §14.3): the two-axis loops (14.19) with rate damping, or the
// single-axis back-EMF voltage law (14.27), with the Hurwitz gain check (14.25)/(14.30) — all in
// firmware/control/power_stabilizer_loops.hpp (PowerStabilizerLoops) — inside the common controller runtime
// (fault monitor, scheduler, header, safe state: firmware/app/controller_runtime.hpp).
//
// Frames: the power stabilizer's own (tools/devices/power_stabilizer/power_stabilizer_signals.toml,
// docs/icd/power_stabilizer.md).
// Reads alpha_rad = α, beta_rad = β [rad], alpha_rate_rad_s = α', beta_rate_rad_s = β' [rad/s]; with the drive
// enabled (torque mode only) the current loops also read motor1_current_A, motor2_current_A [A].
// Writes: torque mode — motor1_torque_Nm = M1^K, motor2_torque_Nm = M2^K [N m], and with the drive enabled
// motor1_voltage_V, motor2_voltage_V from the current loops (channel 0: axis 1, channel 1: axis 2); voltage
// mode — motor1_voltage_V = u_cmd [V] (the drive must be disabled: the law itself outputs the voltage); every
// value 0 in the safe state (the stabilizer has no brake); status bits PowerStabilizerStatusBit 16-20 + the
// runtime's (law_status_bits.hpp).
// ConfigCheck for refused gains: reason = GainCheck::reason, value = the gain margin σ_max (< 1 when
// refused), upper = k_max_equal (torque mode) or r_max (voltage mode); the full GainCheck via gain_check().
// Rates: the loops every control_divisor base ticks (stateless, no dt); the drives every drive_divisor.
// Docs: docs/models/power-stabilizer.md
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/power_stabilizer_loops.hpp"
#include "gyrostab_signals/power_stabilizer_frames.hpp"

namespace gyrostab::firmware {

struct PowerStabilizerControllerConfig {
  RuntimeConfigOf<msg::power_stabilizer::SensorFrame> runtime{};
  DriveConfig drive{};  // current loops on both axes (torque mode only)
  PowerStabilizerConfig loops{};
};

class PowerStabilizerLaw {
 public:
  using SensorFrame = msg::power_stabilizer::SensorFrame;
  using ActuatorFrame = msg::power_stabilizer::ActuatorFrame;
  static constexpr std::uint32_t kDriveAxes = axis_mask(0) | axis_mask(1);
  // The current loops' values: channel 0 drives axis 1 (α), channel 1 axis 2 (β).
  static constexpr DriveSignals kDriveSignals[kDriveChannels] = {
      {msg::power_stabilizer::CommandIndex::motor1_torque_Nm, msg::power_stabilizer::CommandIndex::motor1_voltage_V,
       msg::power_stabilizer::SensorIndex::motor1_current_A, msg::power_stabilizer::SensorIndex::alpha_rate_rad_s},
      {msg::power_stabilizer::CommandIndex::motor2_torque_Nm, msg::power_stabilizer::CommandIndex::motor2_voltage_V,
       msg::power_stabilizer::SensorIndex::motor2_current_A, msg::power_stabilizer::SensorIndex::beta_rate_rad_s}};

  explicit PowerStabilizerLaw(const PowerStabilizerControllerConfig& c) : loops_(c.loops) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) const { loops_.compute(in, cmd); }
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
