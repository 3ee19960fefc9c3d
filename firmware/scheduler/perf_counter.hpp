// Performance counter for one periodic task (PX4's perf_begin/perf_end + perf_count in one): how often it
// ran, how long each run took (min/mean/max), how often it exceeded its budget, and the start-to-start
// interval (period and jitter in real-time runs). Plain data, O(1) per record, no heap.
#pragma once

#include <cstdint>

namespace gyrostab::firmware {

struct PerfCounter {
  std::uint64_t runs{0};            // completed runs [-]
  std::uint64_t overruns{0};        // runs whose compute time exceeded the budget [-]
  std::int64_t total_ns{0};         // sum of compute times [ns]
  std::int64_t min_ns{0};           // shortest compute time; 0 until the first run [ns]
  std::int64_t max_ns{0};           // longest compute time [ns]
  std::int64_t last_ns{0};          // compute time of the latest run [ns]
  std::int64_t interval_min_ns{0};  // shortest start-to-start interval; 0 until the second run [ns]
  std::int64_t interval_max_ns{0};  // longest start-to-start interval [ns]
  std::int64_t last_start_ns{0};    // clock reading at the start of the latest run [ns]

  // Adds one run that started at `start_ns` and took `compute_ns`. A budget ≤ 0 means "no budget": the run
  // is never an overrun. O(1).
  constexpr void record(std::int64_t start_ns, std::int64_t compute_ns, std::int64_t budget_ns) {
    if (runs == 0) {
      min_ns = max_ns = compute_ns;
    } else {
      const std::int64_t interval = start_ns - last_start_ns;
      if (runs == 1 || interval < interval_min_ns) interval_min_ns = interval;
      if (runs == 1 || interval > interval_max_ns) interval_max_ns = interval;
      if (compute_ns < min_ns) min_ns = compute_ns;
      if (compute_ns > max_ns) max_ns = compute_ns;
    }
    ++runs;
    total_ns += compute_ns;
    last_ns = compute_ns;
    last_start_ns = start_ns;
    if (budget_ns > 0 && compute_ns > budget_ns) ++overruns;
  }

  // Mean compute time, truncated to whole nanoseconds; 0 before the first run [ns].
  constexpr std::int64_t mean_ns() const {
    return runs == 0 ? 0 : total_ns / static_cast<std::int64_t>(runs);
  }
};

}  // namespace gyrostab::firmware
