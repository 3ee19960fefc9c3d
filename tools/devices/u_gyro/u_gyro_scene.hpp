// A U-gyro scene (Magnus §15.4, (15.27)-(15.29)), as read and checked: the loop, the plant (the rate gyro with
// an asymmetric rotor on a rate table: sim/plants/u_gyro_plant.hpp), the controller's configuration (no law:
// firmware/app/free_instrument_controller.hpp) and the report's settings. The member initializers are the
// scene's defaults; the keys: u_gyro_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/free_instrument_controller.hpp"
#include "sim/plants/u_gyro_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

// The U-gyro's controller: the free instrument's (no law) on the U-gyro's frames.
template <firmware::MonotonicClock Clock = firmware::NullClock>
using UGyroController = firmware::BasicFreeInstrumentControllerOf<msg::u_gyro::SensorFrame,
                                                                  msg::u_gyro::ActuatorFrame, Clock>;

struct UGyroScene {
  LoopConfig loop;
  plants::UGyroPlantParams plant;
  firmware::FreeInstrumentConfigOf<msg::u_gyro::SensorFrame> controller;
  double settle_s{0.5};  // [report] the output's harmonics are measured after this time [s]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_u_gyro(SceneReader& r);
SceneDoc u_gyro_doc();

// The run's plant and controller (u_gyro_run.cpp).
std::unique_ptr<DeviceScene> make_u_gyro_scene(std::unique_ptr<UGyroScene> s);

}  // namespace gyrostab::tools
