// `gyrostab motion-record SCENE --out FILE [--step-s H] [--duration-s T]`: the base motion the scene's generator produces,
// written as a motion record (tools/scene/motion_csv.hpp) — samples every H seconds over [0, T] (default the scene's duration_s) of
// the attitude, the angular rate and the specific force. Replayed with [motion] kind = "recorded" it
// reproduces the generator within the interpolation error (docs/models/suspension-motion.md#recorded-motion).
#pragma once

#include <string>

namespace gyrostab::tools {

struct MotionRecordRequest {
  std::string scene_path;
  std::string out_path;
  double step_s{0.01};
  double duration_s{-1.0};  // the span recorded [s]; < 0: the scene's duration_s
};

// Exit code: 0 written, 2 scene refused or without a moving base, 3 the file could not be written.
int motion_record(const MotionRecordRequest& req);

}  // namespace gyrostab::tools
