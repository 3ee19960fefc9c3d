#include "tools/commands.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "tools/devices/scene_device.hpp"

namespace gyrostab::tools {
namespace {

constexpr DeviceEntry kDevices[] = {
    {"ship_roll_damper", run_ship_roll_damper},
    {"power_stabilizer", run_power_stabilizer},
    {"monorail", run_monorail},
    {"servo_gyro", run_servo_gyro},
    {"gyro_vertical", run_gyro_vertical},
    {"gyrocompass", run_gyrocompass},
    {"inertial_platform", run_inertial_platform},
    {"gyro_pendulum", run_gyro_pendulum},
};

// The entry of the scene's [scene] device; nullptr (the problem added to the reader) if there is none.
const DeviceEntry* find_device(SceneReader& reader) {
  const std::string device = reader.text("scene", "device", "", "device model");
  for (const DeviceEntry& d : kDevices) {
    if (device == d.name) return &d;
  }
  std::string known;
  for (const DeviceEntry& d : kDevices) known += std::string(known.empty() ? "" : ", ") + d.name;
  reader.fail("scene", "device", "= \"" + device + "\" is not a known device (" + known + ")");
  return nullptr;
}

void print_problems(const SceneReader& reader) {
  for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
}

}  // namespace

int run_scene(const RunRequest& req) {
  // A logging run reads the file once, so that the bus log's scene event holds exactly the text that ran.
  if (!req.transport.log_path.empty() && req.scene_text.empty()) {
    RunRequest with_text = req;
    std::ifstream f(req.scene_path, std::ios::binary);
    std::ostringstream text;
    text << f.rdbuf();
    if (!f || text.str().empty()) {
      std::fprintf(stderr, "%s: cannot read the scene file (or it is empty)\n", req.scene_path.c_str());
      return 2;
    }
    with_text.scene_text = text.str();
    return run_scene(with_text);
  }
  SceneReader reader;
  // scene_text set: the scene came from a bus log (gyrostab replay) or was read above; scene_path names it.
  if (!(req.scene_text.empty() ? reader.open(req.scene_path) : reader.parse(req.scene_text, req.scene_path))) {
    print_problems(reader);
    return 2;
  }
  const DeviceEntry* d = find_device(reader);
  if (d == nullptr) {
    print_problems(reader);
    return 2;
  }
  const int rc = d->run(reader, req);
  print_problems(reader);
  if (rc == 0 && req.check_only) std::printf("%s: ok\n", req.scene_path.c_str());
  if (rc == 0 && !req.check_only && req.write_outputs && req.role != Role::kController) {
    std::printf("%s: wrote %s/report.json, signals.csv\n", req.scene_path.c_str(), req.out_dir.c_str());
  }
  if (rc == 2)
    std::fprintf(stderr, "%s: refused (%zu problem%s)\n", req.scene_path.c_str(), reader.errors().size(),
                 reader.errors().size() == 1 ? "" : "s");
  return rc;
}

int check_scene_text(std::string_view text, const std::string& name, std::vector<std::string>* problems) {
  SceneReader reader;
  RunRequest req;
  req.scene_path = name;
  req.check_only = true;
  req.progress = false;
  req.write_outputs = false;
  int rc = 2;
  if (reader.parse(text, name)) {
    if (const DeviceEntry* d = find_device(reader)) rc = d->run(reader, req);
  }
  if (problems != nullptr) {
    problems->insert(problems->end(), reader.errors().begin(), reader.errors().end());
  } else {
    print_problems(reader);
  }
  return rc;
}

}  // namespace gyrostab::tools
