// A spatial-compass scene (Bauersfeld, Magnus §13.4, (13.40)-(13.64)), as read and checked: the loop, the
// plant (the sphere with its two rotors on a vehicle over the rotating Earth:
// sim/plants/bauersfeld_compass_plant.hpp), the controller's configuration (no law:
// firmware/app/free_instrument_controller.hpp) and the report's settings. The member initializers are the
// scene's defaults; the keys: bauersfeld_compass_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/free_instrument_controller.hpp"
#include "sim/plants/bauersfeld_compass_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

// The compass's controller: the free instrument's (no law) on the compass's frames.
template <firmware::MonotonicClock Clock = firmware::NullClock>
using BauersfeldCompassController =
    firmware::BasicFreeInstrumentControllerOf<msg::bauersfeld_compass::SensorFrame,
                                              msg::bauersfeld_compass::ActuatorFrame, Clock>;

struct BauersfeldCompassScene {
  LoopConfig loop;
  plants::BauersfeldCompassPlantParams plant;
  firmware::FreeInstrumentConfigOf<msg::bauersfeld_compass::SensorFrame> controller;
  double tuning_ratio{1.0};       // [compass] H²/(f m s |R^M|) that sets f when f is absent
  bool tuned{false};              // [compass] refuse unless H² = f m s |R^M| (13.60)
  double period_threshold{1e-6};  // [report] hysteresis of the tilt's zero crossings [rad]
  double rate_bound{0.0};         // derived: an upper bound of |a1'| on the plan [rad/s]
};

// |R^M| = R − s: the centre of mass below the support point on the Earth's surface [m].
inline double bauersfeld_radius_M(const BauersfeldCompassScene& s) {
  return s.plant.vehicle.earth.radius - s.plant.compass.s;
}

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_bauersfeld_compass(SceneReader& r);
SceneDoc bauersfeld_compass_doc();

// The run's plant and controller (bauersfeld_compass_run.cpp).
std::unique_ptr<DeviceScene> make_bauersfeld_compass_scene(std::unique_ptr<BauersfeldCompassScene> s);

}  // namespace gyrostab::tools
