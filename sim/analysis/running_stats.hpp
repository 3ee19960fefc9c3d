// Allocation-free running statistics of a signal for the run report (RMS and peak after a settling time).
#pragma once

#include <cmath>

namespace gyrostab::analysis {

struct RunningStats {
  double sum_sq{0.0};
  double peak{0.0};
  long n{0};
  void add(double v) {
    sum_sq += v * v;
    peak = std::fmax(peak, std::fabs(v));
    ++n;
  }
  double rms() const { return n > 0 ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0; }
};

}  // namespace gyrostab::analysis
