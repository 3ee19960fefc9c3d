// Position-gyro platform controller (Magnus §16.2.2, (16.6)-(16.10), Fig. 16.2): the amplifier from the gyro's
// pick-off to the platform's torquer, M1^KP = −k(δ − α), and the gyro torquer's slew command M2^K = −H ω_cmd,
// inside the common controller runtime (fault monitor, scheduler, header, safe state:
// controller_runtime.hpp).
//
// Law: firmware/control/position_gyro_platform_law.hpp (its check refuses a gain in the unstable band of
// (16.9) with the band's edges, an undamped gyro, and a sampled loop whose discrete closed loop has a
// spectral radius ≥ 1 at the control period and latency).
// Frames: the position-gyro platform's own (tools/devices/position_gyro_platform/
// position_gyro_platform_signals.toml, docs/icd/position_gyro_platform.md; plant:
// sim/plants/position_gyro_platform_plant.hpp). Reads pickoff_rad = δ − α, the pick-off between platform and
// outer gimbal [rad]. (Also sent, not read: platform_rad = δ, platform_rate_rad_s = δ', inner_gimbal_rad = β,
// gyro_frame_rate_rad_s = α', inner_gimbal_rate_rad_s = β'; the fault monitor screens them.)
// Writes platform_torquer_Nm = M1^KP platform torquer, gyro_torquer_Nm = M2^K gyro torquer [N m]; status
// kInstrumentTorqueLimited + the runtime's. No brake: the safe state's zero torques leave the platform free on
// its bearing. No drive.
// Docs: docs/models/position-gyro-platform.md#firmware-law
#pragma once

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/position_gyro_platform_law.hpp"
#include "gyrostab_signals/position_gyro_platform_frames.hpp"

namespace gyrostab::firmware {

struct PositionGyroPlatformConfig {
  RuntimeConfigOf<msg::position_gyro_platform::SensorFrame> runtime{};
  PositionGyroPlatformParams law{};
};

class PositionGyroPlatformLaw {
 public:
  using SensorFrame = msg::position_gyro_platform::SensorFrame;
  using ActuatorFrame = msg::position_gyro_platform::ActuatorFrame;

  explicit PositionGyroPlatformLaw(const PositionGyroPlatformConfig& c) : p_(c.law) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    const PositionGyroPlatformCommand c = position_gyro_platform_step(p_, in.tick, in.pickoff_rad);
    cmd.platform_torquer_Nm = c.platform_torque_Nm;
    cmd.gyro_torquer_Nm = c.gyro_torque_Nm;
    if (c.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() {}  // stateless

 private:
  PositionGyroPlatformParams p_;
};

template <MonotonicClock Clock = NullClock>
class BasicPositionGyroPlatformController : public ControllerRuntime<PositionGyroPlatformLaw, Clock> {
  using Base = ControllerRuntime<PositionGyroPlatformLaw, Clock>;

 public:
  using Config = PositionGyroPlatformConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_position_gyro_platform(c.law, c.runtime.control_period_s(), c.runtime.tick_period_s());
  }

  explicit BasicPositionGyroPlatformController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, PositionGyroPlatformLaw(c), check(c), clock) {}
};

using PositionGyroPlatformController = BasicPositionGyroPlatformController<>;

}  // namespace gyrostab::firmware
