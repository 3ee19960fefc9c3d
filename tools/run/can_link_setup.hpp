// Opening the CAN link of a plant or controller process (`gyrostab plant|controller SCENE --can-if IF`,
// `gyrostab run SCENE --transport can`; docs/can.md):
//   1. the device's bus: the CAN map generated from its signal table (tools/signals/device_can_map.hpp), every
//      frame of it;
//   2. the bus-load check: one sensor set and one command set per controller tick, worst-case bit stuffing, at
//      the configured bit rates (default 1 Mbit/s arbitration, 5 Mbit/s data); above 70 % the scene is refused
//      (exit 2) with the numbers, before anything is sent;
//   3. the SocketCAN socket on IF (CAN FD, kernel filter on the ids this side receives unless --can-no-filter,
//      error frames, kernel timestamps);
//   4. with --can-log FILE, the candump log, headed by comment lines that name the scene, its device, seed,
//      tick, the map (its table and fingerprint) and the bus's nodes, and carry the scene text (base64) so that
//      `gyrostab replay FILE` needs nothing else.
// Start-up only (allocates); the loop then runs through hil::FrameEndpoint<can::CanBusTransport>
// (hil/can/can_endpoint.hpp).
#pragma once

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/can/bus_load.hpp"
#include "hil/can/bus_nodes.hpp"
#include "hil/can/can_endpoint.hpp"
#include "hil/can/frame_map.hpp"
#include "tools/devices/registry.hpp"
#include "tools/run/run_output.hpp"
#include "tools/signals/device_can_map.hpp"

namespace gyrostab::tools {

// The frames a device's bus carries: its map, whole; no bus (map nullptr) for a name no table declares.
inline can::DeviceBus can_bus_of(std::string_view device) { return can::DeviceBus{find_device_can_map(device)}; }

// The "can-map" header line of a candump log: the table the map was generated from and its fingerprint.
inline std::string can_map_text(const can::CanMap& m) {
  char fp[24];
  std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(m.fingerprint));
  return std::string(m.device) + " " + fp;
}

inline std::string base64(const std::string& in) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8) |
                       static_cast<unsigned char>(in[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < in.size()) {
    unsigned v = static_cast<unsigned char>(in[i]) << 16;
    if (i + 1 < in.size()) v |= static_cast<unsigned char>(in[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < in.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// The bus load of a scene's device at its tick rate; "" if acceptable, else the refusal message.
inline std::string can_bus_load_problem(const LoopConfig& loop, const TransportOptions& t, can::BusLoad& load) {
  const can::DeviceBus bus = can_bus_of(loop.device);
  if (bus.map == nullptr) return "device " + loop.device + " has no signal table, so no CAN map";
  const can::BusTiming timing{t.can_bitrate, t.can_data_bitrate};
  const double rate_hz = 1e9 / static_cast<double>(loop.tick_ns);
  load = can::bus_load(bus, rate_hz, timing);
  if (load.acceptable()) return "";
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "bus load %.1f %% exceeds the %.0f %% limit: %d CAN FD frames per tick (nodes %s) at %.0f Hz on a "
                "%.0f/%.0f Mbit/s bus need %.1f us of every %.1f us tick (worst-case bit stuffing). Lower the tick "
                "rate, or raise --can-data-bitrate if the transceivers allow it (docs/can.md)",
                100.0 * load.load, 100.0 * can::kMaxBusLoad, load.frames_per_tick, can::bus_node_list(bus).c_str(), rate_hz,
                timing.nominal_bitrate * 1e-6, timing.data_bitrate * 1e-6, load.busy_s_per_tick * 1e6,
                1e6 / rate_hz);
  return buf;
}

// Opens bus, socket and log for one side. 0, or the exit code after printing why (2: refused scene or bad
// option, 3: the interface or the log cannot be opened).
inline int open_can_link(can::CanBusTransport& bus, const LoopConfig& loop, const RunRequest& req, bool plant_side,
                         nlohmann::json& info) {
  const TransportOptions& t = req.transport;
  const char* who = plant_side ? "gyrostab plant" : "gyrostab controller";
  if (!(t.can_bitrate > 0.0) || !(t.can_data_bitrate >= t.can_bitrate)) {
    std::fprintf(stderr, "%s: --can-bitrate must be > 0 and --can-data-bitrate at least as high\n", who);
    return 2;
  }
  if (const std::string bad = can_bus_load_problem(loop, t, bus.load); !bad.empty()) {
    std::fprintf(stderr, "%s: %s: CAN refused: %s\n", who, loop.name.c_str(), bad.c_str());
    return 2;
  }
  bus.ifname = t.can_if;
  bus.bus = can_bus_of(loop.device);
  bus.tick_ns = loop.tick_ns;
  bus.real_time = t.real_time;
  bus.timing = can::BusTiming{t.can_bitrate, t.can_data_bitrate};
  // This side receives the other direction's messages.
  const can::Direction rx = plant_side ? can::Direction::kActuator : can::Direction::kSensor;
  can::SocketCanConfig config;
  config.ifname = t.can_if;
  std::vector<std::uint32_t> ids;
  for (const can::MessageSpec& m : bus.bus.messages())
    if (m.direction == rx) ids.push_back(m.id);
  if (t.can_filter) config.receive_ids = ids;
  std::string error;
  if (!bus.socket.open(config, error)) {
    std::fprintf(stderr, "%s: %s\n", who, error.c_str());
    return 3;
  }
  if (!t.can_log.empty()) {
    std::string text = req.scene_text;
    if (text.empty()) {
      std::ifstream f(req.scene_path, std::ios::binary);
      std::ostringstream s;
      s << f.rdbuf();
      text = s.str();
    }
    std::vector<std::string> header = {
        "gyrostab-candump 2",
        std::string("role ") + (plant_side ? "plant" : "controller"),
        "scene " + loop.name,
        "device " + loop.device,
        "seed " + std::to_string(loop.seed),
        "tick_ns " + std::to_string(loop.tick_ns),
        "can-map " + can_map_text(*bus.bus.map),
        "nodes " + can::bus_node_list(bus.bus),
        std::string("clock ") + (t.real_time ? "realtime" : "simulated"),
    };
    const std::string b64 = base64(text);
    for (std::size_t i = 0; i < b64.size(); i += 76) header.push_back("scene-toml-base64 " + b64.substr(i, 76));
    if (!bus.log.open(t.can_log, t.can_if, header, error)) {
      std::fprintf(stderr, "%s: %s\n", who, error.c_str());
      return 3;
    }
    bus.logging = true;
  }
  nlohmann::json receives = nlohmann::json::array();
  for (std::uint32_t id : ids) receives.push_back(id);
  info = {{"transport", "can"},
          {"interface", t.can_if},
          {"receives_ids", receives},
          {"kernel_filter", t.can_filter},
          {"timeout_ms", t.timeout_ms},
          {"start_timeout_ms", t.start_timeout_ms}};
  if (bus.logging) info["candump_log"] = t.can_log;
  return 0;
}

}  // namespace gyrostab::tools
