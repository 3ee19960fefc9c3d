// The devices gyrostab knows, in one list (tools/devices/registry.cpp): `run`, `check`, `replay`, the CAN
// link, the accuracy study and docs/scenes.md find a device here by its [scene] device name.
#pragma once

#include <span>
#include <string_view>

#include "firmware/msg/signal_spec.hpp"
#include "tools/devices/device.hpp"

namespace gyrostab::tools {

std::span<const DeviceDescriptor* const> devices();

// nullptr if no device has that name.
const DeviceDescriptor* find_device(std::string_view name);

// The device's CAN nodes; every node for a name no device has.
can::NodeSet can_nodes_of(std::string_view device);

// The signals of the scene's device: its frames' layout on every transport.
const msg::DeviceSignals& signals_of(const DeviceScene& scene);

}  // namespace gyrostab::tools
