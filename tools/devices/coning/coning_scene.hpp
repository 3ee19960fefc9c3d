// A coning scene (Magnus §15.5, (15.36)-(15.42)), as read and checked: the loop, the plant (a platform on a
// vibrating base with a P- or I-gyro on its axis 3 and a geared servo: sim/plants/coning_plant.hpp), the
// firmware controller's configuration (firmware/app/coning_controller.hpp) and the report's settings. The
// member initializers are the scene's defaults; the keys: coning_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/coning_controller.hpp"
#include "sim/plants/coning_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct ConingScene {
  LoopConfig loop;
  plants::ConingPlantParams plant;
  firmware::ConingConfig controller;
  double settle_s{30.0};  // [report] the drift is measured after this time [s]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_coning(SceneReader& r);
SceneDoc coning_doc();

// The run's plant and controller (coning_run.cpp).
std::unique_ptr<DeviceScene> make_coning_scene(std::unique_ptr<ConingScene> s);

}  // namespace gyrostab::tools
