// Controller of an instrument without torquers: a free position gyro read at its gimbal pick-offs (Magnus
// §12.1), the U-gyro rate gyro restrained by its spring (§15.4), Foucault's declinometer and inclinometer
// gyros (§13.1) and the spatial compass of Bauersfeld (§13.4). The instrument needs no control law;
// the controller exists because every device runs the same loop (fault monitor, scheduler, header, safe
// state: controller_runtime.hpp), so its frames, counters and faults are screened and logged like any
// other device's, in process, over LCM, CAN and on the target image.
//
// A template on the device's typed frames (gyrostab_signals/<device>_frames.hpp, from its signal table
// tools/devices/<device>/<device>_signals.toml): the instrument's sensor frame is screened by the fault
// monitor against its table's ranges; its actuator frame carries no command, only the header and the status
// word (the safe state's kSafeState bit and the runtime's counters' bits reach the log through it).
// Law: none. Reads nothing of the sensor frame beyond what the runtime screens. Writes nothing.
// No drive. Rates: the (empty) law every control_divisor base ticks.
// Docs: docs/models/gimbal-error.md, docs/models/u-gyro.md, docs/models/foucault-gyro.md,
// docs/models/bauersfeld-compass.md
#pragma once

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/msg/any_frame.hpp"

namespace gyrostab::firmware {

template <class SensorFrame>
struct FreeInstrumentConfigOf {
  RuntimeConfigOf<SensorFrame> runtime{};
};

template <msg::TypedFrame Sensor, msg::TypedFrame Actuator>
class FreeInstrumentLawOf {
 public:
  using SensorFrame = Sensor;
  using ActuatorFrame = Actuator;
  static_assert(msg::signal_count_v<ActuatorFrame> == 0,
                "an instrument without torquers takes no command: its signal table declares none");

  explicit FreeInstrumentLawOf(const FreeInstrumentConfigOf<SensorFrame>&) {}

  void control(const SensorFrame&, ActuatorFrame&) {}
  void reset() {}  // stateless
};

template <msg::TypedFrame Sensor, msg::TypedFrame Actuator, MonotonicClock Clock = NullClock>
class BasicFreeInstrumentControllerOf
    : public ControllerRuntime<FreeInstrumentLawOf<Sensor, Actuator>, Clock> {
  using Law = FreeInstrumentLawOf<Sensor, Actuator>;
  using Base = ControllerRuntime<Law, Clock>;

 public:
  using Config = FreeInstrumentConfigOf<Sensor>;

  static ConfigCheck check(const Config& c) { return check_runtime(c.runtime, DriveConfig{}, 0u); }

  explicit BasicFreeInstrumentControllerOf(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, Law(c), check(c), clock) {}
};

}  // namespace gyrostab::firmware
