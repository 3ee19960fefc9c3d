#include "tools/log/signal_channel.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

namespace gyrostab::tools {

std::string label_of(const SignalInfo& s) {
  return s.count > 1 ? s.name + "[" + std::to_string(s.element) + "]" : s.name;
}

namespace {

std::vector<std::string> split_keys(std::string_view list) {
  std::vector<std::string> out;
  std::stringstream ss{std::string(list)};
  for (std::string k; std::getline(ss, k, ',');) {
    const auto a = k.find_first_not_of(' ');
    const auto b = k.find_last_not_of(' ');
    if (a != std::string::npos) out.push_back(k.substr(a, b - a + 1));
  }
  return out;
}

const ColumnSpec* find_column(const DeviceOutputs* outputs, const std::string& name) {
  if (outputs == nullptr) return nullptr;
  for (const ColumnSpec& c : outputs->columns)
    if (c.name == name) return &c;
  return nullptr;
}

}  // namespace

std::vector<SignalInfo> signals_of_columns(const std::vector<std::string>& columns, const DeviceOutputs* outputs) {
  std::vector<SignalInfo> out;
  out.reserve(columns.size());
  for (const std::string& c : columns) {
    SignalInfo s;
    s.name = c;
    if (c == "t_s") {
      s.unit = "s";
      s.symbol = "t";
      s.description = "simulated time";
      s.declared = true;  // every run's time column, the same for every device
    } else if (const ColumnSpec* spec = find_column(outputs, c)) {
      s.unit = std::string(spec->unit);
      if (!spec->symbol.empty()) s.symbol = std::string(spec->symbol);
      if (!spec->description.empty()) s.description = std::string(spec->description);
      s.limits = split_keys(spec->limits);
      s.declared = true;
    }
    out.push_back(std::move(s));
  }
  return out;
}

namespace {

std::string describe(const SignalInfo& s) {
  std::string d;
  if (s.symbol) d += *s.symbol + ": ";
  d += s.description.value_or(s.name);
  if (s.unit) d += " [" + *s.unit + "]";
  return d;
}

}  // namespace

std::string json_schema(const ChannelInfo& channel) {
  nlohmann::ordered_json props = nlohmann::ordered_json::object();
  props["tick"] = {{"type", "integer"}, {"description", "loop tick"}};
  for (std::size_t i = 0; i < channel.signals.size(); ++i) {
    const SignalInfo& s = channel.signals[i];
    if (s.element != 0) continue;  // an array's later elements are in its one field
    nlohmann::ordered_json item{{"type", s.integer ? nlohmann::ordered_json("integer")
                                                    : nlohmann::ordered_json({"number", "null"})}};
    if (s.min) item["minimum"] = *s.min;
    if (s.max) item["maximum"] = *s.max;
    nlohmann::ordered_json p;
    if (s.count > 1) {
      p = {{"type", "array"}, {"items", item}, {"minItems", s.count}, {"maxItems", s.count}};
    } else {
      p = item;
    }
    p["description"] = describe(s);
    if (s.unit) p["unit"] = *s.unit;  // an annotation keyword: validators ignore it, readers may show it
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

namespace {

void append_value(std::string& out, const SignalInfo& s, double v) {
  if (s.integer && std::isfinite(v)) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<long long>(v));
    out.append(buf, r.ptr);
    return;
  }
  append_json_number(out, v);
}

}  // namespace

void append_json_row(std::string& out, const ChannelInfo& channel, std::int64_t tick, const double* values) {
  out += "{\"tick\":";
  out += std::to_string(tick);
  const std::size_t n = channel.signals.size();
  for (std::size_t i = 0; i < n; ++i) {
    const SignalInfo& s = channel.signals[i];
    if (s.element == 0) {
      out += ",\"";
      out += s.name;  // table and column names are identifiers: no character needs escaping
      out += "\":";
      if (s.count > 1) out += '[';
    } else {
      out += ',';
    }
    append_value(out, s, values[i]);
    if (s.count > 1 && s.element + 1 == s.count) out += ']';
  }
  out += '}';
}

}  // namespace gyrostab::tools
