#include "tools/view/view_meta.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "firmware/msg/fault_bits.hpp"

namespace gyrostab::tools::view {

namespace {

std::vector<std::string> words(const std::string& key) {
  std::vector<std::string> w;
  std::stringstream ss(key);
  std::string part;
  while (std::getline(ss, part, '_')) w.push_back(part);
  return w;
}

std::string label_of(const std::string& key) {
  if (key.find("soft") != std::string::npos) return "soft limit";
  if (key.find("stop") != std::string::npos) return "end stop";
  std::string l;
  for (const std::string& w : words(key)) {
    if (w == "limit") break;
    l += (l.empty() ? "" : " ") + w;
  }
  return l + " limit";
}

}  // namespace

std::string limit_signal(const std::string& key, const std::vector<std::string>& columns) {
  const std::vector<std::string> w = words(key);
  std::string stripped;
  for (const std::string& x : w) {
    if (x == "limit" || x == "stop" || x == "soft") continue;
    stripped += (stripped.empty() ? "" : "_") + x;
  }
  if (std::find(columns.begin(), columns.end(), stripped) != columns.end()) return stripped;
  const auto unit = unit_from_column_name(key);
  if (!unit || w.empty()) return "";
  std::string found;
  for (const std::string& c : columns) {
    if (c.rfind(w.front() + "_", 0) == 0 && unit_from_column_name(c) == unit) {
      if (!found.empty()) return "";  // two candidates: not clear
      found = c;
    }
  }
  return found;
}

nlohmann::json placed_limits(const nlohmann::json& limits, const std::vector<std::string>& columns) {
  nlohmann::json out = nlohmann::json::array();
  if (!limits.is_object()) return out;
  for (const auto& [key, value] : limits.items()) {
    if (!value.is_number()) continue;
    const double v = value.get<double>();
    if (!std::isfinite(v) || v <= 0) continue;
    const std::string s = limit_signal(key, columns);
    out.push_back({{"key", key},
                   {"value", v},
                   {"signal", s.empty() ? nlohmann::json(nullptr) : nlohmann::json(s)},
                   {"label", label_of(key)}});
  }
  return out;
}

nlohmann::json status_bit_names() {
  using msg::FaultBit;
  struct Name {
    FaultBit bit;
    const char* name;
    const char* kind;
  };
  static const Name kNames[] = {
      {FaultBit::kSensorMissing, "sensor frame missing", "cause"},
      {FaultBit::kSensorStale, "sensor frame stale", "cause"},
      {FaultBit::kSensorNonFinite, "sensor value not finite", "cause"},
      {FaultBit::kSensorOutOfRange, "sensor value out of range", "cause"},
      {FaultBit::kSensorReportedFault, "sensor reported a fault", "cause"},
      {FaultBit::kHoldingLastGood, "holding the last good frame", "state"},
      {FaultBit::kSafeState, "safe state", "state"},
      {FaultBit::kAwaitingFirstFrame, "awaiting the first frame", "state"},
  };
  nlohmann::json out = nlohmann::json::array();
  for (const Name& n : kNames) {
    const std::uint32_t mask = msg::bit(n.bit);
    int bit = 0;
    while ((1u << bit) != mask) ++bit;
    out.push_back({{"bit", bit}, {"mask", mask}, {"name", n.name}, {"kind", n.kind}});
  }
  return out;
}

nlohmann::json signal_json(const SignalInfo& s) {
  auto opt = [](const auto& o) { return o ? nlohmann::json(*o) : nlohmann::json(nullptr); };
  return {{"name", s.name},     {"unit", opt(s.unit)}, {"symbol", opt(s.symbol)},
          {"description", opt(s.description)}, {"min", opt(s.min)},   {"max", opt(s.max)}};
}

nlohmann::json meta_message(const nlohmann::json& scene, const ChannelInfo& signals, const nlohmann::json& limits,
                            std::int64_t buckets, bool has_status) {
  std::vector<std::string> columns;
  nlohmann::json sig = nlohmann::json::array();
  for (const SignalInfo& s : signals.signals) {
    columns.push_back(s.name);
    sig.push_back(signal_json(s));
  }
  return {{"type", "meta"},
          {"scene", scene},
          {"channels", nlohmann::json::array({{{"topic", signals.topic}, {"signals", sig}}})},
          {"limits", placed_limits(limits, columns)},
          {"status_bits", status_bit_names()},
          {"buckets", buckets},
          {"has_status", has_status}};
}

}  // namespace gyrostab::tools::view
