#include "tools/replay_command.hpp"

#include <cstdio>

#include "tools/commands.hpp"
#include "tools/scene/scene_reader.hpp"
#include "tools/log/bus_log_reader.hpp"
#include "tools/run/replay_session.hpp"
#include "tools/run/can_replay.hpp"

namespace gyrostab::tools {

int replay_log(RunRequest req) {
  if (!req.scene_path.empty()) {
    req.transport.replay_scene_override = true;
    req.scene_text.clear();
    return run_scene(req);
  }
  if (can::looks_like_candump_log(req.transport.replay_log)) {  // a candump log of the CAN bus
    can::CandumpFile file;
    std::string error;
    if (!can::read_candump_file(req.transport.replay_log, file, error)) {
      std::fprintf(stderr, "gyrostab: %s, nothing replayed\n", error.c_str());
      return kReplayExitBadLog;
    }
    req.scene_text = candump_scene_text(file);
    if (req.scene_text.empty()) {
      std::fprintf(stderr, "gyrostab: %s: a candump log without gyrostab's header (no scene): give the scene with "
                   "--scene FILE\n", req.transport.replay_log.c_str());
      return 2;
    }
    req.scene_path = req.transport.replay_log + ":scene";
    return run_scene(req);
  }
  buslog::BusLogReader reader;
  const buslog::ReadStatus s = reader.open(req.transport.replay_log);
  if (s != buslog::ReadStatus::kOk) {
    std::fprintf(stderr, "gyrostab: %s: %s, nothing replayed: %s\n", req.transport.replay_log.c_str(),
                 buslog::describe(s), reader.problem().c_str());
    return s == buslog::ReadStatus::kUnreadable ? 2 : kReplayExitBadLog;
  }
  if (reader.scene().toml.empty()) {
    std::fprintf(stderr, "gyrostab: %s: the scene event holds no scene text; give one with --scene FILE\n",
                 req.transport.replay_log.c_str());
    return kReplayExitBadLog;
  }
  req.scene_text = reader.scene().toml;
  req.scene_path = req.transport.replay_log + ":scene";
  // A motion file resolves as it did for the recorded run: against the directory of the scene file it named.
  if (!reader.scene().source.empty()) req.scene_file_root = scene_file_dir(reader.scene().source);
  return run_scene(req);
}

}  // namespace gyrostab::tools
