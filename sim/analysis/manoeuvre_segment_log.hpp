// Per-manoeuvre-segment records of an instrument's run over the vehicle's segments
// (sim/motion/vehicle_motion.hpp): which segment a time falls in (index count = the final cruise after the
// last segment), the switch between records at tick ends, and a walk over the records for the report. The
// device's Record derives from SegmentSpan and adds what it measures.
// Times in s (t_start, t_end) and ns (the switch). Hot path (current, advance): no heap.
// Test: through the instruments' shipped scenes (tests/determinism/scene_determinism_test.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "sim/motion/vehicle_motion.hpp"

namespace gyrostab::analysis {

struct SegmentSpan {
  bool started{false}, ended{false};
  double t_start{0.0}, t_end{0.0};  // [s]
  long samples{0};                  // ticks recorded in the segment (the device counts them)
};

template <class Record>
class ManoeuvreSegmentLog {
 public:
  // Opens the segment of t = 0 (the device fills in the rest of its start through current()).
  explicit ManoeuvreSegmentLog(const motion::VehicleMotionParams& m) : m_(m), current_(index_at(0)) {
    Record& r = current();
    r.started = true;
    r.t_start = 0.0;
  }

  int index_at(std::int64_t t_ns) const {
    int k = 0;
    while (k < m_.count && t_ns >= motion::segment_start_ns(m_, k + 1)) ++k;
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

  // visit(segment, t_end, record) for every record with samples, in order: segment = 1, 2, ... (0: the final
  // cruise), t_end = the record's end, or t_now for the running one [s].
  template <class Visit>
  void visit(double t_now, Visit visit) const {
    for (int i = 0; i <= m_.count; ++i) {
      const Record& r = records_[static_cast<std::size_t>(i)];
      if (!r.started || r.samples == 0) continue;
      visit(i + 1 <= m_.count ? i + 1 : 0, r.ended ? r.t_end : t_now, r);
    }
  }

 private:
  const motion::VehicleMotionParams& m_;
  std::array<Record, motion::kMaxVehicleSegments + 1> records_{};
  int current_;
};

}  // namespace gyrostab::analysis
