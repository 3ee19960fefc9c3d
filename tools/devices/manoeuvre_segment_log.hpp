// Per-manoeuvre-segment records of an instrument's run over the vehicle's [segmentN] list
// (tools/devices/vehicle_motion_scene.hpp): which segment a time falls in (index count = the final cruise
// after the last segment), the switch between records at tick ends, and the records as the report's
// "segments" array. The device's Record derives from SegmentSpan and adds what it measures.
// Hot path (current, advance): no heap; the JSON is built once after the run.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "tools/devices/vehicle_motion_scene.hpp"

namespace gyrostab::tools {

struct SegmentSpan {
  bool started{false}, ended{false};
  double t_start{0.0}, t_end{0.0};  // [s]
  long samples{0};                  // ticks recorded in the segment (the device counts them)
};

template <class Record>
class ManoeuvreSegmentLog {
 public:
  // Opens the segment of t = 0 (the device fills in the rest of its start through current()).
  explicit ManoeuvreSegmentLog(const VehicleMotionConfig& c) : c_(c), current_(index_at(0)) {
    Record& r = current();
    r.started = true;
    r.t_start = 0.0;
  }

  int index_at(std::int64_t t_ns) const {
    int k = 0;
    while (k < c_.count && t_ns >= segment_start_ns(c_, k + 1)) ++k;
    return k;
  }
  Record& current() { return records_[static_cast<std::size_t>(current_)]; }

  // At the end of a tick (t1_ns; t1 the same in s): if a new segment starts there, closes the current record
  // (ended, t_end, then close(record)) and opens the next (started, t_start, then open(record)).
  template <class Close, class Open>
  void advance(std::int64_t t1_ns, double t1, Close close, Open open) {
    const int seg = index_at(t1_ns);
    if (seg == current_) return;
    Record& old = current();
    old.ended = true;
    old.t_end = t1;
    close(old);
    current_ = seg;
    Record& r = current();
    r.started = true;
    r.t_start = t1;
    open(r);
  }

  // The records with samples as a JSON array: segment (1, 2, ...; 0: the final cruise), t_start_s, t_end_s
  // (t_now for the running one), and what fill(json&, const Record&) adds.
  template <class Fill>
  nlohmann::json to_json(double t_now, Fill fill) const {
    nlohmann::json segs = nlohmann::json::array();
    for (int i = 0; i <= c_.count; ++i) {
      const Record& r = records_[static_cast<std::size_t>(i)];
      if (!r.started || r.samples == 0) continue;
      nlohmann::json j{{"segment", i + 1 <= c_.count ? i + 1 : 0},
                       {"t_start_s", r.t_start},
                       {"t_end_s", r.ended ? r.t_end : t_now}};
      fill(j, r);
      segs.push_back(j);
    }
    return segs;
  }

 private:
  const VehicleMotionConfig& c_;
  std::array<Record, kMaxVehicleSegments + 1> records_{};
  int current_;
};

}  // namespace gyrostab::tools
