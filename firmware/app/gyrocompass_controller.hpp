// Gyrocompass controller (Magnus §13.2-13.3, (13.7)-(13.28)): damping torque about the vertical and
// electrical pendulosity about the east axis from the level sensor, inside the common controller runtime
// (fault monitor, scheduler, header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/gyrocompass_law.hpp — M1 = −f β_lvl (13.8), M2 = −c_e β_lvl; c_e typically set for
// Schuler tuning (13.26) at a design latitude (schuler_tuned_pendulosity).
// Frames: the gyrocompass's own (tools/devices/gyrocompass/gyrocompass_signals.toml, docs/icd/gyrocompass.md;
// plant: sim/plants/gyrocompass_plant.hpp). Reads:
//   level_rad = β_lvl = β − β_L   level sensor: elevation of the rotor axis's north end above the apparent
//                                 horizon (the "β + b^N/g" of (13.21)) [rad]
//   (also sent, not read by the law: follow_up_rad = the rotor axis's azimuth relative to the ship's bow,
//   −(ψ + α) wrapped [rad]; azimuth_rate_rad_s, elevation_rate_rad_s = α', β'; indicated_heading_rad = ψ + α
//   wrapped to [−π, π] [rad]; the fault monitor screens them.)
// Writes vertical_torquer_Nm = M1 (about the vertical), east_torquer_Nm = M2 (about the east axis) [N m];
// status kInstrumentTorqueLimited + the runtime's. No brake: the safe state is zero torque, the sphere keeps
// only its mechanical pendulosity.
// Docs: docs/models/gyrocompass.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/gyrocompass_law.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "gyrostab_signals/gyrocompass_frames.hpp"

namespace gyrostab::firmware {

struct GyrocompassConfig {
  RuntimeConfigOf<msg::gyrocompass::SensorFrame> runtime{};
  GyrocompassLawParams law{};
};

class GyrocompassDeviceLaw {
 public:
  using SensorFrame = msg::gyrocompass::SensorFrame;
  using ActuatorFrame = msg::gyrocompass::ActuatorFrame;

  explicit GyrocompassDeviceLaw(const GyrocompassConfig& c) : p_(c.law) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    const GyrocompassTorques t = gyrocompass_torques(p_, in.level_rad);
    cmd.vertical_torquer_Nm = t.M1;
    cmd.east_torquer_Nm = t.M2;
    if (t.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() {}  // stateless

  const GyrocompassLawParams& params() const { return p_; }

 private:
  GyrocompassLawParams p_;
};

template <MonotonicClock Clock = NullClock>
class BasicGyrocompassController : public ControllerRuntime<GyrocompassDeviceLaw, Clock> {
  using Base = ControllerRuntime<GyrocompassDeviceLaw, Clock>;

 public:
  using Config = GyrocompassConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_gyrocompass_law(c.law, c.runtime.control_period_s());
  }

  explicit BasicGyrocompassController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, GyrocompassDeviceLaw(c), check(c), clock) {}
};

using GyrocompassController = BasicGyrocompassController<>;

}  // namespace gyrostab::firmware
