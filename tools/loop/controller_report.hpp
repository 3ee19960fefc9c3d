// The firmware controller's self-measurement for report.json's "timing": per-task counters of the
// scheduler (runs, compute time min/mean/max, overruns, start-to-start interval) and the fault monitor's
// counters. Compute times come from the controller's clock (CLOCK_MONOTONIC in `gyrostab run`); they vary
// run to run and are kept out of "figures", which must be bit-identical.
#pragma once

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "firmware/control/config_check.hpp"

#include "firmware/fault/fault_monitor.hpp"
#include "firmware/scheduler/perf_counter.hpp"

namespace gyrostab::tools {

inline nlohmann::json perf_json(const firmware::PerfCounter& c) {
  return {{"runs", c.runs},         {"overruns", c.overruns},
          {"compute_min_ns", c.min_ns}, {"compute_mean_ns", c.mean_ns()},
          {"compute_max_ns", c.max_ns}, {"interval_min_ns", c.interval_min_ns},
          {"interval_max_ns", c.interval_max_ns}};
}

inline nlohmann::json fault_json(const firmware::FaultCounters& f) {
  return {{"good_frames", f.good_frames}, {"missing", f.missing},         {"stale", f.stale},
          {"non_finite", f.non_finite},   {"out_of_range", f.out_of_range}, {"sensor_reported", f.sensor_reported},
          {"frames_lost", f.frames_lost}, {"held_ticks", f.held_ticks},   {"safe_ticks", f.safe_ticks},
          {"trips", f.trips},             {"recoveries", f.recoveries},     {"acknowledgements_refused", f.acknowledgements_refused}};
}

// A refused start-up check as one line: the reason, the offending value and the computed bounds.
inline std::string describe(const firmware::ConfigCheck& c) {
  std::ostringstream s;
  s << c.reason;
  if (c.value != 0.0 || c.lower != 0.0 || c.upper != 0.0) {
    s << " (value " << c.value;
    if (c.lower != 0.0) s << ", lower bound " << c.lower;
    if (c.upper != 0.0) s << ", upper bound " << c.upper;
    s << ")";
  }
  return s.str();
}

// The scene check's message when the controller's start-up check (Controller::check) refuses the scene's
// controller configuration; "" when it accepts. A schema::Rule over any scene struct with a `controller`.
template <class Controller, class Scene>
std::string controller_refusal(const Scene& s) {
  const firmware::ConfigCheck check = Controller::check(s.controller);
  return check.ok ? "" : "refused by the controller's start-up check: " + describe(check);
}

template <class Controller>
nlohmann::json controller_report(const Controller& c) {
  return {{"tick", perf_json(c.tick_counters())},
          {"control_task", perf_json(c.control_counters())},
          {"drive_task", perf_json(c.drive_counters())},
          {"fault_monitor", fault_json(c.fault_counters())}};
}

}  // namespace gyrostab::tools
