#include "tools/log/candump_export.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/can/candump_log.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/link/end_of_run.hpp"
#include "tools/log/frame_channel.hpp"
#include "tools/run/can_link_setup.hpp"
#include "tools/run/can_replay.hpp"
#include "tools/run/run_mcap.hpp"

namespace gyrostab::tools {

namespace {

struct DumpLine {
  can::CanFrame frame;
  int line{0};
  std::int64_t offset{0};
};

// The log's comments and frame lines up to the first line that is not one (or a last line cut without its
// newline): `problem` and `problem_offset` say where it stopped ("" when the whole file was read).
struct DumpRead {
  can::CandumpFile header;  // comments only
  std::vector<DumpLine> frames;
  std::string problem;
  std::int64_t problem_offset{0};
  std::int64_t bytes{0};
};

bool read_dump(const std::string& path, DumpRead& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  out.bytes = static_cast<std::int64_t>(text.size());
  std::size_t at = 0;
  int number = 0;
  while (at < text.size()) {
    ++number;
    const std::size_t nl = text.find('\n', at);
    const std::string_view line(text.data() + at, (nl == std::string::npos ? text.size() : nl) - at);
    if (nl == std::string::npos && !line.empty() && line[0] == '(') {
      out.problem = "line " + std::to_string(number) + " is cut (the file ends inside it)";
      out.problem_offset = static_cast<std::int64_t>(at);
      return true;
    }
    DumpLine d;
    std::string_view ifname;
    switch (can::parse_candump_line(line, d.frame, ifname)) {
      case can::CandumpParse::kFrame:
        d.line = number;
        d.offset = static_cast<std::int64_t>(at);
        out.frames.push_back(d);
        break;
      case can::CandumpParse::kSkip:
        if (!line.empty() && line[0] == '#')
          out.header.comments.emplace_back(line.size() > 2 ? std::string(line.substr(2)) : std::string());
        break;
      case can::CandumpParse::kError:
        out.problem = "line " + std::to_string(number) + " is not a candump frame line: " +
                      std::string(line.substr(0, 120));
        out.problem_offset = static_cast<std::int64_t>(at);
        return true;
    }
    if (nl == std::string::npos) break;
    at = nl + 1;
  }
  return true;
}

int refuse(const std::string& path, const std::string& why) {
  std::fprintf(stderr, "gyrostab export: %s: %s, nothing written\n", path.c_str(), why.c_str());
  return kExportExitIncomplete;
}

}  // namespace

int export_candump_log(const ExportRequest& req) {
  DumpRead dump;
  if (!read_dump(req.log_path, dump)) {
    std::fprintf(stderr, "gyrostab export: cannot open %s\n", req.log_path.c_str());
    return 2;
  }
  const auto head = [&](const char* key) { return candump_header(dump.header, key); };
  const std::string device_name = head("device");
  if (device_name.empty()) {
    std::fprintf(stderr, "gyrostab export: %s is a candump log without gyrostab's header (no '# device' line), so "
                 "the CAN map that decodes its frames is unknown: export a log recorded with --can-log, nothing "
                 "written\n", req.log_path.c_str());
    return 2;
  }
  if (const std::string v = head("gyrostab-candump"); v != "2")
    return refuse(req.log_path, "a gyrostab candump log of version '" + v + "'; this build reads version 2 (the "
                                "CAN maps generated from the signal tables)");
  const can::CanMap* map = find_device_can_map(device_name);
  if (map == nullptr) return refuse(req.log_path, "device " + device_name + " has no signal table in this build, "
                                                  "so no CAN map");
  if (const std::string recorded = head("can-map"); recorded != can_map_text(*map))
    return refuse(req.log_path, "recorded with the CAN map '" + recorded + "', but device " + device_name +
                                "'s map in this build is '" + can_map_text(*map) +
                                "' (table and fingerprint): its frames would be decoded wrongly");
  std::int64_t tick_ns = 0;
  try {
    tick_ns = std::stoll(head("tick_ns"));
  } catch (...) {
  }
  if (tick_ns <= 0) return refuse(req.log_path, "no '# tick_ns' header line with the scene's tick");
  const msg::DeviceSignals& device = *map->signals;
  const can::DeviceBus bus = can::whole_bus(*map);

  RunMcapFile f(tick_ns);
  std::string error;
  if (!f.open(req.mcap_path, error)) {
    std::fprintf(stderr, "gyrostab export: %s\n", error.c_str());
    return 3;
  }
  const std::string toml = candump_scene_text(dump.header);
  const std::uint16_t scene_ch = f.add_json("/gyrostab/scene", "gyrostab.scene",
                                            "the candump log's header: the run's scene, its text byte for byte when "
                                            "the log carries it, the CAN map");
  nlohmann::json scene{{"name", head("scene")},      {"device", device_name},
                       {"tick_ns", tick_ns},         {"toml", toml},
                       {"role", head("role")},       {"can_map", head("can-map")},
                       {"nodes", head("nodes")},     {"clock", head("clock")},
                       {"log_version", "gyrostab-candump " + head("gyrostab-candump")},
                       {"signals", std::string(device.device)}};
  try {
    scene["seed"] = std::stoull(head("seed"));
  } catch (...) {
    scene["seed"] = nullptr;
  }
  bool ok = f.json(scene_ch, 0, scene);
  const ChannelInfo sensor_info = frame_channel(device, FrameDirection::kSensor);
  const ChannelInfo actuator_info = frame_channel(device, FrameDirection::kActuator);
  const std::uint16_t sensor_ch = f.add(sensor_info);
  const std::uint16_t actuator_ch = f.add(actuator_info);
  std::vector<double> sv(sensor_info.signals.size()), av(actuator_info.signals.size());

  // The live link's decoder, one per direction; a frame on a command identifier goes to the command side,
  // everything else (sensor frames, error frames, foreign identifiers) to the sensor side, which rejects what
  // is not its own, as the controller's receiver does.
  can::SetAssembler sensors(bus, can::Direction::kSensor);
  can::SetAssembler commands(bus, can::Direction::kActuator);
  msg::AnySensorFrame sensor{}, end{};
  msg::AnyActuatorFrame command{}, ack{};
  bool have_sensor = false, ended = false, acknowledged = false;
  std::int64_t last_sensor_tick = -1, last_tick = -1, pairs = 0, written = 0, sensor_sets = 0, command_sets = 0;
  // Ticks without both sets on the bus (a damaged or lost frame): counted, the first one's place kept.
  std::int64_t missing = 0, first_missing = -1, missing_offset = 0;
  const auto gap_before = [&](std::int64_t k, std::int64_t offset) {
    if (k <= last_tick + 1) return;
    if (missing == 0) {
      first_missing = last_tick + 1;
      missing_offset = offset;
    }
    missing += k - last_tick - 1;
  };
  for (const DumpLine& d : dump.frames) {
    const can::CanFrame& fr = d.frame;
    const int index = (fr.flags & (can::kFlagError | can::kFlagExtended)) ? -1 : bus.index_of(fr.id);
    const bool command_id =
        index >= 0 && bus.messages()[static_cast<std::size_t>(index)].direction == can::Direction::kActuator;
    if (!command_id) {
      if (sensors.accept(fr) != can::FrameError::kNone || !sensors.ready()) continue;
      sensors.take(sensor);
      ++sensor_sets;
      const auto k = static_cast<std::int64_t>(sensor.tick);
      if (k == last_sensor_tick) continue;
      last_sensor_tick = k;
      if (hil::is_end_of_run(sensor)) {
        end = sensor;
        ended = true;
        have_sensor = false;
      } else {
        have_sensor = true;
      }
      continue;
    }
    if (commands.accept(fr) != can::FrameError::kNone || !commands.ready()) continue;
    commands.take(command);
    ++command_sets;
    if (ended && command.tick == end.tick) {
      ack = command;
      acknowledged = true;
      continue;
    }
    if (!have_sensor || command.tick != sensor.tick) continue;
    have_sensor = false;
    const auto k = static_cast<std::int64_t>(command.tick);
    gap_before(k, d.offset);
    last_tick = k;
    ++pairs;
    if (k % req.every != 0) continue;
    frame_values(sensor, device, sv.data());
    frame_values(command, device, av.data());
    ok = ok && f.row(sensor_ch, sensor_info, k, sv.data()) && f.row(actuator_ch, actuator_info, k, av.data());
    ++written;
  }
  nlohmann::json rejected = nlohmann::json::object();
  for (const can::SetAssembler* a : {&sensors, &commands})
    for (std::size_t i = 1; i < can::kFrameErrorCount; ++i)
      if (const std::uint64_t n = a->counters().rejected[i]; n > 0) {
        const std::string name(can::frame_error_name(static_cast<can::FrameError>(i)));
        rejected[name] = rejected.value(name, std::uint64_t{0}) + n;
      }
  std::string problem = dump.problem;
  std::int64_t problem_offset = dump.problem_offset;
  if (ended) gap_before(static_cast<std::int64_t>(end.tick), dump.bytes);
  if (problem.empty() && missing > 0) {
    problem = std::to_string(missing) + " ticks have no complete sensor and command set on the bus (the first: tick " +
              std::to_string(first_missing) + "): frames rejected by the decoder: " + rejected.dump();
    problem_offset = missing_offset;
  }
  // The plant's own log may end before the controller's answer reached it (the plant stops listening when its
  // resends of the end frame time out): the end frame alone marks a whole run; the answer is reported.
  if (problem.empty() && !ended) {
    problem = "the log ends without the plant's end-of-run set (cut, or the run was stopped)";
    problem_offset = dump.bytes;
  }
  const bool complete = problem.empty();
  nlohmann::json log{{"file", req.log_path},
                     {"bytes", dump.bytes},
                     {"format", "candump"},
                     {"complete", complete},
                     {"frames", dump.frames.size()},
                     {"frames_rejected", rejected},
                     {"sensor_sets", sensor_sets},
                     {"command_sets", command_sets},
                     {"ticks_read", pairs},
                     {"ticks_missing", missing},
                     {"ticks_written", written},
                     {"every", req.every}};
  if (ended)
    log["end"] = {{"ticks", end.tick},
                  {"second_source", (end.status & msg::bit(msg::SensorStatusBit::kSecondSource)) != 0u},
                  {"acknowledged", acknowledged},
                  {"controller_status", acknowledged ? nlohmann::json(ack.status) : nlohmann::json(nullptr)}};
  else
    log["end"] = nullptr;
  if (!complete) {
    log["problem"] = problem;
    log["problem_offset"] = problem_offset;
  }
  if (!ok) {
    std::fprintf(stderr, "gyrostab export: cannot write %s: a write failed\n", req.mcap_path.c_str());
    return 3;
  }
  if (const int rc = finish_export(f, req, log, last_tick,
                                   "the candump log exported: complete or not, its end of the run, frames "
                                   "rejected by the decoder, or where it broke");
      rc != 0) {
    return rc;
  }
  std::printf("%s: wrote %s: %lld ticks of %s's frames from the CAN bus (%s)\n", req.log_path.c_str(),
              req.mcap_path.c_str(), static_cast<long long>(written), device_name.c_str(),
              complete ? "the log is complete" : "INCOMPLETE");
  if (!complete) {
    std::fprintf(stderr, "gyrostab export: %s: %s; the %lld whole ticks before it are in %s, whose /gyrostab/log "
                 "message says the log is incomplete\n", req.log_path.c_str(), problem.c_str(),
                 static_cast<long long>(pairs), req.mcap_path.c_str());
    return kExportExitIncomplete;
  }
  return 0;
}

}  // namespace gyrostab::tools
