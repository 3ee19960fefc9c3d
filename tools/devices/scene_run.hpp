// The common `run` entry of a device binding (tools/devices/scene_device.hpp): read and validate the scene,
// stop there for `check`, else build the device on it and run it (tools/run/run_device.hpp). The scene and
// the device live on the heap (large fixed-size arrays); the device keeps a reference to the scene.
#pragma once

#include <memory>

#include "tools/run/run_device.hpp"
#include "tools/run/run_output.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

// Builds the device on a scene read and checked, and runs it. Scene: has `loop` (LoopConfig);
// Device(const Scene&). Exit codes as SceneEntry's.
template <class Device, class Scene>
int run_on_scene(const Scene& scene, const RunRequest& req) {
  auto device = std::make_unique<Device>(scene);
  return run_device(*device, scene.loop, req);
}

template <class Device, class Scene>
int run_scene(SceneReader& reader, const RunRequest& req, bool (*read_scene)(SceneReader&, Scene&)) {
  auto scene = std::make_unique<Scene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  return run_on_scene<Device>(*scene, req);
}

}  // namespace gyrostab::tools
