// A gyro pendulum scene (Magnus §12.3.3, (12.52)-(12.68); Chelnokov §2), as read and checked: the loop, the
// plant (the pendulum by the scene's model and integrator, the vehicle's motion and the pick-offs:
// sim/plants/gyro_pendulum_plant.hpp), the monitor-only firmware controller
// (firmware/app/gyro_pendulum_controller.hpp), the pendulum's offset as given or tuned, and the report's
// settings. The member initializers are the scene's defaults; the keys: gyro_pendulum_schema.cpp,
// docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/gyro_pendulum_controller.hpp"
#include "sim/plants/gyro_pendulum_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct GyroPendulumScene {
  LoopConfig loop;
  plants::GyroPendulumPlantParams plant;
  firmware::GyroPendulumConfig controller;
  double s_given{0.0};            // [pendulum] s_m; 0: the tuned value [m]
  double detuning{1.0};           // factor on s
  double s_tuned{0.0};            // (12.66) for H > 0, (12.59) for H = 0 [m] (derived)
  double period_threshold{1e-6};  // [report] hysteresis of the period meter [rad]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_gyro_pendulum(SceneReader& r);
SceneDoc gyro_pendulum_doc();

// The run's plant and controller (gyro_pendulum_run.cpp).
std::unique_ptr<DeviceScene> make_gyro_pendulum_scene(std::unique_ptr<GyroPendulumScene> s);

}  // namespace gyrostab::tools
