#include "tools/dbc_command.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "hil/can/dbc_writer.hpp"
#include "tools/commands.hpp"
#include "tools/devices/registry.hpp"
#include "tools/run/can_link_setup.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

int write_dbc(const DbcRequest& req) {
  std::string device;
  if (find_device(req.target) != nullptr) {
    device = req.target;
  } else if (!req.target.empty() && std::filesystem::is_regular_file(req.target)) {
    SceneReader reader;
    std::unique_ptr<DeviceScene> scene;
    if (reader.open(req.target)) scene = read_device_scene(reader);
    for (const std::string& p : reader.errors()) std::fprintf(stderr, "%s\n", p.c_str());
    if (scene == nullptr) return 2;
    device = scene->loop().device;
  } else {
    std::string names;
    for (const DeviceDescriptor* d : devices()) names += (names.empty() ? "" : ", ") + std::string(d->name);
    std::fprintf(stderr, "gyrostab dbc: '%s' is neither a device nor a scene file; devices: %s\n",
                 req.target.c_str(), names.c_str());
    return 2;
  }
  const can::DeviceBus bus = can_bus_of(device);
  if (bus.map == nullptr) {
    std::fprintf(stderr, "gyrostab dbc: device %s has no signal table, so no CAN map\n", device.c_str());
    return 2;
  }
  const std::string text = can::dbc_text(bus);
  std::FILE* f = req.out.empty() ? stdout : std::fopen(req.out.c_str(), "w");
  const bool written = f != nullptr && std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool closed = f == nullptr || f == stdout ? std::fflush(stdout) == 0 : std::fclose(f) == 0;
  if (!written || !closed) {
    std::fprintf(stderr, "gyrostab dbc: cannot write %s\n", req.out.empty() ? "standard output" : req.out.c_str());
    return 3;
  }
  return 0;
}

}  // namespace gyrostab::tools
