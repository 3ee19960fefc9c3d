// Drift over a long run of a periodically forced, stable closed loop: once the transient has died out, the
// loop's state at the same phase of the forcing repeats period after period; the largest departure from the
// reference period measures what the run accumulates (integration error, rounding of the time, quantization
// walks) over hours. numerics.md §2.3/§3.4 style: the largest departure so far at 10³, 10⁴, … ticks after the
// reference period (linear drift grows by ×10 per decade, a bounded error does not).
//
// The reference period [from, from + period) is stored (allocation before the loop: period × signals
// doubles); every later tick k is compared with the stored value at (k − from) mod period. The forcing's
// period must be a whole number of ticks (the scene checks it), so the phase is exact.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

namespace gyrostab::tools {

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

  // `names[i]` labels signal i.
  nlohmann::json report(const char* const* names, double tick_s) const {
    nlohmann::json j{{"period_ticks", period_}, {"reference_from_s", static_cast<double>(from_) * tick_s},
                     {"compared_ticks", compared_}};
    nlohmann::json w = nlohmann::json::object();
    for (int i = 0; i < n_; ++i) w[names[i]] = worst_[i];
    j["max_departure"] = w;
    nlohmann::json c = nlohmann::json::array();
    for (int d = 0; d < kDecades && checkpoint_ticks_[d] > 0; ++d) {
      c.push_back({{"ticks", checkpoint_ticks_[d]}, {"max_departure", checkpoints_[d]}});
    }
    j["max_departure_so_far"] = c;
    return j;
  }

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

}  // namespace gyrostab::tools
