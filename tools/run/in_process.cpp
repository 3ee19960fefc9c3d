// The in-process run: the recorder, the closed loop under the request's limits and hooks, the report (scene,
// the plant's figures, timing with the firmware controller's counters) and the outputs. With --log FILE the
// same loop has the bus log as its tick sink (bus_log_sink.hpp) and stops at a tick boundary on
// SIGINT/SIGTERM (exit 128 + signal, outputs and log written up to it). With --view the loop's row sink is the
// live view's feed (tools/view/run_view.hpp), which only reads.
#include <cstdio>
#include <memory>
#include <string>

#include "tools/devices/registry.hpp"
#include "tools/run/bus_log_sink.hpp"
#include "tools/loop/closed_loop.hpp"
#include "tools/run/frame_table.hpp"
#include "tools/run/run_mcap.hpp"
#include "tools/run/run_modes.hpp"
#include "tools/view/run_view.hpp"

namespace gyrostab::tools {

nlohmann::json plant_report(const DeviceScene& scene, const PlantPort& plant, const RunRequest& req,
                            const LoopOutcome& outcome) {
  const LoopConfig& loop = scene.loop();
  nlohmann::json report{{"scene", scene_summary(loop, req.scene_path)},
                        {"figures", plant.figures()},
                        {"timing", timing_summary(loop, outcome)},
                        {"limits", scene.limits()}};
  report["timing"].update(plant.extra_timing(outcome));
  report.update(plant.report_extra());
  report["error_estimate"] = plant.error_estimate();
  return report;
}

bool signals_ok(const DeviceScene& scene, const RunRequest& req) {
  const std::string bad = Recorder::check_signals(scene.columns(), scene.loop().signals);
  if (bad.empty()) return true;
  std::fprintf(stderr, "%s: [output] signals: %s\n", req.scene_path.c_str(), bad.c_str());
  return false;
}

Recorder scene_recorder(const DeviceScene& scene, std::int64_t ticks) {
  const LoopConfig& loop = scene.loop();
  return Recorder(scene.row_columns(), ticks, loop.record_every, loop.signals.empty() ? scene.columns() : loop.signals);
}

int run_device_scene(const DeviceScene& scene, const RunRequest& req) {
  switch (req.role) {
    case Role::kInProcess: return run_in_process(scene, req);
    case Role::kPlant: return run_plant_process(scene, req);
    case Role::kController: return run_controller_process(scene, req);
    case Role::kReplay: return replay_controller(scene, req);
    case Role::kResimulate: return resimulate_plant(scene, req);
  }
  return 2;
}

int run_in_process(const DeviceScene& scene, const RunRequest& req) {
  const LoopConfig& loop = scene.loop();
  if (!signals_ok(scene, req)) return 2;
  std::unique_ptr<PlantPort> plant = scene.make_plant(PlantOptions{true, req.ticks});
  std::unique_ptr<ControllerPort> controller = scene.make_controller();
  Recorder rec = scene_recorder(scene, req.ticks >= 0 ? req.ticks : loop.ticks());
  LoopConfig run_loop = loop;
  if (req.ticks >= 0) run_loop.duration_s = static_cast<double>(req.ticks) * run_loop.tick_s();

  const bool logging = !req.transport.log_path.empty();
  LoggedRun logged;
  std::unique_ptr<BusLog> log;
  if (logging) {
    log = std::make_unique<BusLog>();
    if (!log->open(loop, req, logged.error)) {
      std::fprintf(stderr, "gyrostab: %s\n", logged.error.c_str());
      return 3;
    }
  }
  // --mcap: the frames of the recorded ticks (or --mcap-frames-every N) for the file's frame channels.
  std::string why;
  std::unique_ptr<FrameTable> frames = make_frame_table(signals_of(scene), req, loop, run_loop.ticks(), why);
  if (!why.empty()) {
    std::fprintf(stderr, "gyrostab: --mcap: %s\n", why.c_str());
    return 2;
  }
  TickFanOut sinks(log.get(), frames.get());
  std::unique_ptr<view::RunView> live;
  if (req.view.enabled) {
    live = view::RunView::start(scene, req, rec, controller.get(), run_loop.ticks(), why);
    if (!live) {
      std::fprintf(stderr, "gyrostab: %s\n", why.c_str());
      return 2;
    }
  }
  LoopOutcome outcome;
  {
    std::unique_ptr<StopSignalGuard> guard;
    if (logging) guard = std::make_unique<StopSignalGuard>();
    if (req.before_loop) req.before_loop();
    outcome = run_closed_loop(*plant, *controller, run_loop, &rec, req.progress, sinks.sink(),
                              live ? live->sink() : nullptr);
    if (req.after_loop) req.after_loop();
    if (logging && outcome.interrupted) logged.stop_signal = stop_signal_received();
  }
  if (logging) log->close(outcome, logged);

  nlohmann::json report = plant_report(scene, *plant, req, outcome);
  report["timing"]["controller"] = controller->report();
  if (logging) report["log"] = logged.summary;
  std::string error;
  const bool written = write_run_outputs(req, loop, rec, report, error, frames.get());
  if (live) live->finish(report);
  if (!written) {
    std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
    return 3;
  }
  if (logging && !logged.error.empty()) {
    std::fprintf(stderr, "gyrostab: %s\n", logged.error.c_str());
    return 3;
  }
  if (logged.stop_signal != 0) {
    std::fprintf(stderr, "gyrostab: %s: stopped by %s after %lld ticks; outputs and the bus log up to it are written\n",
                 loop.name.c_str(), signal_name(logged.stop_signal), static_cast<long long>(outcome.ticks_run));
    return 128 + logged.stop_signal;
  }
  if (outcome.diverged) {
    std::fprintf(stderr, "gyrostab: %s; outputs up to it are written\n",
                 describe_non_finite(loop.name, outcome.diverged_tick, outcome.diverged_state).c_str());
    return 3;
  }
  return 0;
}

}  // namespace gyrostab::tools
