// One device's run after its scene is read, in the role the request names (run_role.hpp). In process: the
// recorder, the closed loop under the request's limits, the report (scene, the device's figures, timing with
// the firmware controller's counters) and the outputs.
// Exit code: 0 ok, 3 outputs not written or the plant diverged (outputs up to it are written).
#pragma once

#include <cstdio>
#include <string>

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
  Recorder rec(Device::columns(), loop.ticks(), loop.record_every);
  const LoopOutcome outcome = run_requested(device, loop, rec, req);
  nlohmann::json report{{"scene", scene_summary(loop, req.scene_path)},
                        {"figures", device.figures()},
                        {"timing", timing_summary(loop, outcome)}};
  report["timing"]["controller"] = controller_report(device.controller());
  std::string error;
  if (!write_run_outputs(req, loop, rec, report, error)) {
    std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
    return 3;
  }
  if (outcome.diverged) {
    std::fprintf(stderr, "gyrostab: %s: the plant state became non-finite at tick %lld; outputs up to it are written\n",
                 loop.name.c_str(), static_cast<long long>(outcome.diverged_tick));
    return 3;
  }
  return 0;
}

}  // namespace gyrostab::tools
