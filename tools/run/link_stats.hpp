// Timing statistics of one process of a plant ⇄ controller pair, kept per tick without allocation (the
// histograms are allocated with the struct, before the loop) and written to report.json "timing":
//   period      start-to-start interval of consecutive ticks (real time: ≈ the tick; lockstep: the pace)
//   jitter      |interval − tick period| (real time)
//   lateness    how late the tick started against its deadline (real time, plant: the sleep's wake-up)
//   compute     the process's own work in the tick, waits excluded
//   round_trip  plant: sensor frame published → its command accepted (lockstep: the link's round trip)
//   overruns    ticks whose work ended after their deadline; missed frames: ticks without an accepted frame
#pragma once

#include <cstdint>
#include <cstdlib>

#include "hil/rt/latency_histogram.hpp"

namespace gyrostab::tools {

struct LinkStats {
  hil::LatencyHistogram period, jitter, lateness, compute, round_trip;
  std::uint64_t overruns{0};
  std::int64_t previous_start{-1};

  void tick_started(std::int64_t start_ns, std::int64_t period_ns) {
    if (previous_start >= 0) {
      const std::int64_t interval = start_ns - previous_start;
      period.add(interval);
      jitter.add(std::llabs(interval - period_ns));
    }
    previous_start = start_ns;
  }
};

}  // namespace gyrostab::tools
