// `gyrostab run SCENE --transport lcm`: the plant and the controller as two child processes over LCM, one
// report. The parent execs /proc/self/exe twice — `controller SCENE --out OUT/controller` and `plant SCENE
// --out OUT` with the request's link options (the fault injections and --jitter go to the side they name),
// waits for both and merges their reports into OUT/report.json: the plant's report (scene, figures, signals,
// its timing and link) with the controller's firmware counters in timing.controller (as in process), the
// controller process's timing and link under "controller_process", and "processes": how each child ended
// and one line of what happened.
// Channel suffix: the request's, or "_<parent pid>" so that parallel runs on one bus don't mix; one session id
// (drawn here, or --session) for both children. SIGINT/SIGTERM to the parent are forwarded to both children
// (they stop at a tick boundary and write their outputs), their reports are merged, and the parent exits 128 +
// the signal; a child dies with its parent (PR_SET_PDEATHSIG), so killing the parent leaves no orphans.
// Each child detects a silent peer itself (receive timeout: it reaches its safe state, reports, exits 6).
// When a child exits with an error (refused scene, diverged plant, peer lost) and the other is still running
// after its receive timeout + 2 s, the parent stops it with SIGTERM (it stops at a tick boundary and writes
// its report). Exit code: 0 both completed; 128 + N the parent was stopped by signal N; 6 a process was killed
// by a signal; otherwise the plant's code if it failed (6: controller lost, 3: diverged, 7: foreign frames on
// the link, ...), else the controller's.
#pragma once

#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

int run_process_pair(const RunRequest& req);

}  // namespace gyrostab::tools
