// A device's recorded columns and report figures by its [scene] device name, as its signal table declares them
// (gyrostab_signals/all_outputs.hpp, generated from every table of the build). nullptr for a name no table
// declares, or a table that declares no columns.
#pragma once

#include <string_view>

#include "gyrostab_signals/all_outputs.hpp"
#include "tools/signals/output_spec.hpp"

namespace gyrostab::tools {

inline const DeviceOutputs* find_device_outputs(std::string_view device) {
  for (const NamedDeviceOutputs& d : kAllDeviceOutputs)
    if (d.device == device) return d.outputs->columns.empty() ? nullptr : d.outputs;
  return nullptr;
}

}  // namespace gyrostab::tools
