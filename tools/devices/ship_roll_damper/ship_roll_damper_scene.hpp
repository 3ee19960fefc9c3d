// A ship roll damper scene (Magnus §14.2, (14.8)), as read and checked: the loop, the plant (the ship, its
// gyro, the sea and the sensors: sim/plants/ship_roll_damper_plant.hpp), the firmware controller's
// configuration (firmware/app/ship_roll_damper_controller.hpp) and the report's settings. The member
// initializers are the scene's defaults; the keys: ship_roll_damper_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/ship_roll_damper_controller.hpp"
#include "sim/plants/ship_roll_damper_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct ShipRollDamperScene {
  LoopConfig loop;
  plants::ShipRollDamperPlantParams plant;
  firmware::ShipRollDamperConfig controller;
  double settle_s{60.0};  // [report] statistics start here [s]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_ship_roll_damper(SceneReader& r);
// Reads the scene's values only (the accuracy study); false when refused.
bool read_ship_roll_damper_scene(SceneReader& r, ShipRollDamperScene& s);
SceneDoc ship_roll_damper_doc();

// The run's plant and controller (ship_roll_damper_run.cpp).
std::unique_ptr<DeviceScene> make_ship_roll_damper_scene(std::unique_ptr<ShipRollDamperScene> s);

}  // namespace gyrostab::tools
