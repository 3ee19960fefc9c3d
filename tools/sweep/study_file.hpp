// Reads a study file (TOML, docs/sweep.md): [study], [[sea_state]] rows and [[variant]] rows, every key typed
// and range-checked, unknown keys refused, the base scene read and found to be a ship roll damper in an
// irregular sea. Every problem is reported as "file:line: [table] key: reason", all at once.
#pragma once

#include <string>
#include <vector>

#include "tools/sweep/study.hpp"

namespace gyrostab::tools::sweep {

// false (the problems appended) when the file is refused.
bool read_study_file(const std::string& path, Study& study, std::vector<std::string>& problems);

// The scene keys a study sets itself, which a variant may not set: "scene.seed", "sea.Hs", ...
bool study_owns_key(const std::string& section, const std::string& key);

}  // namespace gyrostab::tools::sweep
