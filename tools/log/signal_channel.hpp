// A channel of a run, as the MCAP export and the live view see it: a name, a list of signals (name, and where
// known unit, symbol, range and description) and rows of doubles stamped with a tick. The recorded signals
// (signals.csv's columns) are one such channel today; each device's sensor and actuator frames become more once
// their signals are declared in the device's signal table — an adapter that fills ChannelInfo from the table
// and ChannelRows from the frames is all either consumer needs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace gyrostab::tools {

struct SignalInfo {
  std::string name;
  std::optional<std::string> unit;         // "rad", "N m", ...; absent when not known
  std::optional<std::string> symbol;       // the book's symbol, e.g. "β"
  std::optional<std::string> description;
  std::optional<double> min, max;          // the signal's declared range
};

struct ChannelInfo {
  std::string topic;  // e.g. "/gyrostab/signals"
  std::string title;  // the schema's name
  std::vector<SignalInfo> signals;
};

// The rows of one channel; row r holds signals.size() values.
class ChannelRows {
 public:
  virtual ~ChannelRows() = default;
  virtual std::size_t rows() const = 0;
  virtual std::int64_t tick(std::size_t row) const = 0;
  virtual double value(std::size_t row, std::size_t signal) const = 0;
};

// The unit a column's name ends in (`roll_rate_rad_s` -> "rad/s"), or nothing when its suffix is not one of
// the few unambiguous ones. Stands in for the signal tables' units until they exist.
std::optional<std::string> unit_from_column_name(const std::string& name);
// SignalInfo of the recorder's columns ("t_s" first), units from the names.
std::vector<SignalInfo> signals_of_columns(const std::vector<std::string>& columns);

// The JSON Schema (draft 2020-12) of the channel's messages: an object with an integer "tick" and one number
// per signal (null for a value that is not finite: JSON has no NaN or infinity), with title, unit and range
// in each property's description.
std::string json_schema(const ChannelInfo& channel);
// Appends {"tick":N,"name":value,...} with each double in its shortest form that reads back to the same bits.
void append_json_row(std::string& out, const ChannelInfo& channel, std::int64_t tick, const double* values);
// One double as JSON: shortest round-trip digits, `null` when not finite.
void append_json_number(std::string& out, double v);

}  // namespace gyrostab::tools
