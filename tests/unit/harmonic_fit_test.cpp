// The amplitude, frequency and drift estimators of sim/analysis/ with a constant or slow component 10³ times
// the one they measure: the least-squares harmonic fit (harmonic_fit.hpp) and the servo gyro's drive sums built
// on it against the Fourier sums they replace, which leak the mean into the harmonic over a window that ends on
// a tick; and the meters that were already immune (nutation, extrema, zero crossings at the mean, periodic
// drift), held to the same offset so that a change that makes them leak fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/analysis/extrema_meter.hpp"
#include "sim/analysis/harmonic_fit.hpp"
#include "sim/analysis/nutation_meter.hpp"
#include "sim/analysis/periodic_drift.hpp"
#include "sim/analysis/servo_drive_sums.hpp"
#include "sim/analysis/zero_crossing_meter.hpp"

namespace gyrostab {
namespace harmonic_fit_test {

constexpr double kPi = std::numbers::pi;

// y = m + A cos(θ − φ), θ = w t, sampled every h over [0, T); T not a whole number of periods.
struct Signal {
  double mean, amplitude, phase, w;
  double at(double t) const { return mean + amplitude * std::cos(w * t - phase); }
};

TEST(HarmonicFit, AMean1000TimesTheHarmonicDoesNotLeakIntoIt) {
  const Signal s{1400.0, 1.0, 0.3, 2.0 * kPi * 200.0};  // the U-gyro's 200 Hz twice-spin, mean 1400×
  const double h = 1e-4;                                 // 50 samples a period
  const int n = 5027;                                    // 100.54 periods: the window ends on a tick
  analysis::HarmonicFit fit(false), with_trend(true);
  double c = 0.0, sn = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = k * h, y = s.at(t);
    fit.add(s.w * t, y, t);
    with_trend.add(s.w * t, y, t);
    c += y * std::cos(s.w * t);
    sn += y * std::sin(s.w * t);
  }
  const double fourier = 2.0 / n * std::hypot(c, sn);
  const analysis::HarmonicFit::Result r = fit.solve(), rt = with_trend.solve();
  std::printf("  Fourier sums: amplitude %+.3e relative; fit %+.3e, with trend %+.3e; mean %+.3e\n",
              fourier / s.amplitude - 1.0, r.amplitude() / s.amplitude - 1.0, rt.amplitude() / s.amplitude - 1.0,
              r.mean / s.mean - 1.0);
  // The old estimator: the 0.54 of a period left over carries the mean into the sums, ~1 % here.
  EXPECT_GT(std::fabs(fourier / s.amplitude - 1.0), 1e-3);
  // The fit separates mean and harmonic exactly; what is left is rounding of sums of n terms of size 1400.
  ASSERT_TRUE(r.valid);
  ASSERT_TRUE(rt.valid);
  EXPECT_NEAR(r.amplitude(), s.amplitude, 1e-10);
  EXPECT_NEAR(r.phase(), s.phase, 1e-10);
  EXPECT_NEAR(r.mean, s.mean, 1e-9);
  EXPECT_NEAR(rt.amplitude(), s.amplitude, 1e-10);
  EXPECT_NEAR(rt.mean, s.mean, 1e-9);
  EXPECT_NEAR(rt.slope, 0.0, 1e-8);
}

TEST(HarmonicFit, ASlowTrend1000TimesTheHarmonicIsSeparatedByTheTrendTerm) {
  // A slow drift that moves by 10³ amplitudes over the window (a transient far slower than the harmonic).
  const double w = 2.0 * kPi * 50.0, h = 1e-3, drift = 1000.0 / 2.0;  // 1000 over the 2 s window
  analysis::HarmonicFit fit(true);
  const int n = 2003;
  for (int k = 0; k < n; ++k) {
    const double t = k * h;
    fit.add(w * t, 5.0 + drift * t + 0.5 * std::sin(w * t), t);
  }
  const analysis::HarmonicFit::Result r = fit.solve();
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.amplitude(), 0.5, 1e-9);
  EXPECT_NEAR(r.phase(), kPi / 2, 1e-9);
  EXPECT_NEAR(r.slope, drift, 1e-7);
  EXPECT_NEAR(r.mean, 5.0 + drift * (n - 1) * h / 2.0, 1e-8);
}

TEST(HarmonicFit, TooFewSamplesGiveNoResult) {
  analysis::HarmonicFit fit(true);
  for (int k = 0; k < 4; ++k) fit.add(0.1 * k, 1.0, 0.1 * k);
  EXPECT_FALSE(fit.solve().valid);
  analysis::HarmonicFit constant_phase(false);
  for (int k = 0; k < 100; ++k) constant_phase.add(0.0, 1.0);  // cos θ = 1 always: not separable from the mean
  EXPECT_FALSE(constant_phase.solve().valid);
}

