// A gyrocompass scene (Magnus ch. 13, (13.7)-(13.39)), as read and checked: the loop, the plant (the compass,
// the vehicle's motion over the rotating Earth and the sensors: sim/plants/gyrocompass_plant.hpp), the
// firmware controller's configuration (firmware/app/gyrocompass_controller.hpp) with what sets its gains
// (Schuler tuning (13.26), a damping ratio of (13.12)), and the report's settings. The member initializers
// are the scene's defaults; the keys: gyrocompass_schema.cpp, docs/scenes.md.
#pragma once

#include <limits>
#include <memory>

#include "firmware/app/gyrocompass_controller.hpp"
#include "sim/plants/gyrocompass_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct GyrocompassScene {
  LoopConfig loop;
  plants::GyrocompassPlantParams plant;
  firmware::GyrocompassConfig controller;
  double tune_latitude{
      std::numeric_limits<double>::quiet_NaN()};  // Schuler-tune c_e here [rad]; NaN: c_e given
  double damping_ratio{
      std::numeric_limits<double>::quiet_NaN()};  // set f for this ζ of (13.12); NaN: f given
  double extrema_sample_s{1.0};                   // [report] sampling of α for the extrema [s]
  double extrema_hysteresis{1e-5};                // [report] [rad]
  int extrema_every_ticks{100};                   // extrema_sample_s in ticks (derived)
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_gyrocompass(SceneReader& r);
SceneDoc gyrocompass_doc();

// The run's plant and controller (gyrocompass_run.cpp).
std::unique_ptr<DeviceScene> make_gyrocompass_scene(std::unique_ptr<GyrocompassScene> s);

}  // namespace gyrostab::tools
