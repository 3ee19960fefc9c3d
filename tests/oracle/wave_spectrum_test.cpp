// Oracles for the wave spectra (DNV-RP-C205 §3.5.5 forms, sim/motion/wave_spectrum.hpp) and for the irregular
// sea synthesized from them (sim/motion/irregular_sea.hpp).
#include "sim/motion/wave_spectrum.hpp"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sim/motion/irregular_sea.hpp"

namespace gyrostab {
namespace wave_spectrum_test {

using motion::WaveSpectrum;
using motion::WaveSpectrumParams;
using Kind = WaveSpectrumParams::Kind;

WaveSpectrumParams pm(double Hs, double Tp) {
  return {Kind::kPiersonMoskowitz, Hs, Tp, 1.0, 0.07, 0.09};
}
WaveSpectrumParams jonswap(double Hs, double Tp, double gamma) {
  return {Kind::kJonswap, Hs, Tp, gamma, 0.07, 0.09};
}

// ∫₀^∞ S dω by adaptive 61-point Gauss-Kronrod, split at ωp (JONSWAP's σ switches there) and mapped to
// [ωp, ∞) by Boost's own change of variables — independent of the model's closed form and Simpson rule.
double m0_by_quadrature(const WaveSpectrum& s, double* error_estimate) {
  using boost::math::quadrature::gauss_kronrod;
  const auto f = [&](double w) { return s.density(w); };
  const double wp = s.peak_frequency();
  double e1 = 0.0, e2 = 0.0;
  const double a = gauss_kronrod<double, 61>::integrate(f, 0.0, wp, 15, 1e-12, &e1);
  const double b =
      gauss_kronrod<double, 61>::integrate(f, wp, std::numeric_limits<double>::infinity(), 15, 1e-12, &e2);
  *error_estimate = e1 * a + e2 * b;  // Boost reports relative error estimates
  return a + b;
}

// The model's m0 claim rests on (a) PM's closed form and (b) C(γ) from a Simpson rule with relative error
// ≲ 1e-10 (step σωp/200, see the header); the quadrature's own error estimate is asserted ≤ 1e-11 relative.
// 1e-8 relative therefore separates a wrong formula (errors of percent) from rounding by two orders.
constexpr double kM0Tolerance = 1e-8;

TEST(WaveSpectrum, PiersonMoskowitzM0IsHsSquaredOver16) {
  for (const auto& [Hs, Tp] : {std::pair{1.0, 5.0}, {2.5, 9.0}, {8.0, 14.0}}) {
    const WaveSpectrum s(pm(Hs, Tp));
    double err = 0.0;
    const double m0 = m0_by_quadrature(s, &err);
    std::printf("PM Hs=%.1f Tp=%.1f: m0 quadrature %.15g, Hs^2/16 %.15g, rel diff %.2e (quad err %.1e)\n", Hs,
                Tp, m0, Hs * Hs / 16, m0 / (Hs * Hs / 16) - 1, err / m0);
    EXPECT_LE(err, 1e-11 * m0);
    EXPECT_NEAR(m0, Hs * Hs / 16.0, kM0Tolerance * Hs * Hs / 16.0);
    EXPECT_NEAR(s.integral(0.0, 1e6), Hs * Hs / 16.0, 1e-12 * Hs * Hs / 16.0);
  }
}

TEST(WaveSpectrum, JonswapM0IsHsSquaredOver16ForEveryGamma) {
  for (const double gamma : {1.0, 2.0, 3.3, 5.0, 7.0}) {
    const WaveSpectrum s(jonswap(4.0, 10.0, gamma));
    double err = 0.0;
    const double m0 = m0_by_quadrature(s, &err);
    std::printf("JONSWAP gamma=%.1f: C=%.10f (DNV 1-0.287 ln g = %.10f, %+.2f %%), m0 rel diff %.2e\n", gamma,
                s.normalization(), WaveSpectrum::dnv_normalization(gamma),
                100 * (WaveSpectrum::dnv_normalization(gamma) / s.normalization() - 1), m0 / 1.0 - 1);
    EXPECT_LE(err, 1e-11 * m0);
    EXPECT_NEAR(m0, 1.0, kM0Tolerance);  // Hs²/16 = 1 m²
    // The model's own band integral agrees with the same quadrature over a band.
    const auto f = [&](double w) { return s.density(w); };
    const double band =
        boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, 0.5, 0.63, 15, 1e-12) +
        boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, 0.63, 1.4, 15, 1e-12);
    EXPECT_NEAR(s.integral(0.5, 1.4), band, kM0Tolerance * band);
  }
}

