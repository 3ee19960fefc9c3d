// The run modes, written once against the plant and controller ports (tools/devices/device.hpp builds them
// from a scene): which part of the loop this process runs is the request's role (run_role.hpp).
//   in process     plant + firmware in one process (in_process.cpp)
//   plant          the plant alone over a link: LCM, CAN FD or the tests' memory bus (plant_process.cpp)
//   controller     the firmware controller alone, the other end (controller_process.cpp)
//   replay         the controller alone on a recorded bus log, every actuator frame compared (replay.cpp)
//   re-simulation  the plant alone, open loop, on the recorded actuator frames (resimulate.cpp)
// Exit codes: 0 ok, 2 refused, 3 failed (diverged, outputs or log not written), 4-5 replay (replay_session.hpp),
// 6 the peer was lost, 128 + N stopped by signal N. Docs: docs/architecture.md.
#pragma once

#include <nlohmann/json.hpp>

#include "tools/devices/device.hpp"
#include "tools/loop/loop_outcome.hpp"
#include "tools/loop/recorder.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

int run_device_scene(const DeviceScene& scene, const RunRequest& req);

int run_in_process(const DeviceScene& scene, const RunRequest& req);
int run_plant_process(const DeviceScene& scene, const RunRequest& req);
int run_controller_process(const DeviceScene& scene, const RunRequest& req);
int replay_controller(const DeviceScene& scene, const RunRequest& req);
int resimulate_plant(const DeviceScene& scene, const RunRequest& req);

// report.json of a run that had the plant: "scene", "figures", "timing" (+ the plant's extra timing),
// "limits" and the plant's own blocks ("plant", "error_estimate", ...).
nlohmann::json plant_report(const DeviceScene& scene, const PlantPort& plant, const RunRequest& req,
                            const LoopOutcome& outcome);

// [output] signals checked against the scene's columns; false (message printed) when refused.
bool signals_ok(const DeviceScene& scene, const RunRequest& req);

// The recorder of a run of `ticks` ticks: the plant's rows (row_columns), keeping the scene's [output] signals
// or, without them, the columns the scene has.
Recorder scene_recorder(const DeviceScene& scene, std::int64_t ticks);

}  // namespace gyrostab::tools
