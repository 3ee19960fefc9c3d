// Which fields of two frames differ, bit for bit — for replay's mismatch report. Doubles compare as their bit
// patterns (so -0.0 vs 0.0 and different NaN payloads count as different, as memcmp does), and each
// difference is printed as `field: recorded X, replayed Y` with %.17g (round-trippable) values.
#pragma once

#include <string>

#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::tools::buslog {

// Empty when the frames are byte-identical (memcmp of the whole frame; neither has padding).
std::string frame_differences(const msg::ActuatorFrame& recorded, const msg::ActuatorFrame& replayed);
std::string frame_differences(const msg::SensorFrame& recorded, const msg::SensorFrame& resimulated);

}  // namespace gyrostab::tools::buslog
