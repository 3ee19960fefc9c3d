// A channel of a run, as the MCAP export and the live view see it: a name, a list of signals (name, and where
// known unit, symbol, range and description) and rows of doubles stamped with a tick. Two kinds exist:
//   - the recorded signals (signals.csv's columns): their names, units, symbols and limits come from the
//     device's signal table ([[column]], tools/signals/device_outputs.hpp);
//   - the frames of each direction (tools/log/frame_channel.hpp): the header fields and every signal of the
//     device's table (msg::SignalSpec), an array signal as one array field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tools/signals/output_spec.hpp"

namespace gyrostab::tools {

struct SignalInfo {
  std::string name;                        // the field's name; an array's elements share their base name
  std::optional<std::string> unit;         // "rad", "N m", ...; absent when not known
  std::optional<std::string> symbol;       // the book's symbol, e.g. "β"
  std::optional<std::string> description;
  std::optional<double> min, max;          // the signal's declared range (a command's: the drive's limit)
  std::uint8_t count{1};                   // elements of its array field (1: a scalar)
  std::uint8_t element{0};                 // this value's index in it
  bool integer{false};                     // an integer on the wire (a frame header's ticks, ns, counters, bits)
  bool declared{false};                    // described by a signal table (else only its name is known)
  std::vector<std::string> limits;         // report.json "limits" keys drawn with it, as its table declares
};

// "name", or "name[i]" for element i of an array field: how the view labels it and how Foxglove addresses it.
std::string label_of(const SignalInfo& s);

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

// SignalInfo of the recorder's columns ("t_s" first): from the table's [[column]]s where `outputs` declares the
// column, else only its name (declared = false).
std::vector<SignalInfo> signals_of_columns(const std::vector<std::string>& columns,
                                           const DeviceOutputs* outputs = nullptr);

// The JSON Schema (draft 2020-12) of the channel's messages: an object with an integer "tick" and one field per
// signal — a number (null for a value that is not finite: JSON has no NaN or infinity), an integer for a header
// field, an array of numbers for an array signal — with symbol, unit and range in each field's description.
std::string json_schema(const ChannelInfo& channel);
// Appends {"tick":N,"name":value,...} with each double in its shortest form that reads back to the same bits
// (an array signal's elements as one array).
void append_json_row(std::string& out, const ChannelInfo& channel, std::int64_t tick, const double* values);
// One double as JSON: shortest round-trip digits, `null` when not finite.
void append_json_number(std::string& out, double v);

}  // namespace gyrostab::tools
