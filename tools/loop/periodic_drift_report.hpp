// report.json "drift" of a run with the periodic-drift monitor (sim/analysis/periodic_drift.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include "sim/analysis/periodic_drift.hpp"

namespace gyrostab::tools {

// `names[i]` labels signal i.
inline nlohmann::json periodic_drift_json(const analysis::PeriodicDrift& d, const char* const* names, double tick_s) {
  nlohmann::json j{{"period_ticks", d.period_ticks()},
                   {"reference_from_s", static_cast<double>(d.from_tick()) * tick_s},
                   {"compared_ticks", d.compared_ticks()}};
  nlohmann::json w = nlohmann::json::object();
  for (int i = 0; i < d.signals(); ++i) w[names[i]] = d.worst(i);
  j["max_departure"] = w;
  nlohmann::json c = nlohmann::json::array();
  for (int k = 0; k < d.checkpoints(); ++k) {
    c.push_back({{"ticks", d.checkpoint_ticks(k)}, {"max_departure", d.checkpoint_departure(k)}});
  }
  j["max_departure_so_far"] = c;
  return j;
}

}  // namespace gyrostab::tools
