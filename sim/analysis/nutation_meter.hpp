// Measures a decaying (or growing) oscillation from a sampled signal, streaming and allocation-free:
// local maxima and minima are refined by a parabola through three samples; each max/min pair gives a
// half-amplitude (max - min)/2 that is insensitive to a slowly moving mean (the precession under a nutation);
// least squares of ln(amplitude) against time gives the growth rate, of the maxima's times against their index
// the period. Used for report.json's measured nutation frequency and decay rate.
#pragma once

#include <cmath>
#include <numbers>

namespace gyrostab::analysis {

class NutationMeter {
 public:
  // Only samples in [t_start, t_end] count.
  NutationMeter(double t_start, double t_end) : t0_(t_start), t1_(t_end) {}

  void add(double t, double y) {
    if (t < t0_ || t > t1_) {
      n_ = 0;
      return;
    }
    if (n_ >= 2) {
      const bool is_max = y1_ > y2_ && y1_ >= y;
      const bool is_min = y1_ < y2_ && y1_ <= y;
      if (is_max || is_min) {
        const double den = y2_ - 2.0 * y1_ + y;
        const double s = den != 0.0 ? 0.5 * (y2_ - y) / den : 0.0;  // vertex offset in samples, |s| ≤ 0.5
        const double value = y1_ - 0.25 * (y2_ - y) * s;
        const double tv = t1s_ + s * (t - t1s_);
        if (is_max) {
          if (have_min_) add_amplitude(tv, 0.5 * (value - last_min_));
          // Period from successive maxima.
          sum_k_ += maxima_;
          sum_kk_ += maxima_ * maxima_;
          sum_t_ += tv;
          sum_kt_ += maxima_ * tv;
          maxima_ += 1.0;
          last_max_ = value;
          have_max_ = true;
        } else {
          if (have_max_) add_amplitude(tv, 0.5 * (last_max_ - value));
          last_min_ = value;
          have_min_ = true;
        }
      }
    }
    y2_ = y1_;
    y1_ = y;
    t1s_ = t;
    ++n_;
  }

  bool valid() const { return maxima_ >= 3 && amps_ >= 3; }
  double angular_frequency() const {
    const double n = maxima_;
    const double period = (n * sum_kt_ - sum_k_ * sum_t_) / (n * sum_kk_ - sum_k_ * sum_k_);
    return 2.0 * std::numbers::pi / period;
  }
  // Growth rate of the amplitude [1/s] (negative: decaying).
  double growth_rate() const {
    const double n = amps_;
    return (n * sum_ta_ - sum_tt_a_ * sum_la_) / (n * sum_tt_ - sum_tt_a_ * sum_tt_a_);
  }

 private:
  void add_amplitude(double t, double a) {
    if (!(a > 0.0)) return;
    const double l = std::log(a);
    sum_tt_a_ += t;
    sum_tt_ += t * t;
    sum_la_ += l;
    sum_ta_ += t * l;
    amps_ += 1.0;
  }

  double t0_, t1_;
  long n_{0};
  double y1_{0.0}, y2_{0.0}, t1s_{0.0};
  double last_max_{0.0}, last_min_{0.0};
  bool have_max_{false}, have_min_{false};
  double maxima_{0.0}, sum_k_{0.0}, sum_kk_{0.0}, sum_t_{0.0}, sum_kt_{0.0};
  double amps_{0.0}, sum_tt_a_{0.0}, sum_tt_{0.0}, sum_la_{0.0}, sum_ta_{0.0};
};

}  // namespace gyrostab::analysis
