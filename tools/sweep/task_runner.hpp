// Runs one task in this process, the way `gyrostab run` runs a scene in process (tools/run/in_process.cpp):
// the task's scene text through the scene reader and its device's checks (every check `run` and `check`
// make), then the plant and the firmware controller in the closed loop (tools/loop/closed_loop.hpp) — without a
// recorder, a CSV or plots. Each task owns its scene, plant and controller, so tasks run on many threads.
#pragma once

#include <nlohmann/json.hpp>

#include "tools/sweep/study.hpp"
#include "tools/sweep/task.hpp"

namespace gyrostab::tools::sweep {

// The task's record (task_record.hpp) with "timing" {setup_s, run_s}: setup is building the scene text,
// reading and checking it and building plant and controller; run is the loop.
nlohmann::json run_task(const Study& s, const Task& t);

}  // namespace gyrostab::tools::sweep
