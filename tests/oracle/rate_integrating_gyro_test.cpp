// Oracle tests of the single-degree-of-freedom gyro (sim/sensors/rate_integrating_gyro.hpp) against Magnus
// ch. 15, §15.1-15.3 (docs/models/rate-gyros.md):
//   P-gyro: steady output (15.3) incl. the B Ω2' and H Ω3 terms, (15.4) scale factor H/c2, the free motion
//   of (15.2) (natural frequency sqrt(c2/B) and damping ratio d2/(2 sqrt(B c2))), the −3 dB bandwidth of the
//   second-order response; the turn indicator's under-reading by cosφ (15.6);
//   I-gyro: the step response (15.13) with T_z = B/d2 (15.14), the integrated angle (15.16), the
//   saturation β = Ω1/Ω3 (15.11); I²-gyro: β = (H/B) ∫∫Ω1 (15.19).
// Step: automatic sub-steps with h|λ|max ≤ 0.05 (RK4 local error ≲ (0.05)^5/120 ≈ 3e-9 of a decaying mode
// per step; on the oscillatory mode a relative frequency error ~(hω)^4/120 ≈ 5e-8) — tolerances 1e-6
// relative on frequencies and amplitudes, 1e-9 on steady values.
#include "sim/sensors/rate_integrating_gyro.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "sim/analysis/zero_crossing_meter.hpp"

