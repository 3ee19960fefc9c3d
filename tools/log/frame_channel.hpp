// The frames of a run as channels (the MCAP export's /gyrostab/sensor and /gyrostab/actuator, the LCM view's
// charts): per direction the header fields after the tick (time_ns, sample_time_ns or sensor_tick, sequence,
// status) and every signal of the device's table in frame order, an array signal as one array field whose
// elements Foxglove addresses as `name[i]` and PlotJuggler lists as `name[i]`. Names, symbols, units, ranges
// and descriptions are the table's (msg::DeviceSignals), so a signal added to a table is on the channel with
// nothing written here. Docs: docs/mcap.md.
#pragma once

#include <cstddef>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/signal_spec.hpp"
#include "tools/log/signal_channel.hpp"

namespace gyrostab::tools {

enum class FrameDirection { kSensor, kActuator };

inline constexpr const char* kSensorTopic = "/gyrostab/sensor";
inline constexpr const char* kActuatorTopic = "/gyrostab/actuator";

// Header values before the signals in a frame channel's row (the tick is the row's tick, not a value).
inline constexpr std::size_t kFrameHeaderValues = 4;
// Index of the status word in a frame channel's row.
inline constexpr std::size_t kFrameStatusValue = 3;

// The channel of one direction of the device's frames: topic, schema title "gyrostab.<device>.sensor" or
// ".actuator", the header fields (integers) and the signals as declared.
ChannelInfo frame_channel(const msg::DeviceSignals& device, FrameDirection direction);
// Values per row: kFrameHeaderValues + the direction's signal count.
std::size_t frame_width(const msg::DeviceSignals& device, FrameDirection direction);

// A frame's row: the header values (each an integer, exact as a double below 2^53) then its signals.
// `out` holds frame_width() values. O(signals), no allocation.
void frame_values(const msg::AnySensorFrame& f, const msg::DeviceSignals& device, double* out);
void frame_values(const msg::AnyActuatorFrame& f, const msg::DeviceSignals& device, double* out);

}  // namespace gyrostab::tools
