// How a closed-loop run ended, for every run mode: ticks run, divergence (where, for a plant that names its
// state: tools/loop/state_guard.hpp), wall time, and whether a tick sink stopped it.
#pragma once

#include <cstdint>

#include "tools/loop/state_guard.hpp"

namespace gyrostab::tools {

struct LoopOutcome {
  std::int64_t ticks_run{0};
  bool diverged{false};           // the plant state became non-finite
  std::int64_t diverged_tick{-1};
  NonFiniteState diverged_state{};  // which component, its value and last finite value
  double wall_s{0.0};
  double cpu_s{0.0};              // the loop thread's CPU time (in process; 0 where not measured)
  bool interrupted{false};        // stopped at a tick boundary by the tick sink (stop signal, failed log write)
};

}  // namespace gyrostab::tools
