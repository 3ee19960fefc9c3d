// Irregular long-crested sea synthesized from a wave spectrum (wave_spectrum.hpp) as a fixed-capacity sum of
// N ≤ MaxComponents harmonics, passed through a linear transfer (wave_transfer.hpp): the irregular
// counterpart of Magnus's wave moment E(t) = E0 cos ωt (14.9) that drives the ship roll damper (14.8).
//
//   y(t) = Σᵢ bᵢ cos(ωᵢ t + ψᵢ),   ẏ(t) = −Σᵢ ωᵢ bᵢ sin(ωᵢ t + ψᵢ)
//   band [ω_lo, ω_hi] cut into N equal bins of width Δω; component i:
//     ωᵢ = centre of bin i + jitter·(u₁ − ½)·Δω          (u₁ uniform: breaks the 2π/Δω repeat period;
//                                                          seen at ωᵢ − (ωᵢ²/g) V by an observer moving at V
//                                                          along the waves: velocity_along_waves)
//     aᵢ = √(2 ∫_bin S dω)                                (elevation amplitude [m]: the bin's whole energy)
//     φᵢ = 2π u₂                                          (random phase)
//     bᵢ = |H(ωᵢ)| aᵢ,  ψᵢ = φᵢ + arg H(ωᵢ)                (transfer H: elevation, slope, roll moment, RAO)
//   so the output variance is Σ bᵢ²/2, and for H = 1 it is ∫_band S dω (= m0 less the tails outside the
//   band). Draw order (determinism): for i = 0..N−1: u₁ then u₂ — 2N uniforms from the caller's generator.
//   Default band [0.5 ωp, 5 ωp]: holds 99.8 % of PM's m0 (its energy above ω is m0 (1 − exp(−1.25 (ωp/ω)⁴))).
//
// Evaluation:
//   at(t)        direct sum, N sin/cos — any t, const, exact to rounding (~0.7 µs for N = 64).
//   sample(n)    y and ẏ at t = n·dt on the grid of `grid_period` dt: unit phasors zᵢ = exp(i(ωᵢ t + ψᵢ)) are
//                rotated by the precomputed ρᵢ = exp(i ωᵢ dt) (4 multiplies and 2 adds per component, no
//                libm, summed in the same pass), and re-anchored exactly from the integer index (zᵢ =
//                exp(i(ωᵢ·(n·dt)
//                + ψᵢ)), t = n·dt with one rounding, never accumulated) whenever n is a multiple of
//                kAnchorInterval = 1024. The result is a pure function of n — a jump to another n replays
//                from that block's anchor with the same step() — so it does not depend on the call history,
//                and the rotation error is bounded by 1024 steps (measured ≤ 1.2e-14 Σbᵢ) however long the
//                run. Samples n and n − 1 are cached.
//   sample_at(t), operator()(t)   on the grid (to 16 ulps of t/dt): sample(n); between grid points: the cubic
//                Hermite interpolant of the neighbouring samples' values and rates, error ≤ dt⁴/384 Σ bᵢωᵢ⁴
//                (≈ 4e-13 Σbᵢ for ωᵢ ≤ 3.5 rad/s, dt = 1 ms). With dt = the plant step h, an RK4 step's
//                stages t, t + h/2, t + h cost one phasor step; a plant RHS can call operator()(t) directly.
//                The phasors and cache are `mutable`: one sea per loop/thread.
//
// Parameters: MaxComponents (capacity), N = components ≥ 1, band [rad/s], jitter ∈ [0, 1], grid_period [s] >
// 0. Hot path (sample, sample_at, operator()): allocation-free, O(N) multiply-adds, plus N sincos every 1024
// steps. Tests: tests/oracle/wave_spectrum_test.cpp (sample variance vs m0),
// tests/determinism/motion_determinism_test.cpp, tests/alloc/motion_alloc_test.cpp,
// tests/unit/base_motion_generators_test.cpp (grid vs direct).
// Docs: docs/models/suspension-motion.md#waves
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>

#include "sim/motion/wave_spectrum.hpp"
#include "sim/motion/wave_transfer.hpp"
#include "sim/random/seeded_rng.hpp"

namespace gyrostab::motion {

struct IrregularSeaParams {
  int components{64};        // N [-], 1 ≤ N ≤ MaxComponents
  double omega_min{0.0};     // lower band edge [rad/s]; 0 ⇒ 0.5 ωp
  double omega_max{0.0};     // upper band edge [rad/s]; 0 ⇒ 5 ωp
  double jitter{1.0};        // fraction of a bin over which ωᵢ is drawn [-]
  double grid_period{1e-3};  // dt of the sample(n) grid [s]
  // V: the observer's velocity along the waves' direction of travel [m/s] (ship_course.hpp); each component
  // is then seen at its encounter frequency ωᵢ − (ωᵢ²/g) V, the transfer still evaluated at the wave's ωᵢ.
  double velocity_along_waves{0.0};
};

struct WaveSample {
  double value{0.0};  // y [output unit: m, rad, N m, ...]
  double rate{0.0};   // dy/dt [output unit / s]
};

template <int MaxComponents = 128>
class IrregularSea {
  static_assert(MaxComponents >= 1);
  static constexpr int kCapacity = (MaxComponents + 3) / 4 * 4;  // padded to whole groups of 4

