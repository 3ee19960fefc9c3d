// Identifies a sampled linear loop's roots from its recorded signals: the samples y[k] (uniform, every dt) of a
// loop w[k+1] = M w[k] + N v[k] under a constant input obey the recurrence (ARX)
//   y[k] = a_1 y[k−1] + … + a_n y[k−n] + Σ_ch Σ_{j=0..n} b_{ch,j} v_ch[k−j] + c
// (n ≥ the order the signal sees; c: the new equilibrium; v: inputs the run knows sample by sample, such as
// the sensor errors the firmware saw), whose characteristic roots z are eigenvalues of M. A least-squares fit
// over the window (a QR of the data matrix, not the normal equations, whose condition is the square) gives them;
// s = ln(z)/dt maps them back to decay rate and frequency as the `_predicted_sampled` figures do
// (sampled_loop_roots.hpp).
// Why the inputs: a sensor noise that the law feeds back reaches y through the plant's hold and latency — a
// coloured equation error that biases a fit of y alone by ~1 % on a nutation's decay (and scatters it from seed
// to seed). With the noise samples as regressors the recurrence is exact and the fit recovers M's roots to
// round-off. An over-large n is harmless: the extra roots take up what is left (a slow base motion's forced
// response) and the mode sought is taken as the root nearest its prediction (nearest_root).
// Docs: docs/sampled-data.md. Host only: the fit allocates; the meter's buffer is reserved at construction and
// add() never allocates.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace gyrostab::analysis {

// The roots s = ln(z)/dt of the recurrence fitted to y[0..count) with `channels` inputs v (row k at
// v[k·channels]; null when channels = 0), z = 0 left out. Empty when count is too short for the regressors.
std::vector<std::complex<double>> linear_prediction_roots(const double* y, const double* v, int channels,
                                                          std::size_t count, int order, double dt);

// Collects y(t) and the inputs v(t) in [t_start, t_end] every dt (the first 1e7 samples at most), for
// linear_prediction_roots at the end. The caller bounds t_end by the run's end: the buffer is sized from it.
class LinearPredictionMeter {
 public:
  LinearPredictionMeter(double t_start, double t_end, double dt, int order, int channels = 0);
  void add(double t, double y, const double* v = nullptr) {
    if (t < t0_ || t > t1_ || y_.size() >= y_.capacity()) return;
    y_.push_back(y);
    for (int i = 0; i < channels_; ++i) v_.push_back(v != nullptr ? v[i] : 0.0);
  }
  bool valid() const;
  std::vector<std::complex<double>> roots() const;
  std::size_t samples() const { return y_.size(); }

 private:
  std::size_t min_samples() const;
  double t0_, t1_, dt_;
  int order_, channels_;
  std::vector<double> y_, v_;
};

}  // namespace gyrostab::analysis
