// What every device's `gyrostab accuracy` entry (tools/devices/<device>/*_study.cpp) shares: the options,
// the window, the scene's part of the result, and the ending (table, outputs, exit code).
#pragma once

#include <cstdint>

#include "tools/accuracy/accuracy_command.hpp"
#include "tools/accuracy/study_options.hpp"
#include "tools/accuracy/study_result.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

namespace accuracy {

// What every device's study entry shares.
StudyOptions study_options(const AccuracyRequest& req);
// The study's window in ticks: --duration, else min(default_s, the scene's duration).
std::int64_t window_ticks(const AccuracyRequest& req, double default_s, double scene_s, const LoopConfig& loop);
void fill_scene(StudyResult& r, const LoopConfig& loop, double closed_loop_wall_s);
// Prints the table, writes the outputs; the exit code.
int finish_study(const AccuracyRequest& req, StudyResult& result, double setup_wall_s);
// The smallest power of two ≥ x (x ≥ 1).
int pow2_at_least(double x);

}  // namespace accuracy

}  // namespace gyrostab::tools
