// A gyro vertical scene (Magnus §12.3, (12.35)-(12.51)), as read and checked: the loop, the plant (the
// instrument, the aircraft's motion over the rotating Earth, the turn indicator and the sensors:
// sim/plants/gyro_vertical_plant.hpp) and the firmware controller's configuration
// (firmware/app/gyro_vertical_controller.hpp). The member initializers are the scene's defaults; the keys:
// gyro_vertical_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/gyro_vertical_controller.hpp"
#include "sim/plants/gyro_vertical_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct GyroVerticalScene {
  LoopConfig loop;
  plants::GyroVerticalPlantParams plant;
  firmware::GyroVerticalConfig controller{.law = {.torque_limit_Nm = 0.05}};
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_gyro_vertical(SceneReader& r);
SceneDoc gyro_vertical_doc();

// The run's plant and controller (gyro_vertical_run.cpp).
std::unique_ptr<DeviceScene> make_gyro_vertical_scene(std::unique_ptr<GyroVerticalScene> s);

}  // namespace gyrostab::tools
