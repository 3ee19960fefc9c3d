// An inertial platform scene (Magnus ch. 16, (16.1)-(16.50)), as read and checked: the loop, the plant (the
// single- or three-axis platform with its gyros and servos, the vehicle's motion and the accelerometers:
// sim/plants/inertial_platform_plant.hpp), the firmware controller's configuration
// (firmware/app/inertial_platform_controller.hpp: the Schuler loops) with the loops' initial velocity errors,
// and the report's settings. The member initializers are the scene's defaults; the keys:
// inertial_platform_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/inertial_platform_controller.hpp"
#include "sim/plants/inertial_platform_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct InertialPlatformScene {
  LoopConfig loop;
  plants::InertialPlatformPlantParams plant;
  firmware::InertialPlatformConfig controller;
  double velocity_error0[2]{0.0, 0.0};  // initial velocity error of each channel's integrator [m/s]
  double extrema_sample_s{10.0};        // [report] sampling of the tilt for the extrema [s]
  double extrema_hysteresis{1e-6};      // [report] [rad]
  int extrema_every_ticks{1000};        // extrema_sample_s in ticks (derived)

  int channels() const { return plant.axes == 1 ? 1 : 2; }
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_inertial_platform(SceneReader& r);
SceneDoc inertial_platform_doc();

// The run's plant and controller (inertial_platform_run.cpp).
std::unique_ptr<DeviceScene> make_inertial_platform_scene(std::unique_ptr<InertialPlatformScene> s);

}  // namespace gyrostab::tools
