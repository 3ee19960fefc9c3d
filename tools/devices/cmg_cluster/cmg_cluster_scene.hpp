// A CMG cluster scene (Magnus §14.4, (14.45); the spacecraft is the gyrostat of §4.1), as read and checked:
// the loop, the plant (the spacecraft, the CMGs and their gimbal rate servos, the sensors:
// sim/plants/cmg_cluster_plant.hpp), the firmware controller's configuration
// (firmware/app/cmg_cluster_controller.hpp) and the report's settings. The member initializers are the
// scene's defaults; the keys: cmg_cluster_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "firmware/app/cmg_cluster_controller.hpp"
#include "sim/plants/cmg_cluster_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct CmgClusterScene {
  LoopConfig loop;
  plants::CmgClusterPlantParams plant;
  firmware::CmgClusterConfig controller;
  // [spacecraft] the inertia tensor's components [kg m²]
  double Jxx{60.0}, Jyy{50.0}, Jzz{40.0}, Jxy{0.0}, Jxz{0.0}, Jyz{0.0};
  // [cmg] geometry: the pyramid's skew angle, or explicit axes ("x y z" per CMG)
  double skew_rad{models::kPyramidSkewRad};
  std::vector<std::string> gimbal_axes, spin_axes;
  std::string geometry_problem;  // set by derive() when the explicit axes do not parse or fit
  // [controller] the slew: angle about a body axis, from the identity attitude
  double slew_rad{0.5235987755982988};
  double slew_axis_x{1.0}, slew_axis_y{0.0}, slew_axis_z{0.0};
  double attitude_bandwidth{0.3};  // ω_a [rad/s]
  double attitude_damping{1.0};    // ζ [-]
  // [report]
  double settle_band_rad{0.0017453292519943296};  // the slew is settled once the error stays below this [rad]
  double near_singular_measure{0.01};  // det(A Aᵀ)/h⁶ below this counts as near-singular time [-]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
// The firmware's view of the cluster (steering's gimbal and spin axes, h) from the plant's geometry.
inline firmware::CmgArray cmg_array_of(const models::CmgGeometry& g, double h) {
  firmware::CmgArray a;
  a.count = g.count;
  a.h = h;
  for (int i = 0; i < g.count; ++i) {
    for (int k = 0; k < 3; ++k) {
      a.gimbal_axis[i][k] = g.gimbal_axis[i][k];
      a.spin_axis0[i][k] = g.spin_axis0[i][k];
    }
  }
  return a;
}

std::unique_ptr<DeviceScene> read_cmg_cluster(SceneReader& r);
SceneDoc cmg_cluster_doc();

// The run's plant and controller (cmg_cluster_run.cpp).
std::unique_ptr<DeviceScene> make_cmg_cluster_scene(std::unique_ptr<CmgClusterScene> s);

}  // namespace gyrostab::tools
