// The scenes shipped in sim/scenes/ (every *.toml directly in it), sorted by name.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace gyrostab::testing {

inline std::vector<std::string> shipped_scenes() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(GYROSTAB_SOURCE_DIR "/sim/scenes")) {
    if (e.is_regular_file() && e.path().extension() == ".toml") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace gyrostab::testing
