// Allocation-free mean of a signal over the ticks [from, to) of a run, for the run report (e.g. a steady lean
// measured over the last second of a constant load); empty when no tick fell inside. Test: no test of its own
// yet; the monorail's lean figures (sim/scenes/monorail.toml in tests/determinism) read it.
#pragma once

#include <cstdint>
#include <optional>

namespace gyrostab::analysis {

struct WindowMean {
  std::int64_t from{0}, to{0};
  double sum{0.0};
  std::int64_t n{0};

  void add(std::int64_t tick, double v) {
    if (tick >= from && tick < to) {
      sum += v;
      ++n;
    }
  }
  std::optional<double> mean() const {
    if (n == 0) return std::nullopt;
    return sum / static_cast<double>(n);
  }
};

}  // namespace gyrostab::analysis
