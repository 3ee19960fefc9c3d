// Gyro vertical controller (Magnus §12.3, (12.35)-(12.51)): the erection (correction) torquers of a gyro
// horizon from its erection sensor, inside the common controller runtime (fault monitor, scheduler, header,
// safe state: controller_runtime.hpp).
//
// Law: firmware/control/gyro_vertical_correction.hpp — the five rows of (12.35) (pendulous, viscous,
// Coulomb, linear, relay) summed, with the book's remedy for the turn error (turn cut-out) and a torque limit.
// Reads (SensorFrame; plant: sim/plants/gyro_vertical_plant.hpp):
//   gimbal_angle_rad[kAxis1] = e1 = α − α_L   erection sensor (liquid level on the rotor case), tilt of the
//   gimbal_angle_rad[kAxis2] = e2 = β − β_L   rotor axis from the apparent vertical about axes 1, 2 [rad]
//   gimbal_rate_rad_s[kAxis1] = α', [kAxis2] = β'   gimbal rates relative to the level frame [rad/s]
//   carrier_rate_rad_s[kYaw] = turn rate from the turn indicator (a P rate gyro, (15.6)) [rad/s]
//   (carrier_angle_rad[kRoll], [kPitch] carry the instrument's indication of bank and pitch, φ − α, θ − β;
//   the law does not read them.)
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = M1, gimbal_torque_Nm[kAxis2] = M2 [N m] (torquers);
// precession_brake = 0 (an instrument has no brake; in the safe state the runtime sets 1, which the plant
// ignores: zero torque leaves a free gyro that holds its attitude); status kCorrectionCutOut,
// kInstrumentTorqueLimited + the runtime's.
// No drive (torque-mode torquers). Rates: the law every control_divisor base ticks.
// Docs: docs/models/gyro-vertical.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/gyro_vertical_correction.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct GyroVerticalConfig {
  RuntimeConfig runtime{};
  GyroVerticalCorrectionParams law{};
};

class GyroVerticalLaw {
 public:
  explicit GyroVerticalLaw(const GyroVerticalConfig& c) : p_(c.law) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    const CorrectionSignals s{in.gimbal_angle_rad[msg::kAxis1], in.gimbal_angle_rad[msg::kAxis2],
                              in.gimbal_rate_rad_s[msg::kAxis1], in.gimbal_rate_rad_s[msg::kAxis2],
                              in.carrier_rate_rad_s[msg::kYaw]};
    const CorrectionTorques t = gyro_vertical_correction(p_, s);
    cmd.gimbal_torque_Nm[msg::kAxis1] = t.M1;
    cmd.gimbal_torque_Nm[msg::kAxis2] = t.M2;
    cmd.precession_brake = 0.0;
    if (t.cut_out) cmd.status |= bit(LawStatusBit::kCorrectionCutOut);
    if (t.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() {}  // stateless

  const GyroVerticalCorrectionParams& params() const { return p_; }

 private:
  GyroVerticalCorrectionParams p_;
};

template <MonotonicClock Clock = NullClock>
class BasicGyroVerticalController : public ControllerRuntime<GyroVerticalLaw, Clock> {
  using Base = ControllerRuntime<GyroVerticalLaw, Clock>;

 public:
  using Config = GyroVerticalConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_gyro_vertical_correction(c.law, c.runtime.control_period_s());
  }

  explicit BasicGyroVerticalController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, GyroVerticalLaw(c), check(c), clock) {}
};

using GyroVerticalController = BasicGyroVerticalController<>;

}  // namespace gyrostab::firmware
