// Replay of a bus log into the controller alone (Role::kReplay): NOT IMPLEMENTED YET (issue 4).
#pragma once

#include <cstdio>

#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

template <class Device>
int replay_controller(Device&, const LoopConfig& loop, const RunRequest&) {
  std::fprintf(stderr, "gyrostab: %s: replay is not implemented yet\n", loop.name.c_str());
  return 2;
}

}  // namespace gyrostab::tools
