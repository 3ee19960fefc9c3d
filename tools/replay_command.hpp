// `gyrostab replay LOG [--scene FILE] [--real-time] [--resimulate] [--out DIR]`: reads the scene from the bus
// log's scene event (or FILE), builds the scene's device and hands it to replay_controller
// (tools/run/replay.hpp) or, with --resimulate, to resimulate_plant (tools/run/resimulate.hpp), through
// run_scene with the scene text. Exit codes: tools/run/replay_session.hpp.
#pragma once

#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

// request.role: Role::kReplay or Role::kResimulate; request.transport.replay_log: the log; request.scene_path:
// empty (the log's scene) or the --scene file.
int replay_log(RunRequest request);

}  // namespace gyrostab::tools
