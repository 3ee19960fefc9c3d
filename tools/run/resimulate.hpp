// Open-loop re-simulation of the plant from a bus log (Role::kResimulate): NOT IMPLEMENTED YET (issue 4).
#pragma once

#include <cstdio>

#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

template <class Device>
int resimulate_plant(Device&, const LoopConfig& loop, const RunRequest&) {
  std::fprintf(stderr, "gyrostab: %s: re-simulation is not implemented yet\n", loop.name.c_str());
  return 2;
}

}  // namespace gyrostab::tools
