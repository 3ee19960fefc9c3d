#include "tools/build_paths.hpp"
#include "tools/run/run_output.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "tools/run/output_dir.hpp"
#include "tools/run/run_mcap.hpp"

namespace gyrostab::tools {

nlohmann::json scene_summary(const LoopConfig& cfg, const std::string& scene_path) {
  return {{"name", cfg.name},
          {"file", scene_path},
          {"device", cfg.device},
          {"seed", cfg.seed},
          {"duration_s", cfg.duration_s},
          {"tick_ns", cfg.tick_ns},
          {"plant_substeps", cfg.substeps},
          {"latency_ticks", cfg.latency_ticks},
          {"integrator", cfg.integrator}};
}

nlohmann::json timing_summary(const LoopConfig& cfg, const LoopOutcome& o) {
  nlohmann::json t{{"ticks", o.ticks_run},
                   {"wall_s", o.wall_s},
                   {"ticks_per_second", o.wall_s > 0 ? static_cast<double>(o.ticks_run) / o.wall_s : 0.0},
                   {"real_time_factor", o.wall_s > 0 ? static_cast<double>(o.ticks_run) * cfg.tick_s() / o.wall_s : 0.0}};
  if (o.cpu_s > 0) {
    t["loop_cpu_s"] = o.cpu_s;
    t["ticks_per_cpu_second"] = static_cast<double>(o.ticks_run) / o.cpu_s;
  }
  if (o.diverged) t["diverged_at_tick"] = o.diverged_tick;
  if (o.diverged && o.diverged_state.name != nullptr) {
    t["diverged_state"] = {{"component", o.diverged_state.name},
                           {"index", o.diverged_state.component},
                           {"last_finite_value", o.diverged_state.last_finite}};
  }
  return t;
}

nlohmann::json final_report(const nlohmann::json& in) {
  nlohmann::json report = in;
  // Every scene's figures carry its tick count; ticks_per_second and the compute-time counters vary run to
  // run, so they stay in "timing" (figures must be bit-identical across reruns).
  if (report.contains("timing") && report.contains("figures")) report["figures"]["ticks"] = report["timing"]["ticks"];
  return report;
}

bool write_run_outputs(const RunRequest& req, const LoopConfig& cfg, const Recorder& rec, const nlohmann::json& in,
                       std::string& error, const FrameTable* frames) {
  const nlohmann::json report = final_report(in);
  if (req.report_out) *req.report_out = report;
  if (req.csv_out) *req.csv_out = rec.csv();
  if (!req.write_outputs) return true;
  OutputSet out(req.out_dir, {"report.json", "signals.csv", "signals.png", kSensorFramesCsv, kActuatorFramesCsv});
  if (!out.open(error)) return false;
  if (!out.write("report.json", report.dump(2) + "\n", error)) return false;
  if (!rec.write_csv(out.staged("signals.csv"), error)) return false;
  if (req.mcap_frames_csv && frames != nullptr) {
    if (!write_frames_csv(*frames, FrameDirection::kSensor, out.staged(kSensorFramesCsv), error) ||
        !write_frames_csv(*frames, FrameDirection::kActuator, out.staged(kActuatorFramesCsv), error)) {
      return false;
    }
  }
  const char* here = std::getenv("GYROSTAB_PLOT_SCRIPT");  // set and empty: no plots (tests, the CAN VM)
  if (cfg.plots && (here == nullptr || *here != '\0')) {
    const std::string script = here ? here : std::string(build_source_dir()) + "/tools/plot/plot_run.py";
    std::string why;
    const int rc = run_program({"/usr/bin/python3", script, out.staging_dir()}, why);
    // Say what failed: the interpreter could not start, the helper was killed, or it exited with a status
    // after its own one-line message (which names the cause: a bad signals.csv, missing libraries, ...).
    if (rc < 0) {
      std::fprintf(stderr, "gyrostab: plots not written (%s%s); report.json and signals.csv are complete\n",
                   why.c_str(),
                   why.rfind("cannot start", 0) == 0 ? ": needs /usr/bin/python3 with python3-matplotlib" : "");
    } else if (rc != 0) {
      std::fprintf(stderr, "gyrostab: plots not written (%s exited %d; its message is above); report.json and "
                           "signals.csv are complete\n",
                   script.c_str(), rc);
    }
  }
  std::vector<std::string> written;
  if (!out.commit(written, error)) return false;
  if (req.role != Role::kController) {
    std::printf("%s: wrote %s in %s\n", req.scene_path.c_str(), list_names(written).c_str(), req.out_dir.c_str());
  }
  // After the directory's outputs are in place, so a failure here loses none of them.
  if (!req.mcap_path.empty() && req.role != Role::kController) {
    if (!write_run_mcap(req.mcap_path, cfg, rec, report, frames, error)) return false;
    std::printf("%s: wrote %s\n", req.scene_path.c_str(), req.mcap_path.c_str());
  }
  return true;
}

}  // namespace gyrostab::tools
