// Drift over a long run of a periodically forced, stable closed loop: once the transient has died out, the
// loop's state at the same phase of the forcing repeats period after period; the largest departure from the
// reference period measures what the run accumulates (integration error, rounding of the time, quantization
// walks) over hours (docs/models/integrators.md): the largest departure so far at 10³, 10⁴, … ticks after the
// reference period (linear drift grows by ×10 per decade, a bounded error does not).
//
// The reference period [from, from + period) is stored (allocation before the loop: period × signals
// doubles); every later tick k is compared with the stored value at (k − from) mod period. The forcing's
// period must be a whole number of ticks (the scene checks it), so the phase is exact.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace gyrostab::analysis {

class PeriodicDrift {
 public:
  static constexpr int kMaxSignals = 4;
  static constexpr int kDecades = 8;  // checkpoints 10³ … 10¹⁰ ticks after the reference period

  PeriodicDrift() = default;
  PeriodicDrift(int signals, std::int64_t period_ticks, std::int64_t from_tick)
      : n_(std::min(signals, kMaxSignals)),
        period_(std::max<std::int64_t>(period_ticks, 1)),
        from_(from_tick),
        reference_(static_cast<std::size_t>(period_ticks * n_), 0.0) {}

  bool enabled() const { return n_ > 0; }

  // The signals at the end of tick k.
  void add(std::int64_t k, const double* v) {
    if (n_ == 0 || k < from_) return;
    const std::int64_t since = k - from_;
    const std::size_t at = static_cast<std::size_t>((since % period_) * n_);
    if (since < period_) {
      for (int i = 0; i < n_; ++i) reference_[at + static_cast<std::size_t>(i)] = v[i];
      return;
    }
    for (int i = 0; i < n_; ++i) {
      const double d = std::abs(v[i] - reference_[at + static_cast<std::size_t>(i)]);
      if (!(d <= worst_[i])) worst_[i] = d;
    }
    const std::int64_t after = since - period_ + 1;  // ticks compared so far
    if (after == next_checkpoint_) {
      double m = 0.0;
      for (int i = 0; i < n_; ++i) m = std::max(m, worst_[i]);
      checkpoints_[decade_] = m;
      checkpoint_ticks_[decade_] = after;
      if (decade_ + 1 < kDecades) ++decade_;
      next_checkpoint_ *= 10;
    }
    compared_ = after;
  }

  double worst(int i) const { return worst_[i]; }
  std::int64_t compared_ticks() const { return compared_; }

  int signals() const { return n_; }
  std::int64_t period_ticks() const { return period_; }
  std::int64_t from_tick() const { return from_; }
  // The largest departure so far at 10³, 10⁴, … compared ticks: how many checkpoints were reached, and each.
  int checkpoints() const {
    int n = 0;
    while (n < kDecades && checkpoint_ticks_[n] > 0) ++n;
    return n;
  }
  std::int64_t checkpoint_ticks(int d) const { return checkpoint_ticks_[d]; }
  double checkpoint_departure(int d) const { return checkpoints_[d]; }

 private:
  int n_{0};
  std::int64_t period_{1};
  std::int64_t from_{0};
  std::vector<double> reference_;
  double worst_[kMaxSignals]{};
  double checkpoints_[kDecades]{};
  std::int64_t checkpoint_ticks_[kDecades]{};
  int decade_{0};
  std::int64_t next_checkpoint_{1000};
  std::int64_t compared_{0};
};

}  // namespace gyrostab::analysis
