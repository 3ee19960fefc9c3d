#include "tools/commands.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "tools/devices/registry.hpp"
#include "tools/run/output_dir.hpp"
#include "tools/loop/recorder.hpp"
#include "tools/run/run_mcap.hpp"
#include "tools/run/run_modes.hpp"
#include "tools/scene/scene_hash.hpp"
#include "tools/view/run_view.hpp"

namespace gyrostab::tools {
namespace {

// The descriptor of the scene's [scene] device; nullptr (the problem added to the reader) if there is none.
const DeviceDescriptor* find_device(SceneReader& reader) {
  const std::string device = reader.text("scene", "device", "", "device model");
  if (const DeviceDescriptor* d = tools::find_device(device)) return d;
  std::string known;
  for (const DeviceDescriptor* d : devices()) known += std::string(known.empty() ? "" : ", ") + std::string(d->name);
  reader.fail("scene", "device", "= \"" + device + "\" is not a known device (" + known + ")");
  return nullptr;
}

std::size_t recorded_columns(const DeviceScene& scene) {
  return scene.loop().signals.empty() ? scene.columns().size() : scene.loop().signals.size();
}

// --ticks against the scene: the simulated time of the last tick must fit the integer clock, and the
// recording must fit the recorder's ceiling. "" or the problem.
std::string ticks_problem(const DeviceScene& scene, std::int64_t ticks) {
  const LoopConfig& loop = scene.loop();
  if (ticks < 0) return "";
  if (ticks > INT64_MAX / loop.tick_ns) {
    return "--ticks " + std::to_string(ticks) + ": the simulated time would overflow the integer clock (at most " +
           std::to_string(INT64_MAX / loop.tick_ns) + " ticks of " + std::to_string(loop.tick_ns) + " ns)";
  }
  // Past a recorded motion's last row the interpolant would extrapolate a cubic: refused, not made up.
  if (const motion::SceneBaseMotion* m = scene.base_motion(); m != nullptr && m->kind == motion::BaseMotionKind::kRecorded) {
    const double end_s = m->recorded.record()->t.back(), run_s = static_cast<double>(ticks) * loop.tick_s();
    if (run_s > end_s) {
      return "--ticks " + std::to_string(ticks) + ": the run (" + std::to_string(run_s) + " s) outlasts the motion record ([motion] file ends at " +
             std::to_string(end_s) + " s)";
    }
  }
  const std::string why = recording_problem(recording_size(ticks, loop.record_every, recorded_columns(scene)));
  return why.empty() ? "" : "--ticks " + std::to_string(ticks) + ": " + why;
}

void print_problems(const SceneReader& reader) {
  for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
}

}  // namespace

std::unique_ptr<DeviceScene> read_device_scene(SceneReader& reader) {
  const DeviceDescriptor* d = find_device(reader);
  if (d == nullptr) return nullptr;
  std::unique_ptr<DeviceScene> scene = d->read(reader);
  if (scene == nullptr) return nullptr;
  const std::string bad = Recorder::check_signals(scene->columns(), scene->loop().signals);
  if (!bad.empty()) {
    reader.fail("output", "signals", bad);
    return nullptr;
  }
  const LoopConfig& loop = scene->loop();
  if (const std::string why = recording_problem(recording_size(loop.ticks(), loop.record_every, recorded_columns(*scene)));
      !why.empty()) {
    reader.fail("scene", "duration_s", why);
    return nullptr;
  }
  return scene;
}

int run_scene(const RunRequest& req) {
  // A logging run reads the file once, so that the bus log's scene event holds exactly the text that ran.
  if ((!req.transport.log_path.empty() || !req.transport.can_log.empty()) && req.scene_text.empty()) {
    RunRequest with_text = req;
    std::ifstream f(req.scene_path, std::ios::binary);
    std::ostringstream text;
    text << f.rdbuf();
    if (!f || text.str().empty()) {
      std::fprintf(stderr, "%s: cannot read the scene file (or it is empty)\n", req.scene_path.c_str());
      return 2;
    }
    with_text.scene_text = text.str();
    with_text.scene_file_root = scene_file_dir(req.scene_path);
    return run_scene(with_text);
  }
  SceneReader reader;
  reader.set_file_root(req.scene_file_root);
  // scene_text set: the scene came from a bus log (gyrostab replay) or was read above; scene_path names it.
  if (!(req.scene_text.empty() ? reader.open(req.scene_path) : reader.parse(req.scene_text, req.scene_path))) {
    print_problems(reader);
    return 2;
  }
  std::unique_ptr<DeviceScene> scene = read_device_scene(reader);
  print_problems(reader);
  if (scene == nullptr) {
    std::fprintf(stderr, "%s: refused (%zu problem%s)\n", req.scene_path.c_str(), reader.errors().size(),
                 reader.errors().size() == 1 ? "" : "s");
    return 2;
  }
  const LoopConfig& loop = scene->loop();
  const std::int64_t ticks = req.ticks >= 0 ? req.ticks : loop.ticks();
  if (const std::string why = ticks_problem(*scene, req.ticks); !why.empty()) {
    std::fprintf(stderr, "%s: refused: %s\n", req.scene_path.c_str(), why.c_str());
    return 2;
  }
  if (req.role == Role::kInProcess || req.role == Role::kPlant || (req.role == Role::kResimulate && req.write_outputs)) {
    if (const std::string w = recording_warning(recording_size(ticks, loop.record_every, recorded_columns(*scene)));
        !w.empty()) {
      std::fprintf(stderr, "%s: warning: %s\n", req.scene_path.c_str(), w.c_str());
    }
  }
  if (req.check_only) {
    // The scene's identity, as the handshake carries it and a log records it (docs/protocol.md).
    std::printf("%s: ok (scene hash %s)\n", req.scene_path.c_str(), format_scene_hash(loop.scene_hash).c_str());
    return 0;
  }
  // Before anything runs: a run that cannot write its outputs is refused now, not after simulating.
  if (req.write_outputs && req.role != Role::kReplay) {
    if (std::string error; !check_output_dir(req.out_dir, error)) {
      std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
      return 2;
    }
  }
  if (!req.mcap_path.empty()) {
    if (const std::string why = mcap_path_problem(req.mcap_path); !why.empty()) {
      std::fprintf(stderr, "gyrostab: %s\n", why.c_str());
      return 2;
    }
  }
  if (const std::string why = view::view_options_problem(req); !why.empty()) {
    std::fprintf(stderr, "gyrostab: %s\n", why.c_str());
    return 2;
  }
  return run_device_scene(*scene, req);
}

int check_scene_text(std::string_view text, const std::string& name, std::vector<std::string>* problems) {
  SceneReader reader;
  int rc = 2;
  if (reader.parse(text, name) && read_device_scene(reader) != nullptr) rc = 0;
  if (problems != nullptr) {
    problems->insert(problems->end(), reader.errors().begin(), reader.errors().end());
  } else {
    print_problems(reader);
  }
  return rc;
}

}  // namespace gyrostab::tools
