#include "tools/log/bus_log_export.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "hil/can/candump_log.hpp"
#include "tools/log/bus_log_reader.hpp"
#include "tools/log/candump_export.hpp"
#include "tools/log/frame_channel.hpp"
#include "tools/run/run_mcap.hpp"

namespace gyrostab::tools {

namespace {

const char* reason_name(buslog::EndReason r) {
  switch (r) {
    case buslog::EndReason::kCompleted: return "completed";
    case buslog::EndReason::kDiverged: return "diverged";
    case buslog::EndReason::kSignal: return "signal";
    case buslog::EndReason::kOther: return "other";
  }
  return "?";
}

}  // namespace

int export_log(const ExportRequest& req) {
  if (req.every < 1) {
    std::fprintf(stderr, "gyrostab export: --every must be at least 1\n");
    return 2;
  }
  if (const std::string why = mcap_path_problem(req.mcap_path); !why.empty()) {
    std::fprintf(stderr, "gyrostab export: %s\n", why.c_str());
    return 2;
  }
  if (can::looks_like_candump_log(req.log_path)) return export_candump_log(req);
  buslog::BusLogReader reader;
  const buslog::ReadStatus opened = reader.open(req.log_path);
  if (opened != buslog::ReadStatus::kOk) {
    std::fprintf(stderr, "gyrostab export: %s: %s, nothing written: %s\n", req.log_path.c_str(),
                 buslog::describe(opened), reader.problem().c_str());
    return opened == buslog::ReadStatus::kUnreadable ? 2 : kExportExitIncomplete;
  }
  const buslog::SceneEvent& scene = reader.scene();
  const msg::DeviceSignals& device = reader.signals();
  RunMcapFile f(scene.tick_ns);
  std::string error;
  if (!f.open(req.mcap_path, error)) {
    std::fprintf(stderr, "gyrostab export: %s\n", error.c_str());
    return 3;
  }
  const std::uint16_t scene_ch =
      f.add_json("/gyrostab/scene", "gyrostab.scene", "the bus log's scene event: the run's scene, byte for byte");
  bool ok = f.json(scene_ch, 0,
                   {{"name", scene.name},
                    {"device", scene.device},
                    {"seed", scene.seed},
                    {"tick_ns", scene.tick_ns},
                    {"source", scene.source},
                    {"toml", scene.toml},
                    {"channel_suffix", reader.channel_suffix()},
                    {"log_version", scene.log_version},
                    {"signals", std::string(device.device)}});
  const ChannelInfo sensor = frame_channel(device, FrameDirection::kSensor);
  const ChannelInfo actuator = frame_channel(device, FrameDirection::kActuator);
  const std::uint16_t sensor_ch = f.add(sensor);
  const std::uint16_t actuator_ch = f.add(actuator);
  std::vector<double> sv(sensor.signals.size()), av(actuator.signals.size());
  buslog::TickRecord t;
  buslog::ReadStatus s;
  std::int64_t written = 0, last_tick = -1;
  while ((s = reader.next(t)) == buslog::ReadStatus::kOk) {
    last_tick = t.tick;
    if (t.tick % req.every != 0) continue;
    frame_values(t.sensor, device, sv.data());
    frame_values(t.actuator, device, av.data());
    ok = ok && f.row(sensor_ch, sensor, t.tick, sv.data()) && f.row(actuator_ch, actuator, t.tick, av.data());
    ++written;
  }
  const bool complete = s == buslog::ReadStatus::kEnd;
  nlohmann::json log{{"file", req.log_path},
                     {"bytes", reader.file_size()},
                     {"complete", complete},
                     {"ticks_read", reader.ticks_read()},
                     {"ticks_written", written},
                     {"every", req.every}};
  if (complete) {
    const buslog::EndEvent& e = reader.end_event();
    log["end"] = {{"ticks", e.ticks}, {"reason", reason_name(e.reason)}, {"signal", e.signal}, {"detail", e.detail}};
  } else {
    log["end"] = nullptr;
    log["problem"] = std::string(buslog::describe(s)) + ": " + reader.problem();
    log["problem_offset"] = reader.problem_offset();
  }
  if (!ok) {
    std::fprintf(stderr, "gyrostab export: cannot write %s: a write failed\n", req.mcap_path.c_str());
    return 3;
  }
  if (const int rc = finish_export(f, req, log, last_tick,
                                   "the bus log exported: complete or not, its end event, or where it broke");
      rc != 0) {
    return rc;
  }
  std::printf("%s: wrote %s: %lld ticks of %s's frames (%s)\n", req.log_path.c_str(), req.mcap_path.c_str(),
              static_cast<long long>(written), scene.device.c_str(), complete ? "the log is complete" : "INCOMPLETE");
  if (!complete) {
    std::fprintf(stderr, "gyrostab export: %s: %s: %s; the %lld whole ticks before it are in %s, whose /gyrostab/log "
                         "message says the log is incomplete\n",
                 req.log_path.c_str(), buslog::describe(s), reader.problem().c_str(),
                 static_cast<long long>(reader.ticks_read()), req.mcap_path.c_str());
    return kExportExitIncomplete;
  }
  return 0;
}

int finish_export(RunMcapFile& f, const ExportRequest& req, const nlohmann::json& log, std::int64_t last_tick,
                  const char* what) {
  const std::uint16_t log_ch = f.add_json("/gyrostab/log", "gyrostab.log", what);
  if (!f.json(log_ch, last_tick < 0 ? 0 : last_tick, log)) {
    std::fprintf(stderr, "gyrostab export: cannot write %s: a write failed\n", req.mcap_path.c_str());
    return 3;
  }
  std::string error;
  if (!f.commit(error)) {
    std::fprintf(stderr, "gyrostab export: %s\n", error.c_str());
    return 3;
  }
  return 0;
}

}  // namespace gyrostab::tools