// The servo gyro's sums over whole drive revolutions with a tick that does not divide one: M2's mean 10³
// times its 2β harmonic, α with a mean 10³ times its amplitude (a gimbal offset).
TEST(ServoDriveSums, AMean1000TimesTheHarmonicDoesNotLeakIntoIt) {
  analysis::DriveSums d;
  const double Omega = 10.0, h = 1.3e-3;  // 483.3 ticks a revolution
  const int n = static_cast<int>(3.0 * 2.0 * kPi / (Omega * h));
  double fourier_c2 = 0.0, fourier_s2 = 0.0, sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double beta = Omega * k * h;
    const double alpha = 1e-3 * 1000.0 + 1e-3 * std::cos(beta - 0.4);
    const double M2 = 2000.0 + 2.0 * std::sin(2.0 * beta - 0.4);
    d.add(alpha, beta, 0.0, Omega, 0.5 * std::cos(beta), M2, Omega, 0.0, 0.0);
    fourier_c2 += M2 * std::cos(2.0 * beta);
    fourier_s2 += M2 * std::sin(2.0 * beta);
    sum += M2;
  }
  const analysis::HarmonicFit::Result a = d.alpha_fit.solve(), m1 = d.m1_fit.solve(), m2 = d.m2_fit.solve();
  const double fourier = 2.0 / n * std::hypot(fourier_c2, fourier_s2);
  std::printf("  M2's 2β harmonic: Fourier %+.3e relative, fit %+.3e\n", fourier / 2.0 - 1.0, m2.amplitude() / 2.0 - 1.0);
  EXPECT_GT(std::fabs(fourier / 2.0 - 1.0), 1e-3);
  EXPECT_NEAR(m2.amplitude(), 2.0, 1e-9);
  EXPECT_NEAR(m2.mean, 2000.0, 1e-9);
  EXPECT_NEAR(a.amplitude(), 1e-3, 1e-13);
  EXPECT_NEAR(a.phase(), 0.4, 1e-9);
  EXPECT_NEAR(m1.amplitude(), 0.5, 1e-12);
  EXPECT_EQ(d.n, n);
  EXPECT_NEAR(sum / n, 2000.0, 0.01);
}

// The meters that measure from extrema, crossings or differences: a constant 10³ times the oscillation moves
// nothing but the rounding.
TEST(MetersWithAnOffset, NutationExtremaZeroCrossingsAndPeriodicDriftAreImmune) {
  const double w = 3.0, sigma = -0.05, h = 0.01, offset = 1000.0;
  analysis::NutationMeter plain(0.0, 60.0), shifted(0.0, 60.0);
  analysis::ExtremaMeter<64> e0, e1;
  analysis::ZeroCrossingMeter z0(0.0), z1(offset);
  for (int k = 0; k <= 6000; ++k) {
    const double t = k * h, y = std::exp(sigma * t) * std::cos(w * t);
    plain.add(t, y);
    shifted.add(t, y + offset);
    e0.add(t, y);
    e1.add(t, y + offset);
    z0.add(t, y);
    z1.add(t, y + offset);
  }
  ASSERT_TRUE(plain.valid() && shifted.valid());
  EXPECT_NEAR(shifted.angular_frequency(), plain.angular_frequency(), 1e-9);
  EXPECT_NEAR(shifted.growth_rate(), plain.growth_rate(), 1e-9);
  EXPECT_NEAR(plain.growth_rate(), sigma, 2e-3);
  ASSERT_GE(e1.count(), 10);
  ASSERT_EQ(e0.count(), e1.count());
  EXPECT_NEAR(e1.period(), e0.period(), 1e-9);
  EXPECT_NEAR(e1.equilibrium(2), offset + e0.equilibrium(2), 1e-9);
  EXPECT_NEAR(e1.decay_rate(2), e0.decay_rate(2), 1e-7);
  EXPECT_NEAR(z1.angular_frequency(), z0.angular_frequency(), 1e-9);
  EXPECT_NEAR(z0.angular_frequency(), w, 1e-3);

  // Periodic drift: a constant departs from nothing; the departure of a ramp is the ramp's.
  analysis::PeriodicDrift d(1, 100, 0);
  for (std::int64_t k = 0; k < 5000; ++k) {
    const double v = offset + std::sin(2.0 * kPi * static_cast<double>(k) / 100.0) + 1e-9 * static_cast<double>(k);
    d.add(k, &v);
  }
  EXPECT_NEAR(d.worst(0), 1e-9 * 4900.0, 2e-10);
}

}  // namespace harmonic_fit_test
}  // namespace gyrostab
