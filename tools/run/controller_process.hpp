// The firmware controller as its own process (Role::kController): NOT IMPLEMENTED YET (issue 4).
#pragma once

#include <cstdio>

#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

template <class Device>
int run_controller_process(Device&, const LoopConfig& loop, const RunRequest&) {
  std::fprintf(stderr, "gyrostab: %s: the controller process is not implemented yet\n", loop.name.c_str());
  return 2;
}

}  // namespace gyrostab::tools
