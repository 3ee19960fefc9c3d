// A device's signals by its [scene] device name: the table found among every table of the build
// (gyrostab_signals/all_devices.hpp, generated from tools/devices/*/<device>_signals.toml); nullptr for a name
// no table declares (every registered device has one: tests/unit/contract_test.cpp).
#pragma once

#include <string_view>

#include "gyrostab_signals/all_devices.hpp"

namespace gyrostab::tools {

inline const msg::DeviceSignals* find_device_signals(std::string_view device) {
  for (const msg::DeviceSignals* d : msg::kAllDeviceSignals)
    if (d->device == device) return d;
  return nullptr;
}

}  // namespace gyrostab::tools
