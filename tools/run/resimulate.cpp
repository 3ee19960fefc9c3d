// Open-loop re-simulation of the plant from a bus log (Role::kResimulate, `gyrostab replay LOG
// --resimulate`): the plant the scene builds runs the loop of closed_loop.hpp with the controller replaced
// by the recorded actuator frames — sense(k) → compare with the recorded sensor frame of tick k (memcmp of
// the whole SensorFrame) → the recorded actuator frame of tick k enters the latency pipe → actuate → advance.
// For a log of an in-process or lockstep run the re-simulated sensor frames are bit-identical; the first
// difference is reported with its tick and fields. A plant that diverges where the log ends with "diverged"
// reproduces the run. With write_outputs (--out DIR) the re-simulated run's report.json and signals.csv are
// written as by `gyrostab run`.
// Exit codes: replay_session.hpp (0 identical, 3 plant diverged, 4 mismatch, 5 truncated/corrupt log).
#include <array>
#include <cstdio>
#include <cstring>

#include "hil/can/candump_log.hpp"
#include "tools/devices/registry.hpp"
#include "tools/log/frame_diff.hpp"
#include "tools/loop/closed_loop.hpp"
#include "tools/run/replay_session.hpp"
#include "tools/run/run_modes.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

int resimulate_plant(const DeviceScene& scene, const RunRequest& req) {
  const LoopConfig& loop = scene.loop();
  if (can::looks_like_candump_log(req.transport.replay_log)) {  // candump logs are replayed, not re-simulated
    std::fprintf(stderr, "gyrostab: %s: --resimulate reads gyrostab bus logs (--log); a candump log replays into "
                 "the controller only (without --resimulate)\n", req.transport.replay_log.c_str());
    return 2;
  }
  ReplaySession session;
  int exit_code = 0;
  if (!session.open(loop, req, exit_code)) return exit_code;
  std::unique_ptr<PlantPort> device = scene.make_plant(PlantOptions{false, req.ticks});
  Recorder rec = scene_recorder(scene, loop.ticks());
  PlantTick plant(*device, loop, &rec);
  msg::AnySensorFrame sensed{};
  buslog::TickRecord t;
  LoopOutcome outcome;
  buslog::ReadStatus s;
  int rc = -1;
  while ((s = session.next(t)) == buslog::ReadStatus::kOk) {
    const std::int64_t k = t.tick;
    device->sense(k, sensed);
    if (std::memcmp(&sensed, &t.sensor, sizeof sensed) != 0) {
      std::fprintf(stderr,
                   "gyrostab: %s: MISMATCH at tick %lld (sensor event at byte %lld; the %lld ticks before it are "
                   "identical): %s\n",
                   session.log_path().c_str(), static_cast<long long>(k), static_cast<long long>(t.sensor_offset),
                   static_cast<long long>(outcome.ticks_run), buslog::frame_differences(t.sensor, sensed, signals_of(scene)).c_str());
      rc = kReplayExitMismatch;
      break;
    }
    if (!plant.step(k, t.actuator, outcome)) {
      s = session.next(t);
      const bool recorded = s == buslog::ReadStatus::kEnd &&
                            session.reader().end_event().reason == buslog::EndReason::kDiverged &&
                            session.reader().end_event().ticks == k + 1;
      if (recorded) break;
      std::fprintf(stderr, "gyrostab: %s: the re-simulated plant became non-finite at tick %lld; the recorded run %s\n",
                   session.log_path().c_str(), static_cast<long long>(k),
                   s == buslog::ReadStatus::kOk ? "went on" : "has no such end");
      rc = 3;
      break;
    }
  }
  outcome.wall_s = session.elapsed_s();
  if (req.write_outputs) {
    nlohmann::json report = plant_report(scene, *device, req, outcome);
    report["resimulated_from"] = session.log_path();
    std::string error;
    if (!write_run_outputs(req, loop, rec, report, error)) {
      std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
      if (rc < 0) rc = 3;
    }
  }
  if (rc >= 0) return rc;
  return session.finish(s, "re-simulated sensor frame", outcome.ticks_run);
}

}  // namespace gyrostab::tools
