// Identifies one oscillatory mode from a planar signal x = (α, β) sampled every dt: once every other mode has
// died out, x[k+1] = Φ x[k] + b + c k exactly for x = x_eq(t) + the mode, with a slowly moving equilibrium
// (b, c take up x_eq and its drift), and Φ's eigenvalues are e^{λ dt}, e^{λ̄ dt}. A least-squares fit of Φ, b,
// c (a QR of the data matrix) gives λ = ln(μ)/dt: decay −Re λ and frequency |Im λ| of the mode. Unlike a
// recurrence of α alone, whose many lags sampled slowly turn a small coloured noise into a large bias of the
// roots, the eight unknowns here stand against hundreds of samples: a noise σ against a transient S moves λ
// by O(σ²/S²). Φ is a general 2×2 matrix: the mode need not be circular (unequal axes, couplings).
// Docs: docs/sampled-data.md. Host only: the buffer is reserved at construction, add() never allocates.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace gyrostab::analysis {

class PlanarModeFit {
 public:
  PlanarModeFit() = default;
  // Samples in [t_start, t_end] every dt (the first 1e7 at most); the caller bounds t_end by the run's end.
  PlanarModeFit(double t_start, double t_end, double dt);
  void add(double t, double a, double b) {
    if (t < t0_ || t > t1_ || x_.size() >= x_.capacity()) return;
    x_.push_back({a, b});
  }
  bool valid() const { return x_.size() >= 12; }
  // λ with Im λ ≥ 0 [1/s] (NaN when not valid; a real pair gives the slower root).
  std::complex<double> root() const;
  // Both of Φ's roots ln(μ)/dt [1/s] (a conjugate or a real pair; NaN when not valid): near a double root,
  // where each alone is ill-conditioned, their sum and product are not.
  struct Pair {
    std::complex<double> first, second;
  };
  Pair pair() const;
  std::size_t samples() const { return x_.size(); }

 private:
  struct Sample {
    double a, b;
  };
  double t0_{0.0}, t1_{-1.0}, dt_{1.0};
  std::vector<Sample> x_;
};

}  // namespace gyrostab::analysis