 public:
  static constexpr int kAnchorInterval = 1024;

  static const char* check(const IrregularSeaParams& p) {
    if (p.components < 1 || p.components > MaxComponents)
      return "irregular sea: components must be in [1, capacity]";
    if (p.omega_min < 0.0 || (p.omega_max != 0.0 && !(p.omega_max > p.omega_min)))
      return "irregular sea: band must satisfy 0 <= omega_min < omega_max";
    if (!(p.jitter >= 0.0 && p.jitter <= 1.0)) return "irregular sea: jitter must be in [0, 1]";
    if (!(p.grid_period > 0.0)) return "irregular sea: grid_period must be > 0 s";
    if (!std::isfinite(p.velocity_along_waves)) return "irregular sea: velocity_along_waves must be finite";
    return nullptr;
  }

  template <class Transfer = ElevationTransfer>
  IrregularSea(const WaveSpectrum& spectrum, const IrregularSeaParams& p, random::SeededRng& rng,
               const Transfer& transfer = {})
      : n_(std::clamp(p.components, 1, MaxComponents)),
        dt_(p.grid_period) {  // clamp: memory-safe even unchecked
    const double wp = spectrum.peak_frequency();
    lo_ = p.omega_min > 0.0 ? p.omega_min : 0.5 * wp;
    hi_ = p.omega_max > 0.0 ? p.omega_max : 5.0 * wp;
    const double dw = (hi_ - lo_) / n_;
    for (int i = 0; i < n_; ++i) {
      const double u1 = rng.uniform();
      const double u2 = rng.uniform();
      const double bin_lo = lo_ + i * dw;
      const double w = bin_lo + (0.5 + p.jitter * (u1 - 0.5)) * dw;
      const double a = std::sqrt(2.0 * spectrum.integral(bin_lo, bin_lo + dw));
      const std::complex<double> h = transfer(w);
      const double we = w - w * w / kStandardGravity * p.velocity_along_waves;
      omega_[i] = we;
      elevation_amplitude_[i] = a;
      amplitude_[i] = std::abs(h) * a;
      phase_[i] = 2.0 * std::numbers::pi * u2 + std::arg(h);
      rate_coeff_[i] = -we * amplitude_[i];
      rot_re_[i] = std::cos(we * dt_);
      rot_im_[i] = std::sin(we * dt_);
      band_variance_ += 0.5 * a * a;
      output_variance_ += 0.5 * amplitude_[i] * amplitude_[i];
    }
    // Padding slots keep amplitude 0 and rotate by 1: they add exact zeros.
    for (int i = n_; i < kCapacity; ++i) rot_re_[i] = 1.0;
    groups_ = (n_ + 3) / 4;
  }

  int size() const { return n_; }
  double band_lo() const { return lo_; }
  double band_hi() const { return hi_; }
  double grid_period() const { return dt_; }
  double frequency(int i) const { return omega_[i]; }  // ωᵢ as seen: encounter frequency if V ≠ 0 [rad/s]
  double elevation_amplitude(int i) const { return elevation_amplitude_[i]; }  // aᵢ [m]
  double amplitude(int i) const { return amplitude_[i]; }                      // bᵢ [output unit]
  double phase(int i) const { return phase_[i]; }                              // ψᵢ [rad]
  double band_variance() const { return band_variance_; }      // Σ aᵢ²/2 = ∫_band S [m²]
  double output_variance() const { return output_variance_; }  // Σ bᵢ²/2 [output unit²]

  // Direct evaluation at any t [s].
  WaveSample at(double t) const {
    WaveSample s;
    for (int i = 0; i < n_; ++i) {
      const double th = omega_[i] * t + phase_[i];
      s.value += amplitude_[i] * std::cos(th);
      s.rate += rate_coeff_[i] * std::sin(th);
    }
    return s;
  }

  // Grid evaluation at t = n·dt (see the header). Logically const: the phasors are a cache.
  const WaveSample& sample(std::int64_t n) const {
    if (has_cur_ && n == n_cur_) return cur_;
    if (has_prev_ && n == n_cur_ - 1) return prev_;
    const bool follows = has_cur_ && n == n_cur_ + 1;
    if (follows) prev_ = cur_;
    has_prev_ = follows;
    if (follows && floor_mod(n) != 0) {
      cur_ = step();  // the same step() as a replay: bit-identical either way
    } else {
      const std::int64_t n0 = n - floor_mod(n);
      anchor(n0);
      cur_ = sum();
      for (std::int64_t k = n0; k < n; ++k) cur_ = step();
    }
    n_cur_ = n;
    has_cur_ = true;
    return cur_;
  }

