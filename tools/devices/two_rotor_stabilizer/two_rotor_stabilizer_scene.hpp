// A two-rotor stabilizer scene (Magnus §14.3.4, Figs. 14.7, 14.8), as read and checked: the loop, the plant
// (sim/plants/two_rotor_stabilizer_plant.hpp: the gyro frame on a moving base, or the two-axis stabilizer),
// the firmware controller's configuration (firmware/app/two_rotor_stabilizer_controller.hpp). The member
// initializers are the scene's defaults; the keys: two_rotor_stabilizer_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/two_rotor_stabilizer_controller.hpp"
#include "sim/plants/two_rotor_stabilizer_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

struct TwoRotorStabilizerScene {
  LoopConfig loop;
  plants::TwoRotorPlantParams plant;
  firmware::TwoRotorStabilizerConfig controller;
  int base_axis{2};  // [base] harmonic_axis, 1-based (plant.base.axis is 0-based)
  bool counter_rotating{true};  // two-axis: [gyro] spin
  double nutation_window_s{2.0};  // [report]: the nutation is fitted over this long after the first step
};

std::unique_ptr<DeviceScene> read_two_rotor_stabilizer(SceneReader& r);
SceneDoc two_rotor_stabilizer_doc();

std::unique_ptr<DeviceScene> make_two_rotor_stabilizer_scene(std::unique_ptr<TwoRotorStabilizerScene> s);

}  // namespace gyrostab::tools
