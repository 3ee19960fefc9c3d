// What a run leaves in its output directory: report.json ({"scene", "figures", "timing"}), signals.csv and
// signals.png (matplotlib through Debian's /usr/bin/python3; a missing interpreter is reported, not fatal).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "tools/loop/loop_outcome.hpp"
#include "tools/loop/recorder.hpp"
#include "tools/run/run_role.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

class FrameTable;

struct RunRequest {
  std::string scene_path;
  std::string scene_text;  // the scene's TOML when not read from scene_path (replay: the log's scene event);
                           // a logging run fills it from the file so the bus log holds exactly what ran
  // With scene_text: the directory its data files (a [motion] file) resolve against; empty: none may be read.
  std::string scene_file_root;
  std::string out_dir{"out"};
  Role role{Role::kInProcess};  // which part of the loop this process runs (run_role.hpp)
  TransportOptions transport;
  std::string mcap_path;  // --mcap FILE: the run as an MCAP file too (run_mcap.hpp)
  // --mcap-frames-every N: the file's frame channels hold every N-th tick's frames (< 0: the recorder's row
  // interval; 0: no frame channels).
  std::int64_t mcap_frames_every{-1};
  // The plant process of `run --transport lcm|can --mcap`: the frames as frames_*.csv beside signals.csv, for
  // the parent's MCAP file (run_mcap.hpp).
  bool mcap_frames_csv{false};
  // --view [ADDR:PORT]: the live view (tools/view/run_view.hpp)
  struct View {
    bool enabled{false};
    std::string address;   // "" = 127.0.0.1 on a free port
    double wait_s{0};      // before tick 0, wait this long at most for a page to connect
    double linger_s{-1};   // after the run, serve this long (< 0: until SIGINT/SIGTERM)
  } view;
  bool check_only{false};  // validate the scene and stop
  bool progress{true};     // progress line on a terminal
  // For tests and studies:
  std::int64_t ticks{-1};            // run exactly this many ticks (the scene's duration otherwise)
  bool write_outputs{true};          // false: keep report and CSV in memory only
  void (*before_loop)(){nullptr};    // called after every allocation of the set-up, just before tick 0
  void (*after_loop)(){nullptr};     // called right after the last tick
  nlohmann::json* report_out{nullptr};  // receives report.json's content
  std::string* csv_out{nullptr};        // receives signals.csv's content
};

// The "scene" and "timing" parts every device shares.
nlohmann::json scene_summary(const LoopConfig& cfg, const std::string& scene_path);
nlohmann::json timing_summary(const LoopConfig& cfg, const LoopOutcome& outcome);

// report.json as written: `report` with figures.ticks (every scene's figures carry its tick count).
nlohmann::json final_report(const nlohmann::json& report);

// Hands the report and CSV to the request (report_out, csv_out) and, if write_outputs, writes report.json,
// signals.csv and (if cfg.plots) signals.png; returns false with `error` set. `frames`: the frames the run kept
// for its MCAP file (or its parent's: frames_sensor.csv, frames_actuator.csv).
bool write_run_outputs(const RunRequest& req, const LoopConfig& cfg, const Recorder& rec, const nlohmann::json& report,
                       std::string& error, const FrameTable* frames = nullptr);

}  // namespace gyrostab::tools
