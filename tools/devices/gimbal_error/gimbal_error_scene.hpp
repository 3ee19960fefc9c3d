// A gimbal-error scene (Magnus §12.1, (12.2)-(12.20)), as read and checked: the loop, the plant (a free
// position gyro in one of the six mountings on a vehicle with prescribed yaw, pitch and roll:
// sim/plants/gimbal_error_plant.hpp) and the controller's configuration (no law:
// firmware/app/free_instrument_controller.hpp). The member initializers are the scene's defaults; the keys:
// gimbal_error_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/free_instrument_controller.hpp"
#include "sim/plants/gimbal_error_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

// One vehicle angle as the scene gives it: a(t) = angle + rate t + amplitude sin(2π t/period + phase).
struct VehicleAngleKeys {
  double angle{0.0};      // [rad]
  double rate{0.0};       // [rad/s]
  double amplitude{0.0};  // [rad]
  double period{10.0};    // [s]
  double phase{0.0};      // [rad]
};

// The gyro's controller: the free instrument's (no law) on the gimbal error's frames.
template <firmware::MonotonicClock Clock = firmware::NullClock>
using GimbalErrorController = firmware::BasicFreeInstrumentControllerOf<msg::gimbal_error::SensorFrame,
                                                                        msg::gimbal_error::ActuatorFrame, Clock>;

struct GimbalErrorScene {
  LoopConfig loop;
  plants::GimbalErrorPlantParams plant;  // plant.gyro.vehicle is built from yaw, pitch, roll
  VehicleAngleKeys yaw, pitch, roll;     // ψ, ϑ, φ of (12.2)
  firmware::FreeInstrumentConfigOf<msg::gimbal_error::SensorFrame> controller;
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_gimbal_error(SceneReader& r);
SceneDoc gimbal_error_doc();

// The run's plant and controller (gimbal_error_run.cpp).
std::unique_ptr<DeviceScene> make_gimbal_error_scene(std::unique_ptr<GimbalErrorScene> s);

}  // namespace gyrostab::tools
