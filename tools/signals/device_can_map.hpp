// A device's CAN FD map by its [scene] device name: the map generated from its own signal table
// (gyrostab_signals/all_can_maps.hpp); nullptr for a name no table declares (every registered device has one:
// tests/unit/contract_test.cpp).
#pragma once

#include <string_view>

#include "gyrostab_signals/all_can_maps.hpp"

namespace gyrostab::tools {

inline const can::CanMap* find_device_can_map(std::string_view device) { return can::find_can_map(device); }

}  // namespace gyrostab::tools
