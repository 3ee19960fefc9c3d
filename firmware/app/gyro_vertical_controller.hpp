// Gyro vertical controller (Magnus §12.3, (12.35)-(12.51)): the erection (correction) torquers of a gyro
// horizon from its erection sensor, inside the common controller runtime (fault monitor, scheduler, header,
// safe state: controller_runtime.hpp).
//
// Law: firmware/control/gyro_vertical_correction.hpp — the five rows of (12.35) (pendulous, viscous,
// Coulomb, linear, relay) summed, with the book's remedy for the turn error (turn cut-out) and a torque limit.
// Frames: the gyro vertical's own (tools/devices/gyro_vertical/gyro_vertical_signals.toml,
// docs/icd/gyro_vertical.md; plant: sim/plants/gyro_vertical_plant.hpp). Reads:
//   erection_e1_rad = e1 = α − α_L   erection sensor (liquid level on the rotor case), tilt of the
//   erection_e2_rad = e2 = β − β_L   rotor axis from the apparent vertical about axes 1, 2 [rad]
//   alpha_rate_rad_s = α', beta_rate_rad_s = β'   gimbal rates relative to the level frame [rad/s]
//   turn_indicator_rad_s = turn rate from the turn indicator (a P rate gyro, (15.6)) [rad/s]
//   (indicated_bank_rad, indicated_pitch_rad carry the instrument's indication of bank and pitch, φ − α,
//   θ − β; the law does not read them, the fault monitor screens them.)
// Writes torquer1_Nm = M1, torquer2_Nm = M2 [N m] (torquers); status kCorrectionCutOut,
// kInstrumentTorqueLimited + the runtime's. An instrument has no brake: the safe state is zero torque, which
// leaves a free gyro that holds its attitude.
// No drive (torque-mode torquers). Rates: the law every control_divisor base ticks.
// Docs: docs/models/gyro-vertical.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/gyro_vertical_correction.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "gyrostab_signals/gyro_vertical_frames.hpp"

namespace gyrostab::firmware {

struct GyroVerticalConfig {
  RuntimeConfigOf<msg::gyro_vertical::SensorFrame> runtime{};
  GyroVerticalCorrectionParams law{};
};

class GyroVerticalLaw {
 public:
  using SensorFrame = msg::gyro_vertical::SensorFrame;
  using ActuatorFrame = msg::gyro_vertical::ActuatorFrame;

  explicit GyroVerticalLaw(const GyroVerticalConfig& c) : p_(c.law) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    const CorrectionSignals s{in.erection_e1_rad, in.erection_e2_rad, in.alpha_rate_rad_s, in.beta_rate_rad_s,
                              in.turn_indicator_rad_s};
    const CorrectionTorques t = gyro_vertical_correction(p_, s);
    cmd.torquer1_Nm = t.M1;
    cmd.torquer2_Nm = t.M2;
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
