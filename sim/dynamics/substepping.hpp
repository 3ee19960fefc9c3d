// Integer time: the loop counts controller ticks; the plant takes an integer number of equal sub-steps per
// tick. Time is computed from the integer tick and the integer period in nanoseconds, never accumulated.
// Docs: docs/models/integrators.md
#pragma once

#include <cstdint>

namespace gyrostab::dynamics {

template <class Integrator>
class SubstepDriver {
 public:
  using State = typename Integrator::State;

  SubstepDriver(Integrator& integrator, std::int64_t tick_ns, int substeps)
      : integrator_(integrator), tick_ns_(tick_ns), substeps_(substeps < 1 ? 1 : substeps),
        h_(1e-9 * static_cast<double>(tick_ns) / substeps_) {}

  // Advance the state from the start of `tick` to the start of `tick + 1`.
  void advance_tick(std::int64_t tick, State& x) {
    const double t0 = 1e-9 * static_cast<double>(tick * tick_ns_);
    for (int k = 0; k < substeps_; ++k) integrator_.step(t0 + k * h_, h_, x);
  }

  double substep() const { return h_; }
  int substeps() const { return substeps_; }
  std::int64_t tick_ns() const { return tick_ns_; }

 private:
  Integrator& integrator_;
  std::int64_t tick_ns_;
  int substeps_;
  double h_;
};

}  // namespace gyrostab::dynamics
