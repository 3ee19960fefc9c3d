// The first message a page receives: the scene, the channels and their signals (name, unit, symbol, range,
// description — what is known), the scene's limits (report.json "limits") each placed on the signal it bounds,
// and the names of the controller's status bits.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/log/signal_channel.hpp"

namespace gyrostab::tools::view {

// The signal a limit bounds, or "" when none is clear. Until the signal tables declare it, by name: the limit's
// key less its "limit"/"stop"/"soft" words must be a column's name ("precession_stop_rad" -> "precession_rad",
// "precession_torque_limit_Nm" -> "precession_torque_Nm"), else the one column that starts with the key's
// first word and ends in the same unit ("motor_torque_limit_Nm" -> "motor_torque_x_Nm" if it is the only one).
std::string limit_signal(const std::string& key, const std::vector<std::string>& columns);

// [{"key", "value", "signal" (or null), "label"}] for the limits that are finite positive numbers.
nlohmann::json placed_limits(const nlohmann::json& limits, const std::vector<std::string>& columns);

// [{"bit", "mask", "name", "kind": "cause" | "state"}] of msg::FaultBit.
nlohmann::json status_bit_names();

// {"type": "meta", "scene": {...}, "channels": [{"topic", "signals": [...]}], "limits", "status_bits",
//  "buckets", "has_status"}
nlohmann::json meta_message(const nlohmann::json& scene, const ChannelInfo& signals, const nlohmann::json& limits,
                            std::int64_t buckets, bool has_status);

nlohmann::json signal_json(const SignalInfo& s);

}  // namespace gyrostab::tools::view
