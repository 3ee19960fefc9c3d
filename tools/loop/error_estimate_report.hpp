// report.json "error_estimate" of a run: the half-step comparison over a sampled window
// (sim/analysis/half_step_window.hpp) with the names of the states it covers and the invariants watched.
#pragma once

#include <array>
#include <nlohmann/json.hpp>

#include "sim/analysis/half_step_window.hpp"

namespace gyrostab::tools {

template <int N>
nlohmann::json error_estimate_json(const analysis::HalfStepEstimate<N>& e, const std::array<const char*, N>& names,
                                   const char* invariants) {
  nlohmann::json j{{"method", "half-step comparison over a sampled window"},
                   {"invariants", invariants},
                   {"integrator", e.integrator},
                   {"order", e.order},
                   {"step_s", e.step_s},
                   {"window_start_s", e.window_start_s},
                   {"window_ticks", e.window_ticks}};
  if (e.window_ticks == 0) {
    j["available"] = false;
    j["why"] = "the run ended before the window";
    return j;
  }
  nlohmann::json errors;
  for (int c = 0; c < N; ++c) errors[names[static_cast<std::size_t>(c)]] = e.max_abs_error[static_cast<std::size_t>(c)];
  j["available"] = true;
  j["reproduces_run"] = e.reproduces_run;
  j["max_abs_error"] = errors;
  if (!e.reproduces_run) j["note"] = "the re-integration at the run's step did not land on the run's states: estimate unreliable";
  return j;
}

}  // namespace gyrostab::tools
