// Frequency of an oscillating signal from its upward zero crossings, over whole periods only — averaging over a partial period biases a measured rate by ~1 % (docs/models/rigid-bodies.md#heavy-symmetric-top).
// Crossings are located by cubic Hermite interpolation when the derivative is given (a few samples per
// period suffice: 5 samples of a 200 Hz nutation at 1 kHz), by linear interpolation otherwise.
// Streaming and allocation-free: feed samples in time order.
#pragma once

#include <numbers>

namespace gyrostab::analysis {

class ZeroCrossingMeter {
 public:
  explicit ZeroCrossingMeter(double level = 0.0) : level_(level) {}

  void add(double t, double y) { add(t, y, 0.0, false); }
  void add(double t, double y, double dy) { add(t, y, dy, true); }

  int crossings() const { return crossings_; }
  double first_crossing() const { return first_; }
  double last_crossing() const { return last_; }
  // Angular frequency [rad/s] over the whole periods seen; 0 until two crossings.
  double angular_frequency() const {
    return crossings_ < 2 ? 0.0 : 2.0 * std::numbers::pi * (crossings_ - 1) / (last_ - first_);
  }

 private:
  void add(double t, double y, double dy, bool hermite) {
    const double v = y - level_;
    if (has_prev_ && prev_v_ < 0.0 && v >= 0.0) {
      const double dt = t - prev_t_;
      double s = -prev_v_ / (v - prev_v_);  // linear estimate in [0, 1]
      if (hermite) {
        // p(s) = h00 y0 + h10 dt y0' + h01 y1 + h11 dt y1'; Newton from the linear estimate.
        for (int k = 0; k < 6; ++k) {
          const double s2 = s * s, s3 = s2 * s;
          const double p = (2 * s3 - 3 * s2 + 1) * prev_v_ + (s3 - 2 * s2 + s) * dt * prev_dy_ +
                           (-2 * s3 + 3 * s2) * v + (s3 - s2) * dt * dy;
          const double dp = (6 * s2 - 6 * s) * prev_v_ + (3 * s2 - 4 * s + 1) * dt * prev_dy_ +
                            (-6 * s2 + 6 * s) * v + (3 * s2 - 2 * s) * dt * dy;
          if (dp == 0.0) break;
          s -= p / dp;
        }
        if (!(s >= 0.0 && s <= 1.0)) s = -prev_v_ / (v - prev_v_);
      }
      const double tc = prev_t_ + dt * s;
      if (crossings_ == 0) first_ = tc;
      last_ = tc;
      ++crossings_;
    }
    prev_t_ = t;
    prev_v_ = v;
    prev_dy_ = dy;
    has_prev_ = true;
  }

  double level_;
  double prev_t_{0.0}, prev_v_{0.0}, prev_dy_{0.0};
  bool has_prev_{false};
  int crossings_{0};
  double first_{0.0}, last_{0.0};
};

}  // namespace gyrostab::analysis
