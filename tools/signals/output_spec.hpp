// What a device records and reports, as its signal table declares it (docs/signals.md): the generated
// gyrostab_signals/<device>_outputs.hpp has a Record struct (one CSV row) and these specs, from which the CSV
// header, the ICD's tables and the figure documentation come.
#pragma once

#include <span>
#include <string_view>

namespace gyrostab::tools {

struct ColumnSpec {
  std::string_view name;    // the CSV header and the Record field
  std::string_view symbol;  // the book's symbol
  std::string_view unit;
  std::string_view when;    // "": always recorded; else the scene option that makes it exist
  std::string_view limits;  // report.json "limits" keys drawn with it, comma-separated
  std::string_view description;
};

struct FigureSpec {
  std::string_view name;  // report.json "figures" key
  std::string_view unit;
  std::string_view description;
};

struct DeviceOutputs {
  std::span<const ColumnSpec> columns;
  std::span<const FigureSpec> figures;
};

}  // namespace gyrostab::tools