  // y and ẏ at any t [s]: sample(n) on the grid (within the rounding of t), else the cubic Hermite
  // interpolant of the two neighbouring grid samples (values and rates), |error| ≤ dt⁴/384 Σ bᵢωᵢ⁴ (ẏ:
  // O(dt³)).
  WaveSample sample_at(double t) const {
    const double x = t / dt_;
    if (!(std::abs(x) < 4.0e18)) return at(t);
    const double fl = std::floor(x), s = x - fl;
    const auto n = static_cast<std::int64_t>(fl);
    // Snap only within the rounding of t itself (16 ulps of x), so snapping never costs accuracy.
    const double snap = 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(x));
    if (s <= snap) return sample(n);
    if (s >= 1.0 - snap) return sample(n + 1);
    const WaveSample a = sample(n);
    const WaveSample b = sample(n + 1);
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d11 = 3 * s2 - 2 * s;
    return {h00 * a.value + h10 * dt_ * a.rate + h01 * b.value + h11 * dt_ * b.rate,
            (d00 * (a.value - b.value)) / dt_ + d10 * a.rate + d11 * b.rate};
  }

  // y(t) [output unit], for a plant's right-hand side.
  double operator()(double t) const { return sample_at(t).value; }

 private:
  static std::int64_t floor_mod(std::int64_t n) {
    const std::int64_t r = n % kAnchorInterval;
    return r < 0 ? r + kAnchorInterval : r;
  }

  void anchor(std::int64_t n0) const {
    const double t0 = static_cast<double>(n0) * dt_;
    for (int i = 0; i < n_; ++i) {
      const double th = omega_[i] * t0 + phase_[i];
      re_[i] = std::cos(th);
      im_[i] = std::sin(th);
    }
  }

  // Four interleaved partial sums (lane = i mod 4) combined in a fixed order: vectorizable and deterministic.
  WaveSample sum() const {
    double v[4] = {0, 0, 0, 0}, d[4] = {0, 0, 0, 0};
    for (int g = 0; g < groups_; ++g) {
      for (int l = 0; l < 4; ++l) {
        const int i = 4 * g + l;
        v[l] += amplitude_[i] * re_[i];
        d[l] += rate_coeff_[i] * im_[i];
      }
    }
    return {(v[0] + v[1]) + (v[2] + v[3]), (d[0] + d[1]) + (d[2] + d[3])};
  }

  // z ← z ρ for every component, summing y and ẏ in the same pass. Written with two-double vectors (GCC/clang
  // vector extension, SSE2 on x86-64): lanes 0-1 and 2-3 of each group of 4, lane l only ever added to lane
  // l, so the result is bit-identical to the scalar loop over i with sums v[i mod 4] (no FMA: baseline x86-64
  // has none). GCC -O2 kept that scalar loop's lane sums in memory and did not vectorize it: this is ~2x
  // fewer instructions, +20 % ticks/s on the ship scene (tools/bench/scene_bench.cpp).
  WaveSample step() const {
    using V2 = double __attribute__((vector_size(16)));
    const auto load = [](const double* p) {
      V2 x;
      std::memcpy(&x, p, sizeof x);
      return x;
    };
    V2 v01{}, v23{}, d01{}, d23{};
    const auto pair = [&](int i, V2& v, V2& d) {
      const V2 re = load(re_.data() + i), im = load(im_.data() + i);
      const V2 cr = load(rot_re_.data() + i), ci = load(rot_im_.data() + i);
      const V2 r = re * cr - im * ci;
      const V2 m = re * ci + im * cr;
      std::memcpy(re_.data() + i, &r, sizeof r);
      std::memcpy(im_.data() + i, &m, sizeof m);
      v += load(amplitude_.data() + i) * r;
      d += load(rate_coeff_.data() + i) * m;
    };
    for (int i = 0; i < 4 * groups_; i += 4) {
      pair(i, v01, d01);
      pair(i + 2, v23, d23);
    }
    return {(v01[0] + v01[1]) + (v23[0] + v23[1]), (d01[0] + d01[1]) + (d23[0] + d23[1])};
  }

  using Array = std::array<double, kCapacity>;
  int n_;
  int groups_{0};
  double dt_;
  double lo_{0.0}, hi_{0.0};
  double band_variance_{0.0}, output_variance_{0.0};
  Array omega_{}, elevation_amplitude_{}, amplitude_{}, phase_{}, rate_coeff_{};
  Array rot_re_{}, rot_im_{};
  mutable Array re_{}, im_{};
  mutable WaveSample cur_{}, prev_{};  // samples n_cur_ and n_cur_ − 1
  mutable std::int64_t n_cur_{0};
  mutable bool has_cur_{false}, has_prev_{false};
};

}  // namespace gyrostab::motion
