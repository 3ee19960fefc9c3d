// One device's run after its scene is read, in the role the request names (run_role.hpp). In process: the
// recorder, the closed loop under the request's limits, the report (scene, the device's figures, timing with
// the firmware controller's counters) and the outputs.
// Exit code: 0 ok, 3 outputs not written or the plant diverged (outputs up to it are written), or the bus log
// (--log) not created or incomplete; 128 + N stopped by signal N (SIGINT, SIGTERM) at a tick boundary.
#pragma once

#include <cstdio>
#include <string>

#include "tools/run/bus_log_sink.hpp"
#include "tools/run/controller_process.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/run/plant_process.hpp"
#include "tools/run/replay.hpp"
#include "tools/run/resimulate.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

template <class Device>
int run_device(Device& device, const LoopConfig& loop, const RunRequest& req) {
  switch (req.role) {
    case Role::kInProcess: break;
    case Role::kPlant: return run_plant_process(device, loop, req);
    case Role::kController: return run_controller_process(device, loop, req);
    case Role::kReplay: return replay_controller(device, loop, req);
    case Role::kResimulate: return resimulate_plant(device, loop, req);
  }
  // [output] signals: only the named columns are recorded; an unknown name refuses the run before tick 0.
  if (const std::string bad = Recorder::check_signals(Device::columns(), loop.signals); !bad.empty()) {
    std::fprintf(stderr, "%s: [output] signals: %s\n", req.scene_path.c_str(), bad.c_str());
    return 2;
  }
  Recorder rec(Device::columns(), loop.ticks(), loop.record_every, loop.signals);
  // --log FILE: the same loop with the bus log as its tick sink (bus_log_sink.hpp); stops at a tick boundary
  // on SIGINT/SIGTERM (exit 128 + signal, outputs and log written up to it).
  const bool logging = !req.transport.log_path.empty();
  LoggedRun logged;
  const LoopOutcome outcome = logging ? run_logged(device, loop, rec, req, logged) : run_requested(device, loop, rec, req);
  if (logging && !logged.started) {
    std::fprintf(stderr, "gyrostab: %s\n", logged.error.c_str());
    return 3;
  }
  nlohmann::json report{{"scene", scene_summary(loop, req.scene_path)},
                        {"figures", device.figures()},
                        {"timing", timing_summary(loop, outcome)}};
  report["timing"]["controller"] = controller_report(device.controller());
  // A device that times more than its own loop (e.g. the reduced-model comparison's full-model run).
  if constexpr (requires(const Device& d) { d.extra_timing(outcome); }) report["timing"].update(device.extra_timing(outcome));
  // Blocks a device adds beside "figures" (e.g. "plant": what the loop assembled; "reduced_model").
  if constexpr (requires(const Device& d) { d.report_extra(); }) report.update(device.report_extra());
  // The run's integration error estimate beside its run time (tools/accuracy/half_step_window.hpp, computed
  // here after the loop). Deterministic, but kept out of "figures": figures are the device's physics.
  if constexpr (requires(const Device& d) { d.error_estimate(); }) {
    report["error_estimate"] = device.error_estimate();
  } else {
    report["error_estimate"] = {{"available", false}, {"why", "this device binding has no error estimate"}};
  }
  if (logging) report["log"] = logged.summary;
  std::string error;
  if (!write_run_outputs(req, loop, rec, report, error)) {
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
