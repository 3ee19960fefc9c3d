// A directional (heading) gyro scene (Magnus §12.2, (12.21)-(12.34)), as read and checked: the loop, the
// plant (the instrument, the aircraft's motion over the rotating Earth, the compass:
// sim/plants/directional_gyro_plant.hpp) and the firmware controller's configuration
// (firmware/app/directional_gyro_controller.hpp). The member initializers are the scene's defaults; the
// keys: directional_gyro_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/directional_gyro_controller.hpp"
#include "sim/plants/directional_gyro_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct DirectionalGyroScene {
  LoopConfig loop;
  plants::DirectionalGyroPlantParams plant;
  firmware::DirectionalGyroConfig controller{};
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_directional_gyro(SceneReader& r);
SceneDoc directional_gyro_doc();

// The run's plant and controller (directional_gyro_run.cpp).
std::unique_ptr<DeviceScene> make_directional_gyro_scene(std::unique_ptr<DirectionalGyroScene> s);

}  // namespace gyrostab::tools
