// What a run leaves in its output directory: report.json ({"scene", "figures", "timing"}), signals.csv and
// signals.png (matplotlib through Debian's /usr/bin/python3; a missing interpreter is reported, not fatal).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "tools/run/closed_loop.hpp"
#include "tools/run/recorder.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct RunRequest {
  std::string scene_path;
  std::string out_dir{"out"};
  bool check_only{false};  // validate the scene and stop
  bool progress{true};     // progress line on a terminal
};

// The "scene" and "timing" parts every device shares.
nlohmann::json scene_summary(const LoopConfig& cfg, const std::string& scene_path);
nlohmann::json timing_summary(const LoopConfig& cfg, const LoopOutcome& outcome);

// Writes report.json, signals.csv and (if cfg.plots) signals.png; returns false with `error` set.
bool write_run_outputs(const RunRequest& req, const LoopConfig& cfg, const Recorder& rec, const nlohmann::json& report,
                       std::string& error);

}  // namespace gyrostab::tools
