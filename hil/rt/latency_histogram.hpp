// A fixed-bin histogram of durations for real-time statistics (tick-start lateness, compute time, period):
// 1 µs bins up to 20 ms plus an overflow count, min/max kept exactly. Percentiles are read off the bins, so
// they are exact to 1 µs below 20 ms; above it the exact max is reported and the percentile says "≥ 20 ms".
// Storage is a member array sized at compile time (160 KB): no allocation per sample, O(1) add.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

namespace gyrostab::hil {

class LatencyHistogram {
 public:
  static constexpr std::int64_t kBinNs = 1000;
  static constexpr int kBins = 20000;

  void add(std::int64_t ns) {
    if (ns < 0) ns = 0;
    ++count_;
    sum_ns_ += ns;
    if (ns < min_ns_) min_ns_ = ns;
    if (ns > max_ns_) max_ns_ = ns;
    const std::int64_t b = ns / kBinNs;
    if (b >= kBins) {
      ++overflow_;
    } else {
      ++bins_[static_cast<std::size_t>(b)];
    }
  }

  std::uint64_t count() const { return count_; }
  std::int64_t min_ns() const { return count_ ? min_ns_ : 0; }
  std::int64_t max_ns() const { return max_ns_; }
  double mean_ns() const { return count_ ? static_cast<double>(sum_ns_) / static_cast<double>(count_) : 0.0; }

  // The upper edge of the bin holding the q-quantile (0 < q ≤ 1) [ns]; the exact max if it lies in the
  // overflow; 0 without samples.
  std::int64_t quantile_ns(double q) const {
    if (count_ == 0) return 0;
    const auto rank = static_cast<std::uint64_t>(q * static_cast<double>(count_ - 1)) + 1;
    std::uint64_t seen = 0;
    for (int b = 0; b < kBins; ++b) {
      seen += bins_[static_cast<std::size_t>(b)];
      if (seen >= rank) {
        const std::int64_t edge = (b + 1) * kBinNs;
        return edge < max_ns_ ? edge : max_ns_;
      }
    }
    return max_ns_;
  }

 private:
  std::array<std::uint32_t, kBins> bins_{};
  std::uint64_t count_{0};
  std::uint64_t overflow_{0};
  std::int64_t sum_ns_{0};
  std::int64_t min_ns_{std::numeric_limits<std::int64_t>::max()};
  std::int64_t max_ns_{0};
};

}  // namespace gyrostab::hil
