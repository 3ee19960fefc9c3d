// The first message a page receives: the scene, the channels and their signals (name, unit, symbol, range,
// description — what is known), the scene's limits (report.json "limits") each placed on the signal it bounds,
// and the names of the status bits.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/log/signal_channel.hpp"

namespace gyrostab::tools::view {

// [{"key", "value", "channel", "signal" (or null), "label", "placed_by": "table" | ""}] for the limits that are
// finite positive numbers: on every signal of `channel` whose table declares the key; else unplaced (signal
// null).
nlohmann::json placed_limits(const nlohmann::json& limits, const ChannelInfo& channel);

// [{"bit", "mask", "name", "kind": "cause" | "state"}] of msg::FaultBit (the actuator frame's status word).
nlohmann::json status_bit_names();
// [{"bit", "mask", "name"}] of msg::SensorStatusBit (the sensor frame's status word).
nlohmann::json sensor_status_bit_names();

// What the meta message says of one channel.
struct ChannelMeta {
  const ChannelInfo* info;
  std::string status;  // "fault": its rows carry the controller's status word; "sensor": a sensor frame's; ""
  std::int64_t buckets;
  std::int64_t span_ticks;
};

// {"type": "meta", "source", "scene": {...}, "channels": [{"topic", "title", "signals", "status", "buckets",
//  "span_ticks", "span_s"}], "limits", "status_bits", "sensor_status_bits", "has_status", "tick_s"}
nlohmann::json meta_message(const std::string& source, const nlohmann::json& scene,
                            const std::vector<ChannelMeta>& channels, const nlohmann::json& limits, double tick_s);

nlohmann::json signal_json(const SignalInfo& s);

}  // namespace gyrostab::tools::view
