// The period of a slow oscillation from its upward zero crossings, with hysteresis: armed once the signal is
// below −threshold, a crossing is counted at the first sample ≥ 0 after that (its time by linear
// interpolation). Ripple smaller than the threshold (e.g. a gyro pendulum's nutation, ≲ 2e-7 rad) cannot
// count. Units: t [s], the signal's and the threshold's own. Hot path: O(1), no heap.
// Test: through tests/determinism/scene_determinism_test.cpp (the gyro pendulum's shipped scene).
#pragma once

namespace gyrostab::analysis {

class HysteresisCrossings {
 public:
  explicit HysteresisCrossings(double threshold) : thr_(threshold) {}

  void add(double t, double y) {
    if (y < -thr_) armed_ = true;
    if (has_prev_ && armed_ && prev_y_ < 0.0 && y >= 0.0) {
      const double tc = prev_t_ + (t - prev_t_) * (-prev_y_ / (y - prev_y_));
      if (n_ == 0) first_ = tc;
      last_ = tc;
      ++n_;
      armed_ = false;
    }
    prev_t_ = t;
    prev_y_ = y;
    has_prev_ = true;
  }
  int crossings() const { return n_; }
  // Mean time between the crossings [s]; 0 with fewer than two.
  double period() const { return n_ < 2 ? 0.0 : (last_ - first_) / (n_ - 1); }

 private:
  double thr_;
  bool armed_{false}, has_prev_{false};
  double prev_t_{0.0}, prev_y_{0.0}, first_{0.0}, last_{0.0};
  int n_{0};
};

}  // namespace gyrostab::analysis
