// The gyrostab bus log: an LCM event log (LCM's own file format, written and read through lcm/eventlog.h, so
// lcm-logplayer and lcm-spy open it) with a fixed event order, so that a log alone replays a run
// (docs/logs.md):
//
//   event 0            GYROSTAB_SCENE<suffix>     scene_t      timestamp 0
//   event 1 + 2k       GYROSTAB_SENSOR<suffix>    sensor_frame_t   of tick k   timestamp sim_time_us(k)
//   event 2 + 2k       GYROSTAB_ACTUATOR<suffix>  actuator_frame_t of tick k   timestamp sim_time_us(k)
//   last event         GYROSTAB_END<suffix>       log_end_t    timestamp sim_time_us(ticks)
//
// Timestamps are simulated time, not LCM's usual receive wall time: timestamp = k · tick_ns / 1000 µs
// (integer division), the same value the frames carry in sim_time_us. The sensor/actuator channels are the
// ones the LCM link uses on the bus (hil/lcm), with the run's channel suffix.
#pragma once

#include <cstdint>
#include <string>

#include "hil/lcm/log_event_codec.hpp"

namespace gyrostab::tools::buslog {

// The scene and end events' types and codec live beside the frame codec (hil/lcm/).
using hil::EndEvent;
using hil::EndReason;
using hil::kLogVersion;
using hil::SceneEvent;

inline constexpr const char* kSceneChannel = "GYROSTAB_SCENE";
inline constexpr const char* kSensorChannel = "GYROSTAB_SENSOR";
inline constexpr const char* kActuatorChannel = "GYROSTAB_ACTUATOR";
inline constexpr const char* kEndChannel = "GYROSTAB_END";

// LCM's own reader refuses channel names of 1000 bytes or more (lcm/eventlog.c).
inline constexpr int kMaxChannelLength = 999;
// Largest scene_t / log_end_t payload accepted when reading (a scene file is a few kB): a corrupt length field
// must not make the reader allocate the rest of a large file.
inline constexpr int kMaxSceneEventBytes = 16 << 20;

// The event timestamp of tick k [µs]: simulated time, integer division (tick_ns >= 1000 in every scene, see
// tools/scene/loop_config.cpp, so distinct ticks have distinct timestamps).
constexpr std::int64_t sim_time_us(std::int64_t tick, std::int64_t tick_ns) {
  return tick * tick_ns / 1000;
}

inline std::string channel(const char* base, const std::string& suffix) {
  return std::string(base) + suffix;
}

}  // namespace gyrostab::tools::buslog
