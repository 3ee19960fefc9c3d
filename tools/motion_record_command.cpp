#include "tools/motion_record_command.hpp"

#include <cmath>
#include <cstdio>
#include <memory>

#include "tools/commands.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/motion_csv.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

int motion_record(const MotionRecordRequest& req) {
  if (!(req.step_s > 0.0) || !std::isfinite(req.step_s)) {
    std::fprintf(stderr, "gyrostab motion-record: --step-s must be a positive number of seconds\n");
    return 2;
  }
  SceneReader reader;
  std::unique_ptr<DeviceScene> scene;
  if (reader.open(req.scene_path)) scene = read_device_scene(reader);
  for (const std::string& p : reader.errors()) std::fprintf(stderr, "%s\n", p.c_str());
  if (scene == nullptr) return 2;
  const motion::SceneBaseMotion* base = scene->base_motion();
  if (base == nullptr) {
    std::fprintf(stderr, "%s: this device's base does not move by a base-motion generator; nothing to record\n",
                 req.scene_path.c_str());
    return 2;
  }
  const double duration = req.duration_s >= 0.0 ? req.duration_s : scene->loop().duration_s;
  // Whole samples past the end, so that the record covers the scene's duration however the step divides it.
  const auto n = static_cast<long long>(std::ceil(duration / req.step_s - 1e-9));
  std::FILE* f = std::fopen(req.out_path.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "gyrostab motion-record: cannot write %s\n", req.out_path.c_str());
    return 3;
  }
  std::fprintf(f, "# gyrostab motion-record %s, every %.17g s over [0, %.17g] s\n", req.scene_path.c_str(), req.step_s,
               static_cast<double>(n) * req.step_s);
  std::fprintf(f, "%s\n", motion_csv_header().c_str());
  for (long long k = 0; k <= n; ++k) {
    // t = k·h, not an accumulated sum: the same times on every run.
    const double t = static_cast<double>(k) * req.step_s;
    const models::BaseSample b = (*base)(t);
    write_motion_csv_row(f, t, base->attitude(t), b.w_B, b.up_B * base->g());
  }
  if (std::fclose(f) != 0) {
    std::fprintf(stderr, "gyrostab motion-record: cannot write %s\n", req.out_path.c_str());
    return 3;
  }
  return 0;
}

}  // namespace gyrostab::tools
