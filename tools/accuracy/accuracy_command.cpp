#include "tools/accuracy/accuracy_command.hpp"

#include "tools/run/output_dir.hpp"

#include "tools/accuracy/study_entry.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tools/accuracy/study_report.hpp"
#include "tools/devices/registry.hpp"

namespace gyrostab::tools {

namespace accuracy {

StudyOptions study_options(const AccuracyRequest& req) {
  StudyOptions opt;
  opt.repeats = req.quick ? 1 : std::max(1, req.repeats);
  opt.progress = req.progress && isatty(STDERR_FILENO);  // a progress line is for a terminal, not a log
  return opt;
}

int pow2_at_least(double x) {
  int n = 1;
  while (n < x && n < (1 << 20)) n *= 2;
  return n;
}

std::int64_t window_ticks(const AccuracyRequest& req, double default_s, double scene_s, const LoopConfig& loop) {
  const double s = req.duration_s > 0.0 ? req.duration_s : std::min(default_s, scene_s);
  return std::max<std::int64_t>(1, std::llround(s / loop.tick_s()));
}

void fill_scene(StudyResult& r, const LoopConfig& loop, double closed_loop_wall_s) {
  r.scene = loop.name;
  r.device = loop.device;
  r.scene_method = loop.integrator;
  r.scene_substeps = loop.substeps;
  r.closed_loop_wall_s = closed_loop_wall_s;
}

int finish_study(const AccuracyRequest& req, StudyResult& result, double setup_wall_s) {
  result.total_wall_s += setup_wall_s;
  std::printf("%s", format_table(result).c_str());
  if (req.report_out) *req.report_out = study_json(result);
  if (req.write_outputs) {
    std::string error;
    std::vector<std::string> written;
    if (!write_study_outputs(result, req.out_dir, req.plot, written, error)) {
      std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
      return 3;
    }
    std::printf("%s: wrote %s in %s\n", req.scene_path.c_str(), list_names(written).c_str(), req.out_dir.c_str());
  }
  if (!result.reference.converged) {
    std::fprintf(stderr, "gyrostab: %s: the reference is not converged: see report.json \"reference\" and docs/accuracy.md\n",
                 req.scene_path.c_str());
    return 4;
  }
  return 0;
}

}  // namespace accuracy

int run_accuracy(const AccuracyRequest& req) {
  SceneReader reader;
  if (!reader.open(req.scene_path)) {
    for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
    return 2;
  }
  const std::string device = reader.text("scene", "device", "", "device model");
  const DeviceDescriptor* d = find_device(device);
  if (d == nullptr || d->accuracy == nullptr) {
    std::string takes;
    for (const DeviceDescriptor* e : devices()) {
      if (e->accuracy != nullptr) takes += std::string(takes.empty() ? "" : " and ") + std::string(e->name);
    }
    std::fprintf(stderr, "%s: the accuracy study takes %s scenes, not \"%s\"\n", req.scene_path.c_str(),
                 takes.c_str(), device.c_str());
    return 2;
  }
  return d->accuracy(reader, req);
}

}  // namespace gyrostab::tools
