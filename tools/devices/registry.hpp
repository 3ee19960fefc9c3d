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

// The signals of the scene's device: its frames' layout on every transport (every registered device has a
// signal table: tests/unit/contract_test.cpp).
const msg::DeviceSignals& signals_of(const DeviceScene& scene);

}  // namespace gyrostab::tools
