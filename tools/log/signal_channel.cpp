#include "tools/log/signal_channel.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>

namespace gyrostab::tools {

std::optional<std::string> unit_from_column_name(const std::string& name) {
  // Longest suffix first: "_rad_s" before "_s".
  static const std::pair<const char*, const char*> kSuffixes[] = {
      {"_rad_s2", "rad/s²"}, {"_rad_s", "rad/s"}, {"_deg_s", "°/s"}, {"_m_s2", "m/s²"}, {"_m_s", "m/s"},
      {"_Nms", "N m s"},     {"_Nm", "N m"},      {"_rad", "rad"},   {"_deg", "°"},     {"_m", "m"},
      {"_s", "s"},           {"_V", "V"},         {"_A", "A"},       {"_W", "W"},       {"_kg", "kg"},
      {"_Hz", "Hz"},
  };
  for (const auto& [suffix, unit] : kSuffixes) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) return std::string(unit);
  }
  return std::nullopt;
}

std::vector<SignalInfo> signals_of_columns(const std::vector<std::string>& columns) {
  std::vector<SignalInfo> out;
  out.reserve(columns.size());
  for (const std::string& c : columns) {
    SignalInfo s;
    s.name = c;
    s.unit = unit_from_column_name(c);
    if (c == "t_s") s.description = "simulated time";
    out.push_back(std::move(s));
  }
  return out;
}

std::string json_schema(const ChannelInfo& channel) {
  nlohmann::ordered_json props = nlohmann::ordered_json::object();
  props["tick"] = {{"type", "integer"}, {"description", "loop tick"}};
  for (const SignalInfo& s : channel.signals) {
    std::string d = s.description.value_or(s.name);
    if (s.unit) d += " [" + *s.unit + "]";
    nlohmann::ordered_json p{{"type", {"number", "null"}}, {"description", d}};
    if (s.min) p["minimum"] = *s.min;
    if (s.max) p["maximum"] = *s.max;
    props[s.name] = std::move(p);
  }
  nlohmann::ordered_json schema{{"$schema", "https://json-schema.org/draft/2020-12/schema"},
                                {"title", channel.title},
                                {"type", "object"},
                                {"properties", std::move(props)}};
  return schema.dump();
}

void append_json_number(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  out.append(buf, r.ptr);
}

void append_json_row(std::string& out, const ChannelInfo& channel, std::int64_t tick, const double* values) {
  out += "{\"tick\":";
  out += std::to_string(tick);
  for (std::size_t i = 0; i < channel.signals.size(); ++i) {
    out += ",\"";
    out += channel.signals[i].name;  // column names are identifiers: no character needs escaping
    out += "\":";
    append_json_number(out, values[i]);
  }
  out += '}';
}

}  // namespace gyrostab::tools
