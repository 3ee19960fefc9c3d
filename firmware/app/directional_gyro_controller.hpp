// Directional (heading) gyro controller (Magnus §12.2, (12.22)-(12.24)): drift compensation, heading
// correction toward the compass and inter-gimbal correction, inside the common controller runtime (fault
// monitor, scheduler, header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/directional_gyro_corrections.hpp — M2 = (12.22) compensation (set for a configured
// latitude and ground speed, at the gyro's own indicated heading) + H κ (ψ − ψ_soll) (12.23),
// M1 = −k β (12.24); the turn cut-out; a torque limit.
// Frames: the directional gyro's own (tools/devices/directional_gyro/directional_gyro_signals.toml,
// docs/icd/directional_gyro.md; plant: sim/plants/directional_gyro_plant.hpp). Reads:
//   indicated_heading_rad = ψ   the heading indication: the outer-gimbal pick-off read on the card
//                               (outer-gimbal angle against the case + the card's setting), [−π, π) [rad]
//   inner_gimbal_rad = β        inner-gimbal pick-off [rad]
//   compass_heading_rad = ψ_soll   the external heading reference (compass), [−π, π) [rad]
//   case_yaw_rate_rad_s = turn rate about the vehicle's normal axis (the cut-out's input) [rad/s]
//   (also sent, not read: the gimbal rates α', β', the bank and the other case rates; the fault monitor
//   screens them.)
// Writes outer_torquer_Nm = M1 (outer, normal axis), inner_torquer_Nm = M2 (inner axis) [N m]; status
// kCorrectionCutOut, kInstrumentTorqueLimited + the runtime's. An instrument has no brake: the safe state is
// zero torque, which leaves a free gyro.
// No drive (torque-mode torquers). Rates: the law every control_divisor base ticks.
// Docs: docs/models/directional-gyro.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/directional_gyro_corrections.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "gyrostab_signals/directional_gyro_frames.hpp"

namespace gyrostab::firmware {

struct DirectionalGyroConfig {
  RuntimeConfigOf<msg::directional_gyro::SensorFrame> runtime{};
  DirectionalGyroCorrectionParams law{};
};

class DirectionalGyroLaw {
 public:
  using SensorFrame = msg::directional_gyro::SensorFrame;
  using ActuatorFrame = msg::directional_gyro::ActuatorFrame;

  explicit DirectionalGyroLaw(const DirectionalGyroConfig& c) : p_(c.law) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    const DirectionalGyroSignals s{in.indicated_heading_rad, in.inner_gimbal_rad, in.compass_heading_rad,
                                   in.case_yaw_rate_rad_s};
    const DirectionalGyroTorques t = directional_gyro_corrections(p_, s);
    cmd.outer_torquer_Nm = t.M1;
    cmd.inner_torquer_Nm = t.M2;
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
