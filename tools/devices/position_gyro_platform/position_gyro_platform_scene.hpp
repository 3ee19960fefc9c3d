// A position-gyro platform scene (Magnus §16.2.2, (16.6)-(16.10)), as read and checked: the loop, the plant
// (the platform with its two-degree-of-freedom gyro, the disturbance step and the base's roll:
// sim/plants/position_gyro_platform_plant.hpp), the firmware controller's configuration
// (firmware/app/position_gyro_platform_controller.hpp: the amplifier and the slew command) and the report's
// settings. The member initializers are the scene's defaults; the keys: position_gyro_platform_schema.cpp,
// docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/position_gyro_platform_controller.hpp"
#include "sim/plants/position_gyro_platform_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct PositionGyroPlatformScene {
  LoopConfig loop;
  plants::PositionGyroPlatformPlantParams plant;
  firmware::PositionGyroPlatformConfig controller;
  double disturbance_start_s{0.2};  // [disturbance] the step's time [s]
  double slew_start_s{4.0};         // [controller] the slew's start [s]
  double slew_duration_s{4.0};      // [controller] [s]
  double fit_delay_s{1.0};          // [report] the decay is fitted from this long after the step [s]
  double lag_window_s{0.5};         // [report] means over this long before the slew's start and end [s]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_position_gyro_platform(SceneReader& r);
SceneDoc position_gyro_platform_doc();

// The run's plant and controller (position_gyro_platform_run.cpp).
std::unique_ptr<DeviceScene> make_position_gyro_platform_scene(std::unique_ptr<PositionGyroPlatformScene> s);

}  // namespace gyrostab::tools
