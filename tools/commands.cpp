#include "tools/commands.hpp"

#include <cstdio>
#include <string>

#include "tools/devices/scene_device.hpp"

namespace gyrostab::tools {
namespace {

constexpr DeviceEntry kDevices[] = {
    {"ship_roll_damper", run_ship_roll_damper},
};

}  // namespace

int run_scene(const RunRequest& req) {
  SceneReader reader;
  if (!reader.open(req.scene_path)) {
    for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
    return 2;
  }
  const std::string device = reader.text("scene", "device", "", "device model");
  for (const DeviceEntry& d : kDevices) {
    if (device == d.name) {
      const int rc = d.run(reader, req);
      for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
      if (rc == 0 && req.check_only) std::printf("%s: ok\n", req.scene_path.c_str());
      if (rc == 0 && !req.check_only && req.write_outputs) std::printf("%s: wrote %s/report.json, signals.csv\n", req.scene_path.c_str(),
                                                  req.out_dir.c_str());
      if (rc == 2) std::fprintf(stderr, "%s: refused (%zu problem%s)\n", req.scene_path.c_str(),
                                reader.errors().size(), reader.errors().size() == 1 ? "" : "s");
      return rc;
    }
  }
  std::string known;
  for (const DeviceEntry& d : kDevices) known += std::string(known.empty() ? "" : ", ") + d.name;
  reader.fail("scene", "device", "= \"" + device + "\" is not a known device (" + known + ")");
  for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
  return 2;
}

}  // namespace gyrostab::tools
