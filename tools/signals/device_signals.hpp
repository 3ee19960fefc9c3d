// A device's signals by its [scene] device name: the table found among every table of the build
// (gyrostab_signals/all_devices.hpp, generated from tools/devices/*/<device>_signals.toml). A device that has no
// table of its own yet carries the shared legacy frame (firmware/msg/legacy_signals.toml).
#pragma once

#include <string_view>

#include "firmware/msg/sensor_frame.hpp"
#include "gyrostab_signals/all_devices.hpp"

namespace gyrostab::tools {

inline const msg::DeviceSignals& find_device_signals(std::string_view device) {
  for (const msg::DeviceSignals* d : msg::kAllDeviceSignals)
    if (d->device == device) return *d;
  return msg::kSignals;
}

}  // namespace gyrostab::tools