TEST(WaveSpectrum, DnvNormalizationIsWithinTwoPercentOfTheExactOne) {
  // DNV-RP-C205 calls 1 − 0.287 ln γ an approximation; document how far it is for 1 ≤ γ ≤ 7.
  for (const double gamma : {1.5, 2.0, 3.3, 5.0, 7.0}) {
    const WaveSpectrum s(jonswap(4.0, 10.0, gamma));
    EXPECT_NEAR(WaveSpectrum::dnv_normalization(gamma) / s.normalization(), 1.0, 0.02) << gamma;
  }
}

TEST(WaveSpectrum, PeakIsAtOmegaP) {
  for (const auto& p : {pm(2.0, 8.0), jonswap(2.0, 8.0, 3.3), jonswap(2.0, 8.0, 7.0)}) {
    const WaveSpectrum s(p);
    const double wp = s.peak_frequency();
    EXPECT_DOUBLE_EQ(wp, 2 * std::numbers::pi / 8.0);
    // Dense scan 0.2 ωp .. 5 ωp in steps of 1e-5 ωp: the maximum sits on the grid point ωp.
    double best_w = 0.0, best = -1.0;
    for (int k = 20000; k <= 500000; ++k) {
      const double w = wp * k * 1e-5;
      if (s.density(w) > best) best = s.density(w), best_w = w;
    }
    EXPECT_NEAR(best_w, wp, 1e-5 * wp);
    // Zero slope at ωp: the centred difference with h = 1e-6 ωp is O(h) (JONSWAP's curvature differs on the
    // two sides), far below the O(1) S(ωp)/ωp a misplaced peak would give.
    const double h = 1e-6 * wp;
    EXPECT_LT(std::abs(s.density(wp + h) - s.density(wp - h)) / (2 * h), 1e-4 * s.density(wp) / wp);
  }
}

TEST(WaveSpectrum, JonswapWithGammaOneIsPiersonMoskowitzExactly) {
  const WaveSpectrum j(jonswap(3.0, 11.0, 1.0)), p(pm(3.0, 11.0));
  EXPECT_EQ(j.normalization(), 1.0);
  for (int k = 1; k <= 4000; ++k) {
    const double w = 1e-3 * k;
    ASSERT_EQ(j.density(w), p.density(w)) << w;
  }
  EXPECT_EQ(j.integral(0.3, 2.0), p.integral(0.3, 2.0));
}

// Sample variance of the synthesized sea over a long window against m0.
//
// For fixed amplitudes aᵢ and frequencies ωᵢ and independent uniform phases, the average of y² over M samples
// t_n = n dt is Σaᵢ²/2 plus zero-mean terms:
//   Var[⟨y²⟩] = Σᵢ aᵢ⁴ D(2ωᵢ)²/8 + Σ_{i<j} aᵢ²aⱼ² [D(ωᵢ − ωⱼ)² + D(ωᵢ + ωⱼ)²]/2,
//   D(Ω) = sin(MΩdt/2) / (M sin(Ωdt/2))   (the Dirichlet kernel: the average of cos(Ω t_n + φ) is D
//   cos(...)).
// The assertion is |s² − Σaᵢ²/2| ≤ 5σ + (5σ_mean)², σ_mean² = Σ aᵢ² D(ωᵢ)²/2 bounding the squared sample
// mean: a sum of ~2000 independent terms, nearly normal, so a false failure has probability ~1e-6 for a
// random seed. Separately Σaᵢ²/2 = ∫_band S dω (PM: closed form, 1e-12) and the band [0.5, 5] ωp holds 99.8 %
// of m0.
struct SeaVarianceCheck {
  double sample_variance, synthesized, sigma, band_fraction;
};

