// The keys of the vehicle's motion over the rotating Earth that the instruments on a vehicle (gyro_vertical,
// gyrocompass, inertial_platform, gyro_pendulum, bauersfeld_compass) share: [earth], [vehicle] and the
// consecutive [segment1], [segment2], ... (at most 32), one field table over motion::VehicleMotionParams
// (sim/motion/vehicle_motion.hpp). A device's defaults (its start latitude, its Earth rate) are the
// initializers of its plant's VehicleMotionParams. Documented once in docs/scenes.md: each device's doc()
// returns the same titled table, and `gyrostab scene-keys` writes it at its first device only.
#pragma once

#include "sim/motion/vehicle_motion.hpp"
#include "tools/scene/scene_doc.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

// Reads the keys into `m` (absent keys keep m's values) and checks the motion (the generator's check()).
void read_vehicle_motion(SceneReader& r, motion::VehicleMotionParams& m);

// The table "vehicle motion", with its note.
SceneDocTable vehicle_motion_doc();

}  // namespace gyrostab::tools
