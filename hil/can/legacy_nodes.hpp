// Transitional, deleted with the shared legacy signal table (firmware/msg/legacy_signals.toml): which of the
// legacy table's nodes a device's hardware has (DeviceDescriptor::can_nodes, tools/devices/). A device still on
// the legacy table carries only those nodes' frames (frame_map.hpp device_bus), so its bus load is what its
// hardware needs; a device with a table of its own carries exactly its table's frames and needs none of this.
#pragma once

#include <cstdint>
#include <string_view>

namespace gyrostab::can {

// Node presence bits (NodeSet). The sensor hub and the controller are always on the bus.
enum NodeBit : std::uint8_t {
  kNodeImu = 1u << 0,
  kNodeDrive1 = 1u << 1,
  kNodeDrive2 = 1u << 2,
  kNodeCluster = 1u << 3,
};
using NodeSet = std::uint8_t;
inline constexpr NodeSet kAllNodes = kNodeImu | kNodeDrive1 | kNodeDrive2 | kNodeCluster;

// The bit of a node; 0 for the sensor hub, the controller and a name the legacy table does not use.
constexpr NodeSet node_bit(std::string_view node) {
  if (node == "imu") return kNodeImu;
  if (node == "drive1") return kNodeDrive1;
  if (node == "drive2") return kNodeDrive2;
  if (node == "cluster") return kNodeCluster;
  return 0;
}

// A frame of this node is on the bus of a device with these nodes.
constexpr bool node_present(std::string_view node, NodeSet nodes) {
  const NodeSet bit = node_bit(node);
  return bit == 0 || (nodes & bit) != 0;
}

}  // namespace gyrostab::can
