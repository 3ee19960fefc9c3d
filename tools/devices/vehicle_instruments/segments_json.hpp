// report.json "segments" of an instrument on a vehicle: one object per manoeuvre segment with samples
// (sim/analysis/manoeuvre_segment_log.hpp) — segment (1, 2, ...; 0: the final cruise), t_start_s, t_end_s
// (the run's end for the running one) and what the device's fill(json&, const Record&) adds.
#pragma once

#include <nlohmann/json.hpp>

#include "sim/analysis/manoeuvre_segment_log.hpp"

namespace gyrostab::tools {

template <class Record, class Fill>
nlohmann::json segments_json(const analysis::ManoeuvreSegmentLog<Record>& log, double t_now, Fill fill) {
  nlohmann::json segments = nlohmann::json::array();
  log.visit(t_now, [&](int segment, double t_end, const Record& r) {
    nlohmann::json j{{"segment", segment}, {"t_start_s", r.t_start}, {"t_end_s", t_end}};
    fill(j, r);
    segments.push_back(j);
  });
  return segments;
}

}  // namespace gyrostab::tools