namespace gyrostab {
namespace rate_integrating_gyro_test {

using sensors::GyroCaseMotion;
using sensors::SingleAxisGyro;
using sensors::SingleAxisGyroKind;
using sensors::SingleAxisGyroParams;
constexpr double kPi = std::numbers::pi;

SingleAxisGyroParams rate_gyro(double zeta) {
  SingleAxisGyroParams p;
  p.B = 2e-5;
  p.c2 = 0.2;  // ω_n = 100 rad/s (16 Hz; book 10-60 Hz)
  p.H = 0.01;
  p.d2 = 2.0 * zeta * std::sqrt(p.B * p.c2);
  p.sample_period = 1e-3;
  return p;
}

TEST(RateGyroOracle, SteadyOutput15_3_15_4) {
  SingleAxisGyroParams p = rate_gyro(0.7);
  SingleAxisGyro g(p);
  EXPECT_EQ(p.kind(), SingleAxisGyroKind::kRate);
  const GyroCaseMotion m{0.3, 5.0, 2.0};
  for (int k = 0; k < 2000; ++k) g.update(m);  // 2 s: e^-140 of the transient
  const double book = (p.H * m.Omega1 - p.B * m.Omega2_dot) / (p.c2 + p.H * m.Omega3);  // (15.3)
  EXPECT_NEAR(g.beta(), book, 1e-12);
  // (15.4): without the Ω2', Ω3 terms the reading (c2/H) β is the input rate.
  SingleAxisGyro g2(p);
  for (int k = 0; k < 2000; ++k) g2.update({0.3, 0.0, 0.0});
  EXPECT_NEAR(g2.indicated(), 0.3, 1e-12);
  EXPECT_NEAR(g2.beta(), p.H / p.c2 * 0.3, 1e-13);
}

TEST(RateGyroOracle, FreeMotionFrequencyAndDamping15_2) {
  const double zeta = 0.05;
  SingleAxisGyroParams p = rate_gyro(zeta);
  SingleAxisGyro g(p);
  EXPECT_NEAR(g.natural_frequency(), 100.0, 1e-12);
  EXPECT_NEAR(g.damping_ratio(), zeta, 1e-12);
  g.reset(1e-3, 0.0);
  analysis::ZeroCrossingMeter zc;
  double peak_first = 0, peak_last = 0, t_first = 0, t_last = 0;
  double prev = g.beta(), prev2 = prev;
  for (int k = 1; k <= 2000; ++k) {
    g.update({});
    const double t = k * p.sample_period;
    zc.add(t, g.beta(), g.beta_rate());
    // maxima of β: damping from two peaks (sampled at 1 kHz; both peaks sampled with the same phase error
    // would cancel only on average — use the envelope through the zero-crossing-based frequency instead)
    if (k >= 2 && prev > prev2 && prev > g.beta()) {
      if (peak_first == 0) {
        peak_first = prev;
        t_first = t - p.sample_period;
      }
      peak_last = prev;
      t_last = t - p.sample_period;
    }
    prev2 = prev;
    prev = g.beta();
  }
  const double wd = 100.0 * std::sqrt(1 - zeta * zeta);
  std::printf("damped frequency %.6f rad/s (book %.6f)\n", zc.angular_frequency(), wd);
  EXPECT_NEAR(zc.angular_frequency() / wd, 1.0, 1e-6);
  // Sampled peaks sit within ±h/2 of the true ones: the ratio is off by ≤ 2 (1 − cos(ω h/2)) ≈ 2.5e-3.
  const double sigma = -std::log(peak_last / peak_first) / (t_last - t_first);
  EXPECT_NEAR(sigma / (zeta * 100.0), 1.0, 3e-3);
}

TEST(RateGyroOracle, BandwidthOfThePGyro) {
  // |G(iω)| / G(0) = 1/sqrt((1 − r²)² + (2ζr)²), r = ω/ω_n: −3 dB at r² = 1 − 2ζ² + sqrt((1 − 2ζ²)² + 1).
  const double zeta = 0.7;
  SingleAxisGyroParams p = rate_gyro(zeta);
  const double a = 1 - 2 * zeta * zeta, r3 = std::sqrt(a + std::sqrt(a * a + 1)), w = r3 * 100.0;
  const double amp = 0.1;
  const int per = 2000;  // samples per input period (the gyro's sample period set to T/per)
  p.sample_period = 2 * kPi / w / per;
  SingleAxisGyro gs(p);
  double sc = 0, ss = 0;
  const int periods_settle = 20, periods = 10;
  for (int k = 0; k < (periods_settle + periods) * per; ++k) {
    const double t0 = k * p.sample_period, t1 = t0 + p.sample_period;
    gs.update({amp * std::sin(w * t0), 0.0, 0.0}, {amp * std::sin(w * t1), 0.0, 0.0});
    if (k >= periods_settle * per) {
      sc += gs.indicated() * std::cos(w * t1);
      ss += gs.indicated() * std::sin(w * t1);
    }
  }
  const double gain = 2.0 / (periods * per) * std::hypot(sc, ss) / amp;
  std::printf("P-gyro gain at the -3 dB frequency %.3f rad/s: %.6f (book 1/sqrt2 = %.6f)\n", w, gain, 1 / std::sqrt(2.0));
  // The input is linear between samples (2000 per period): its interpolation error on a sinusoid is
  // ~(ωT)²/8 = 1.2e-6 relative; the transient after 20 periods is e^-(2π 20 ζ/r3) ≈ 1e-30.
  EXPECT_NEAR(gain * std::sqrt(2.0), 1.0, 1e-5);
}

TEST(RateGyroOracle, TurnIndicatorUnderReadsByCosBank15_6) {
  // Level turn at Ω = 0.05 rad/s, bank φ = 30°: gyro axes (input = normal, output = longitudinal, spin =
  // lateral) see Ω_i = (Ω cosφ, 0, Ω sinφ) (15.5): β = H Ω cosφ/(c2 + H Ω sinφ) (15.6).
  SingleAxisGyroParams p = rate_gyro(0.7);
  SingleAxisGyro g(p);
  const double W = 0.05, phi = kPi / 6;
  for (int k = 0; k < 2000; ++k) g.update({W * std::cos(phi), 0.0, W * std::sin(phi)});
  EXPECT_NEAR(g.beta(), p.H * W * std::cos(phi) / (p.c2 + p.H * W * std::sin(phi)), 1e-12);
  EXPECT_NEAR(g.indicated() / W, std::cos(phi), 2e-3);  // ≈ cosφ: the H Ω sinφ/c2 = 1.25e-3 correction
}

TEST(RateGyroOracle, IntegratingGyroStepResponse15_13_15_16) {
  SingleAxisGyroParams p;
  p.B = 2e-5;
  p.c2 = 0.0;
  p.d2 = 1e-4;  // H/d2 = 100 (book ≈ 100), T_z = B/d2 = 0.2 s
  p.H = 0.01;
  p.sample_period = 1e-3;
  SingleAxisGyro g(p);
  EXPECT_EQ(p.kind(), SingleAxisGyroKind::kIntegrating);
  EXPECT_NEAR(g.time_constant(), 0.2, 1e-15);
  const double W = 0.01;
  for (int k = 1; k <= 3000; ++k) {
    g.update({W, 0.0, 0.0});
    const double t = k * p.sample_period, Tz = 0.2;
    // (15.13) integrated from β(0) = β'(0) = 0.
    const double rate = p.H / p.d2 * W * (1 - std::exp(-t / Tz));
    const double beta = p.H / p.d2 * W * (t - Tz * (1 - std::exp(-t / Tz)));
    ASSERT_NEAR(g.beta_rate(), rate, 1e-9 * p.H / p.d2 * W) << t;
    ASSERT_NEAR(g.beta(), beta, 1e-9 * p.H / p.d2 * W) << t;
  }
  // (15.16): the indicated angle (d2/H) β follows ∫Ω1 dt = W t with the lag W T_z.
  EXPECT_NEAR(g.indicated(), W * (3.0 - 0.2), 1e-9);
}

TEST(RateGyroOracle, IntegratingGyroSaturatesUnderSpinAxisRate15_11) {
  SingleAxisGyroParams p;
  p.B = 2e-5;
  p.c2 = 0.0;
  p.d2 = 1e-4;
  p.H = 0.01;
  SingleAxisGyro g(p);
  const GyroCaseMotion m{0.02, 0.0, 0.1};
  for (int k = 0; k < 20000; ++k) g.update(m);  // slowest root H Ω3/d2 = 10 /s
  EXPECT_NEAR(g.beta(), m.Omega1 / m.Omega3, 1e-10);  // = 0.2 rad: not small
}

TEST(RateGyroOracle, DoubleIntegratingGyro15_19) {
  SingleAxisGyroParams p;
  p.B = 2e-5;
  p.c2 = 0.0;
  p.d2 = 0.0;
  p.H = 0.01;
  SingleAxisGyro g(p);
  EXPECT_EQ(p.kind(), SingleAxisGyroKind::kDoubleIntegrating);
  const double W = 1e-3;
  for (int k = 0; k < 1000; ++k) g.update({W, 0.0, 0.0});
  EXPECT_NEAR(g.beta(), p.H / p.B * W * 0.5, 1e-12);  // (H/B) W t²/2 at t = 1 s (RK4 exact on t²)
  EXPECT_NEAR(g.indicated(), W * 0.5, 1e-15);
}

}  // namespace rate_integrating_gyro_test
}  // namespace gyrostab
