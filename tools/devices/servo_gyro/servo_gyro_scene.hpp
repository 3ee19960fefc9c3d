// A servo gyro scene (Magnus §14.4, (14.41)-(14.44)), as read and checked: the loop, the plant (the gimballed
// rotor, the oscillator on axis 1, the brake and the sensors: sim/plants/servo_gyro_plant.hpp), the firmware
// controller's configuration (firmware/app/servo_gyro_controller.hpp) and the report's settings. The member
// initializers are the scene's defaults; the keys: servo_gyro_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/servo_gyro_controller.hpp"
#include "sim/plants/servo_gyro_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct ServoGyroScene {
  LoopConfig loop;
  plants::ServoGyroPlantParams plant;
  firmware::ServoGyroConfig controller;  // reference_kind kRate: [controller] Omega is the drive rate
  double settle_s{15.0};                 // [report] the measurements start here [s]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_servo_gyro(SceneReader& r);
SceneDoc servo_gyro_doc();

// The run's plant and controller (servo_gyro_run.cpp).
std::unique_ptr<DeviceScene> make_servo_gyro_scene(std::unique_ptr<ServoGyroScene> s);

}  // namespace gyrostab::tools
