// Where a scene's motion record may come from, and loading it: a relative path, resolved against the scene
// file's directory, that stays inside that directory or the motion_records/ directory beside it (how
// sim/scenes/ reaches sim/motion_records/), names a regular .csv file of at most 16 MiB. A scene read from
// text (no file root: check_scene_text, the fuzz target) names no file at all. Docs:
// docs/models/suspension-motion.md#recorded-motion.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tools/scene/motion_csv.hpp"

namespace gyrostab::tools {

inline constexpr std::uintmax_t kMaxMotionFileBytes = 16u << 20;

// The record, or nullptr with the problems ("file:line: ..." for the CSV's, else the path's).
std::shared_ptr<const motion::MotionRecord> load_motion_file(const std::string& file, const std::string& file_root,
                                                             const MotionCsvLimits& limits,
                                                             std::vector<std::string>& problems);

}  // namespace gyrostab::tools
