// Controller of an instrument without torquers: a free position gyro read at its gimbal pick-offs (Magnus
// §12.1), the U-gyro rate gyro restrained by its spring (§15.4) and the spatial compass of Bauersfeld
// (§13.4). The instrument needs no control law;
// the controller exists because every device runs the same loop (fault monitor, scheduler, header, safe
// state: controller_runtime.hpp), so its frames, counters and faults are screened and logged like any
// other device's, in process, over LCM, CAN and on the target image.
//
// Law: none. Reads nothing of the SensorFrame beyond what the runtime screens.
// Writes (ActuatorFrame): zero torque on both gimbal axes, precession_brake = 0. In the safe state the
// runtime sets the brake to 1; the instruments' plants ignore it (an instrument has no brake).
// No drive. Rates: the (empty) law every control_divisor base ticks.
// Docs: docs/models/gimbal-error.md, docs/models/u-gyro.md, docs/models/bauersfeld-compass.md
#pragma once

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct FreeInstrumentConfig {
  RuntimeConfig runtime{};
};

class FreeInstrumentLaw {
 public:
  explicit FreeInstrumentLaw(const FreeInstrumentConfig&) {}

  void control(const msg::SensorFrame&, msg::ActuatorFrame& cmd) {
    cmd.gimbal_torque_Nm[msg::kAxis1] = 0.0;
    cmd.gimbal_torque_Nm[msg::kAxis2] = 0.0;
    cmd.precession_brake = 0.0;
  }
  void reset() {}  // stateless
};

template <MonotonicClock Clock = NullClock>
class BasicFreeInstrumentController : public ControllerRuntime<FreeInstrumentLaw, Clock> {
  using Base = ControllerRuntime<FreeInstrumentLaw, Clock>;

 public:
  using Config = FreeInstrumentConfig;

  static ConfigCheck check(const Config& c) { return check_runtime(c.runtime, DriveConfig{}, 0u); }

  explicit BasicFreeInstrumentController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, FreeInstrumentLaw(c), check(c), clock) {}
};

using FreeInstrumentController = BasicFreeInstrumentController<>;

}  // namespace gyrostab::firmware