template <int N>
SeaVarianceCheck measure_sea_variance(const WaveSpectrum& s, std::uint64_t seed) {
  random::SeededRng rng(seed);
  motion::IrregularSeaParams p;
  p.components = N;
  p.grid_period = 0.05;
  const motion::IrregularSea<N> sea(s, p, rng);
  const std::int64_t M = 216000;  // 3 h at 20 Hz
  double sum = 0.0, sum2 = 0.0;
  for (std::int64_t n = 0; n < M; ++n) {
    const double y = sea.sample(n).value;
    sum += y;
    sum2 += y * y;
  }
  const double mean = sum / M, var = sum2 / M - mean * mean;
  const auto D = [&](double w) {
    return std::sin(M * w * p.grid_period / 2) / (M * std::sin(w * p.grid_period / 2));
  };
  double v2 = 0.0, v1 = 0.0;
  for (int i = 0; i < N; ++i) {
    const double ai2 = sea.elevation_amplitude(i) * sea.elevation_amplitude(i);
    v2 += ai2 * ai2 * D(2 * sea.frequency(i)) * D(2 * sea.frequency(i)) / 8;
    v1 += ai2 * D(sea.frequency(i)) * D(sea.frequency(i)) / 2;
    for (int j = i + 1; j < N; ++j) {
      const double aj2 = sea.elevation_amplitude(j) * sea.elevation_amplitude(j);
      const double dm = D(sea.frequency(i) - sea.frequency(j)), dp = D(sea.frequency(i) + sea.frequency(j));
      v2 += ai2 * aj2 * (dm * dm + dp * dp) / 2;
    }
  }
  const double sigma = std::sqrt(v2) + 5 * v1;  // 5σ + 25σ_mean² = 5 (σ + 5σ_mean²)
  return {var, sea.band_variance(), sigma, sea.band_variance() / s.m0()};
}

TEST(IrregularSea, SampleVarianceOverThreeHoursMatchesM0) {
  for (const auto& p : {pm(2.5, 9.0), jonswap(2.5, 9.0, 3.3)}) {
    const WaveSpectrum s(p);
    const SeaVarianceCheck c = measure_sea_variance<64>(s, 20240611);
    std::printf(
        "%s: m0 %.6f, synthesized %.6f (%.4f of m0), sample variance %.6f, deviation %.2e = %.2f sigma "
        "(bound 5 sigma = %.2e), variance/m0 - 1 = %+.4f\n",
        p.kind == Kind::kJonswap ? "JONSWAP 3.3" : "PM", s.m0(), c.synthesized, c.band_fraction,
        c.sample_variance, c.sample_variance - c.synthesized, (c.sample_variance - c.synthesized) / c.sigma,
        5 * c.sigma, c.sample_variance / s.m0() - 1);
    EXPECT_LE(std::abs(c.sample_variance - c.synthesized), 5 * c.sigma);
    EXPECT_GT(c.band_fraction, 0.997);
    EXPECT_LE(c.band_fraction, 1.0);
    if (p.kind == Kind::kPiersonMoskowitz) {
      const double exact = s.m0() * (s.pm_fraction_below(5 * s.peak_frequency()) -
                                     s.pm_fraction_below(0.5 * s.peak_frequency()));
      EXPECT_NEAR(c.synthesized, exact, 1e-12 * exact);
    }
    // Overall: within the band loss (0.2 %) plus the statistical bound of m0.
    EXPECT_NEAR(c.sample_variance / s.m0(), c.band_fraction, 5 * c.sigma / s.m0());
    // What a sizing study relies on: the generated elevation's variance within 2 % of Hs²/16 (band loss
    // 0.2 % + the 3-hour record's statistical spread, 5σ ≈ 1 % here).
    EXPECT_NEAR(c.sample_variance, p.Hs * p.Hs / 16.0, 0.02 * p.Hs * p.Hs / 16.0);
  }
}

}  // namespace wave_spectrum_test
}  // namespace gyrostab
