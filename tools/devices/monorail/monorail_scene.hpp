// A monorail scene (Magnus §14.1, (14.1)-(14.7)), as read and checked: the loop, the plant (the car, its gyro
// case, the track with its curve and gust, the initial tilt and the sensors: sim/plants/monorail_plant.hpp),
// the firmware controller's configuration (firmware/app/monorail_controller.hpp) and the report's settings.
// The member initializers are the scene's defaults; the keys: monorail_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/monorail_controller.hpp"
#include "sim/plants/monorail_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct MonorailScene {
  LoopConfig loop;
  plants::MonorailPlantParams plant;
  bool allow_unstable_curve{false};  // [track] run even if the loop of (14.6) is unstable in the curve
  firmware::MonorailConfig controller;
  double settle_s{10.0};  // [report] the tilt statistics start here [s]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_monorail(SceneReader& r);
SceneDoc monorail_doc();

// The run's plant and controller (monorail_run.cpp).
std::unique_ptr<DeviceScene> make_monorail_scene(std::unique_ptr<MonorailScene> s);

}  // namespace gyrostab::tools
