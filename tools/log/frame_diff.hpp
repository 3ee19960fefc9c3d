// Which fields of two frames differ, bit for bit — for replay's mismatch report. Doubles compare as their bit
// patterns (so -0.0 vs 0.0 and different NaN payloads count as different, as memcmp does), and each
// difference is printed as `field: recorded X, replayed Y` with %.17g (round-trippable) values.
#pragma once

#include <string>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/signal_spec.hpp"

namespace gyrostab::tools::buslog {

// Empty when the frames are byte-identical (memcmp of the whole frame; neither has padding); else the differing
// header fields and signals, named as the device's signal table names them.
std::string frame_differences(const msg::AnyActuatorFrame& recorded, const msg::AnyActuatorFrame& replayed,
                              const msg::DeviceSignals& device);
std::string frame_differences(const msg::AnySensorFrame& recorded, const msg::AnySensorFrame& resimulated,
                              const msg::DeviceSignals& device);

}  // namespace gyrostab::tools::buslog
