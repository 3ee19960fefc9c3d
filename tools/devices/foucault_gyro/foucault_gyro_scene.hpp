// A Foucault gyro scene (Magnus §13.1, (13.1)-(13.4)), as read and checked: the loop, the plant (a declinometer
// or an inclinometer released from rest on an Earth-fixed base: sim/plants/foucault_gyro_plant.hpp), the
// controller's configuration (no law: firmware/app/free_instrument_controller.hpp) and the report's settings.
// The member initializers are the scene's defaults; the keys: foucault_gyro_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/free_instrument_controller.hpp"
#include "sim/plants/foucault_gyro_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

// |latitude| beyond which a declinometer scene is refused: its directive torque H ω^E cosφ vanishes at the
// pole (13.2), and its period grows as 1/sqrt(cosφ) (13.6) — 3.4 times the equator's at 85°.
inline constexpr double kDeclinometerLatitudeLimitDeg = 85.0;

// The Foucault gyros' controller: the free instrument's (no law) on their frames.
template <firmware::MonotonicClock Clock = firmware::NullClock>
using FoucaultGyroController = firmware::BasicFreeInstrumentControllerOf<msg::foucault_gyro::SensorFrame,
                                                                         msg::foucault_gyro::ActuatorFrame, Clock>;

struct FoucaultGyroScene {
  LoopConfig loop;
  plants::FoucaultGyroPlantParams plant;
  firmware::FreeInstrumentConfigOf<msg::foucault_gyro::SensorFrame> controller;
  double small_amplitude{0.008726646259971648};  // [report] period and decay from extrema below this offset [rad]
  double settle_tolerance{4.84813681109536e-05};  // [report] settled once |offset| stays below this [rad]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_foucault_gyro(SceneReader& r);
SceneDoc foucault_gyro_doc();

// The run's plant and controller (foucault_gyro_run.cpp).
std::unique_ptr<DeviceScene> make_foucault_gyro_scene(std::unique_ptr<FoucaultGyroScene> s);

}  // namespace gyrostab::tools
