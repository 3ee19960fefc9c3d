// `gyrostab run SCENE [--out DIR]` and `gyrostab check SCENE`: dispatch on the scene's [scene] device.
#pragma once

#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

// Exit code: 0 ok, 2 scene refused (every problem printed), 3 run failed.
int run_scene(const RunRequest& request);

}  // namespace gyrostab::tools
