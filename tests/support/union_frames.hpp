// The tests' generic device: the union fixture (tests/signals/union_fixture_signals.toml), every shipped
// device's signal shapes in one pair of typed frames, msg::SensorFrame and msg::ActuatorFrame, for the tests of
// the device-independent code (transports, codecs, fault monitor, controller runtime). Never a device of the
// program: generated into the build's generated-test/, which only the tests see.
#pragma once

#include "firmware/fault/fault_monitor.hpp"
#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/axes.hpp"
#include "gyrostab_signals/union_fixture_frames.hpp"

namespace gyrostab::firmware {

using FaultMonitor = FaultMonitorOf<msg::SensorFrame>;
using FaultMonitorConfig = FaultMonitorConfigOf<msg::SensorFrame>;

}  // namespace gyrostab::firmware
