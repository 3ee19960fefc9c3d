// Test helper for mcap_frames_test.py: a candump log of the CAN bus made from a bus log (`run --log`) with the
// project's own CAN codec, as `--can-log` writes it on a lockstep CAN run — the header lines of
// tools/run/can_link_setup.hpp, every tick's sensor set then command set encoded by can::FrameEncoder on the
// device's map (header frame last, alive counters, CRC), stamped with the tick's simulated time, then the
// plant's end-of-run set and the controller's answer (hil/link/end_of_run.hpp). The link envelope (sender,
// session, freshness, MAC) stays zero: no key is involved. Lockstep CAN runs are bit-identical to in-process
// ones, so the frames are those a real CAN run of the scene puts on the bus.
//   candump_from_buslog BUS_LOG SCENE_FILE OUT.candump
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hil/can/bus_nodes.hpp"
#include "hil/can/candump_log.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/link/end_of_run.hpp"
#include "tools/log/bus_log_reader.hpp"
#include "tools/run/can_link_setup.hpp"

using namespace gyrostab;
namespace buslog = gyrostab::tools::buslog;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: candump_from_buslog BUS_LOG SCENE_FILE OUT.candump\n");
    return 2;
  }
  buslog::BusLogReader reader;
  if (reader.open(argv[1]) != buslog::ReadStatus::kOk) {
    std::fprintf(stderr, "candump_from_buslog: %s: %s\n", argv[1], reader.problem().c_str());
    return 1;
  }
  const buslog::SceneEvent& scene = reader.scene();
  const can::CanMap* map = tools::find_device_can_map(scene.device);
  if (map == nullptr) {
    std::fprintf(stderr, "candump_from_buslog: no CAN map for %s\n", scene.device.c_str());
    return 1;
  }
  const can::DeviceBus bus = can::whole_bus(*map);
  std::ifstream in(argv[2], std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::vector<std::string> header = {
      "gyrostab-candump 2",         "role plant",
      "scene " + scene.name,        "device " + scene.device,
      "seed " + std::to_string(scene.seed),
      "tick_ns " + std::to_string(scene.tick_ns),
      "can-map " + tools::can_map_text(*map),
      "nodes " + can::bus_node_list(bus), "clock simulated",
  };
  const std::string b64 = tools::base64(text.str());
  for (std::size_t i = 0; i < b64.size(); i += 76) header.push_back("scene-toml-base64 " + b64.substr(i, 76));
  can::CandumpWriter out;
  std::string error;
  if (!out.open(argv[3], "vcan0", header, error)) {
    std::fprintf(stderr, "candump_from_buslog: %s\n", error.c_str());
    return 1;
  }
  can::FrameEncoder sensors(bus, can::Direction::kSensor), commands(bus, can::Direction::kActuator);
  std::array<can::CanFrame, can::kMaxMessagesPerDirection> tx{};
  const auto put = [&](std::size_t n, std::int64_t tick) {
    for (std::size_t i = 0; i < n; ++i) out.write(tx[i], tick * scene.tick_ns);
    return n > 0;
  };
  buslog::TickRecord t;
  buslog::ReadStatus s;
  msg::AnyActuatorFrame last{};
  std::int64_t ticks = 0;
  while ((s = reader.next(t)) == buslog::ReadStatus::kOk) {
    if (!put(sensors.encode(t.sensor, tx), t.tick) || !put(commands.encode(t.actuator, tx), t.tick)) {
      std::fprintf(stderr, "candump_from_buslog: tick %lld has a value the bus cannot carry\n",
                   static_cast<long long>(t.tick));
      return 1;
    }
    last = t.actuator;
    ticks = t.tick + 1;
  }
  if (s != buslog::ReadStatus::kEnd) {
    std::fprintf(stderr, "candump_from_buslog: %s: %s\n", argv[1], reader.problem().c_str());
    return 1;
  }
  const msg::AnySensorFrame end = hil::end_of_run_frame(ticks, scene.tick_ns, false);
  put(sensors.encode(end, tx), ticks);
  put(commands.encode(hil::end_of_run_ack(end, last, 0, scene.tick_ns, reader.signals()), tx), ticks);
  if (!out.close(error)) {
    std::fprintf(stderr, "candump_from_buslog: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s: %lld ticks, %llu CAN frames\n", argv[3], static_cast<long long>(ticks),
              static_cast<unsigned long long>(out.frames_written()));
  return 0;
}
