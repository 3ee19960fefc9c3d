// A device's CAN FD map by its [scene] device name: the map generated from its own signal table
// (gyrostab_signals/all_can_maps.hpp), or — a device with no table of its own yet — the shared legacy table's
// (firmware/msg/legacy_signals.toml), the same rule as find_device_signals (device_signals.hpp). Which of the
// legacy map's frames a device's bus carries: tools/run/can_link_setup.hpp can_bus_of.
#pragma once

#include <string_view>

#include "gyrostab_signals/all_can_maps.hpp"

namespace gyrostab::tools {

inline const can::CanMap& find_device_can_map(std::string_view device) {
  if (const can::CanMap* m = can::find_can_map(device)) return *m;
  return can::legacy::kCanMap;
}

}  // namespace gyrostab::tools
