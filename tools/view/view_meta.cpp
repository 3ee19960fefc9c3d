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

std::string limit_label(const std::string& key) {
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

nlohmann::json placed_limits(const nlohmann::json& limits, const ChannelInfo& channel) {
  nlohmann::json out = nlohmann::json::array();
  if (!limits.is_object()) return out;
  for (const auto& item : limits.items()) {
    // Named copies, not structured bindings: a lambda below uses the key (clang does not capture bindings).
    const std::string key = item.key();
    const nlohmann::json& value = item.value();
    if (!value.is_number()) continue;
    const double v = value.get<double>();
    if (!std::isfinite(v) || v <= 0) continue;
    auto entry = [&](const nlohmann::json& signal, const char* by) {
      out.push_back({{"key", key}, {"value", v}, {"channel", channel.topic}, {"signal", signal},
                     {"label", limit_label(key)}, {"placed_by", by}});
    };
    bool placed = false;
    for (const SignalInfo& s : channel.signals) {
      if (std::find(s.limits.begin(), s.limits.end(), key) == s.limits.end()) continue;
      entry(tools::label_of(s), "table");
      placed = true;
    }
    if (placed) continue;
    entry(nullptr, "");
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

nlohmann::json sensor_status_bit_names() {
  using msg::SensorStatusBit;
  struct Name {
    SensorStatusBit bit;
    const char* name;
  };
  static const Name kNames[] = {
      {SensorStatusBit::kRateGyroSaturated, "rate gyro saturated"},
      {SensorStatusBit::kEncoderError, "encoder error"},
      {SensorStatusBit::kDriveFault, "drive fault"},
      {SensorStatusBit::kRotorSpeedInvalid, "rotor speed invalid"},
  };
  nlohmann::json out = nlohmann::json::array();
  for (const Name& n : kNames) {
    const std::uint32_t mask = msg::bit(n.bit);
    int bit = 0;
    while ((1u << bit) != mask) ++bit;
    out.push_back({{"bit", bit}, {"mask", mask}, {"name", n.name}});
  }
  return out;
}

nlohmann::json signal_json(const SignalInfo& s) {
  auto opt = [](const auto& o) { return o ? nlohmann::json(*o) : nlohmann::json(nullptr); };
  return {{"name", s.name},
          {"label", tools::label_of(s)},
          {"unit", opt(s.unit)},
          {"symbol", opt(s.symbol)},
          {"description", opt(s.description)},
          {"min", opt(s.min)},
          {"max", opt(s.max)},
          {"count", s.count},
          {"element", s.element},
          {"integer", s.integer},
          {"declared", s.declared}};
}

nlohmann::json meta_message(const std::string& source, const nlohmann::json& scene,
                            const std::vector<ChannelMeta>& channels, const nlohmann::json& limits, double tick_s) {
  nlohmann::json ch = nlohmann::json::array();
  nlohmann::json placed = nlohmann::json::array();
  bool has_status = false;
  for (const ChannelMeta& c : channels) {
    nlohmann::json sig = nlohmann::json::array();
    for (const SignalInfo& s : c.info->signals) sig.push_back(signal_json(s));
    ch.push_back({{"topic", c.info->topic},
                  {"title", c.info->title},
                  {"signals", sig},
                  {"status", c.status},
                  {"buckets", c.buckets},
                  {"span_ticks", c.span_ticks},
                  {"span_s", static_cast<double>(c.span_ticks) * tick_s}});
    for (const auto& l : placed_limits(limits, *c.info)) {
      // A limit no signal of a channel takes is listed once, with the first channel.
      if (l["signal"].is_null() && &c != &channels.front()) continue;
      placed.push_back(l);
    }
    has_status = has_status || c.status == "fault";
  }
  return {{"type", "meta"},
          {"source", source},
          {"scene", scene},
          {"channels", ch},
          {"limits", placed},
          {"status_bits", status_bit_names()},
          {"sensor_status_bits", sensor_status_bit_names()},
          {"has_status", has_status},
          {"tick_s", tick_s}};
}

}  // namespace gyrostab::tools::view
