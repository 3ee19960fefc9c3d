// `gyrostab run SCENE [--out DIR]` and `gyrostab check SCENE`: dispatch on the scene's [scene] device.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

// Exit code: 0 ok, 2 scene refused (every problem printed), 3 run failed.
// The scene is request.scene_text if set (named request.scene_path in messages), else the file scene_path.
int run_scene(const RunRequest& request);

// `gyrostab check` on a scene held in memory (tests, the fuzz target tests/fuzz/scene_fuzz.cpp): parse the
// text (`name` stands for the file in messages), find the [scene] device and run its scene validation
// (parameters and the controller's start-up checks) without building or running anything. Returns 0 (valid)
// or 2 (refused); the problems go to `problems` if given, else to stderr. Never throws on bad input.
int check_scene_text(std::string_view text, const std::string& name,
                     std::vector<std::string>* problems = nullptr);

class DeviceScene;
class SceneReader;
// A parsed scene read and checked as `run` and `check` read it (its device's schema and checks, [output]
// signals, the recording's size); nullptr, with the problems in the reader, when refused. `gyrostab sweep`
// reads every task's scene through it.
std::unique_ptr<DeviceScene> read_device_scene(SceneReader& reader);

}  // namespace gyrostab::tools
