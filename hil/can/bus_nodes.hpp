// The nodes on a device's CAN bus (frame_map.hpp DeviceBus), for the DBC file's node list, the report and the
// log header: the two header nodes (sensor_hub, controller), then every other node that sends or receives a
// frame of the bus, in the order of its first frame (sensor frames first, so by identifier). Host side.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "hil/can/frame_map.hpp"

namespace gyrostab::can {

inline std::vector<std::string_view> bus_nodes(const DeviceBus& bus) {
  std::vector<std::string_view> nodes{"sensor_hub", "controller"};
  const auto add = [&](std::string_view n) {
    if (std::find(nodes.begin(), nodes.end(), n) == nodes.end()) nodes.push_back(n);
  };
  for (Direction d : {Direction::kSensor, Direction::kActuator}) {
    for (std::size_t i = 0; i < bus.messages().size(); ++i) {
      const MessageSpec& m = bus.messages()[i];
      if (m.direction == d) add(m.node);
    }
  }
  return nodes;
}

inline std::string bus_node_list(const DeviceBus& bus) {
  std::string s;
  for (std::string_view n : bus_nodes(bus)) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

// The nodes that act on the controller's commands (every command frame's node but the controller's).
inline std::vector<std::string_view> command_receivers(const DeviceBus& bus) {
  std::vector<std::string_view> out;
  for (std::size_t i = 0; i < bus.messages().size(); ++i) {
    const MessageSpec& m = bus.messages()[i];
    if (m.direction == Direction::kActuator && m.node != "controller" &&
        std::find(out.begin(), out.end(), m.node) == out.end())
      out.push_back(m.node);
  }
  return out;
}

}  // namespace gyrostab::can
