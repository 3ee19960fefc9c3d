// Period, decay and equilibrium of a slow damped oscillation from its extrema: each local extremum of the
// sampled signal is located by a parabola through the sample at it and its two neighbours; for
// x(t) = x_eq + A e^(−σt) cos(ω t + φ) the extrema are exactly π/ω apart (half a period) and alternate about
// x_eq with ratio −e^(−σπ/ω), so
//   period  T = 2 (t_last − t_first)/(n − 1)           (whole half-periods)
//   x_eq    = (e0 e2 − e1²)/(e0 + e2 − 2 e1)          (Aitken's Δ² on three successive extrema)
//   σ       = −ln(|e2 − x_eq| / |e1 − x_eq|) / (t2 − t1)
// Hysteresis h ≥ 0: a maximum counts only once the signal has fallen more than h below it (a minimum: risen
// more than h above it), and maxima and minima alternate — so noise and a ripple (e.g. a nutation riding on
// a precession) smaller than h, or an oscillation decayed below h, add no extrema.
// Used for the gyrocompass's (13.12) and the platform's Schuler period (16.38) in scenes and tests.
// Streaming, allocation-free: feed samples in time order; stores the first kMax extrema.
#pragma once

#include <cmath>

namespace gyrostab::analysis {

template <int kMax = 64>
class ExtremaMeter {
 public:
  explicit ExtremaMeter(double hysteresis = 0.0) : hyst_(hysteresis) {}

  void add(double t, double y) {
    if (n_ == 0) {
      set_candidate(t, y);
      prev_t_ = t;
      prev_y_ = y;
      ++n_;
      return;
    }
    if (need_next_) {  // the sample right after the candidate, for the parabola
      next_t_ = t;
      next_y_ = y;
      need_next_ = false;
    }
    if (dir_ == 0) {  // direction not yet known: follow the signal away from the first sample
      if (y > c_y_ + hyst_ || y < c_y_ - hyst_) {
        dir_ = y > c_y_ ? +1 : -1;  // rising: look for a maximum
        set_candidate(t, y);
      }
    } else if ((dir_ > 0 && y > c_y_) || (dir_ < 0 && y < c_y_)) {
      set_candidate(t, y);
    } else if ((dir_ > 0 && y < c_y_ - hyst_) || (dir_ < 0 && y > c_y_ + hyst_)) {
      confirm();
      dir_ = -dir_;
      set_candidate(t, y);
    }
    prev_t_ = t;
    prev_y_ = y;
    ++n_;
  }

  int count() const { return count_; }
  double time(int i) const { return t_[i]; }
  double value(int i) const { return v_[i]; }

  // From extrema first..last (inclusive, last < count()); 0 when fewer than two.
  double period(int first, int last) const {
    return last > first ? 2.0 * (t_[last] - t_[first]) / static_cast<double>(last - first) : 0.0;
  }
  double period() const { return count_ >= 2 ? period(0, count_ - 1) : 0.0; }
  // Equilibrium and decay rate from extrema i, i + 1, i + 2.
  double equilibrium(int i) const {
    const double e0 = v_[i], e1 = v_[i + 1], e2 = v_[i + 2];
    const double den = e0 + e2 - 2.0 * e1;
    return den != 0.0 ? (e0 * e2 - e1 * e1) / den : e1;
  }
  double decay_rate(int i) const {
    const double x = equilibrium(i);
    return -std::log(std::fabs(v_[i + 2] - x) / std::fabs(v_[i + 1] - x)) / (t_[i + 2] - t_[i + 1]);
  }

 private:
  void set_candidate(double t, double y) {
    b_t_ = prev_t_;
    b_y_ = prev_y_;
    has_before_ = n_ > 0;
    c_t_ = t;
    c_y_ = y;
    need_next_ = true;
  }
  void confirm() {
    if (count_ >= kMax) return;
    double te = c_t_, ye = c_y_;
    if (has_before_ && !need_next_) {
      // Parabola through (b, c, next): vertex.
      const double h0 = c_t_ - b_t_, h1 = next_t_ - c_t_;
      const double d0 = (c_y_ - b_y_) / h0, d1 = (next_y_ - c_y_) / h1;
      const double a = (d1 - d0) / (h0 + h1);                     // y'' / 2
      const double slope = (d0 * h1 + d1 * h0) / (h0 + h1);       // y'(t_c)
      if (a != 0.0) {
        const double dt = -slope / (2.0 * a);
        if (std::fabs(dt) <= 0.5 * (h0 + h1)) {
          te = c_t_ + dt;
          ye = c_y_ + slope * dt + a * dt * dt;
        }
      }
    }
    t_[count_] = te;
    v_[count_] = ye;
    ++count_;
  }

  double hyst_;
  long n_{0};
  int dir_{0};  // +1: looking for a maximum, −1: a minimum, 0: unknown yet
  double prev_t_{0.0}, prev_y_{0.0};
  double b_t_{0.0}, b_y_{0.0}, c_t_{0.0}, c_y_{0.0}, next_t_{0.0}, next_y_{0.0};
  bool has_before_{false}, need_next_{false};
  int count_{0};
  double t_[kMax]{}, v_[kMax]{};
};

}  // namespace gyrostab::analysis
