// The [motion] keys of a device whose base moves (models::BaseSample): which generator drives the base —
// the device's own harmonic roll, a prescribed yaw/pitch/roll with a lever arm, or a recorded motion file —
// and a translational vibration of the suspension point. Reads into motion::SceneBaseMotion
// (sim/motion/scene_base_motion.hpp); the record is loaded and checked here, at scene read time.
// Docs: docs/models/suspension-motion.md, docs/scenes.md#base-motion.
#pragma once

#include "sim/motion/scene_base_motion.hpp"
#include "tools/scene/scene_doc.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

// `duration_s`: the run the motion must cover (a record must span [0, duration_s]).
void read_base_motion(SceneReader& r, motion::SceneBaseMotion& m, double duration_s);
SceneDocTable base_motion_doc();

}  // namespace gyrostab::tools
