// Sensor models: encoder quantization, rate-gyro bandwidth (DC gain, −3 dB point), noise and bias statistics,
// output stage, accelerometer. Statistical assertions use 5-sigma bounds of the estimator under the model,
// with fixed seeds (deterministic: the bound says how far a correct model could be, the seed makes it
// repeatable).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "sim/sensors/accelerometer.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/rate_gyro.hpp"

namespace gyrostab {
namespace sensors_test {

using sensors::Encoder;
using sensors::EncoderParams;
using sensors::LowpassParams;
using sensors::RateGyro;
using sensors::RateGyroParams;
using Order = LowpassParams::Order;
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------- encoder

TEST(Encoder, FloorQuantizationGivesTheExactCountInsideEveryBin) {
  EncoderParams p;
  p.counts_per_rev = 4096;
  p.offset = 0.3;
  const Encoder e(p);
  const double lsb = 2 * kPi / 4096;
  EXPECT_EQ(e.lsb(), lsb);
  // Three turns back and four forward, each bin probed near both edges and in the middle. 1e-6 LSB from an
  // edge is ~1e8 ulps of q for |q| ≤ 2e4: rounding cannot move a probe across the edge.
  for (std::int64_t k = -3 * 4096; k <= 4 * 4096; ++k) {
    for (const double f : {1e-6, 0.5, 1 - 1e-6}) {
      const double theta = p.offset + (static_cast<double>(k) + f) * lsb;
      ASSERT_EQ(e.counts(theta), k) << "k=" << k << " f=" << f;
      ASSERT_EQ(e.measure(theta), static_cast<double>(k) * lsb);
    }
  }
  EXPECT_EQ(e.counts(p.offset - 0.5 * lsb), -1);  // floor, not truncation toward zero
}

TEST(Encoder, NearestRoundingCentresTheErrorAndAbsoluteModeWraps) {
  EncoderParams p;
  p.counts_per_rev = 1000;
  p.offset = -0.1;
  p.rounding = EncoderParams::Rounding::kNearest;
  p.mode = EncoderParams::Mode::kAbsolute;
  const Encoder e(p);
  const double lsb = 2 * kPi / 1000;
  for (std::int64_t k = -2500; k <= 2500; ++k) {
    for (const double f : {-0.5 + 1e-6, 0.0, 0.5 - 1e-6}) {
      const double theta = p.offset + (static_cast<double>(k) + f) * lsb;
      const std::int64_t wrapped = ((k % 1000) + 1000) % 1000;
      ASSERT_EQ(e.counts(theta), wrapped) << "k=" << k << " f=" << f;
      ASSERT_GE(e.measure(theta), 0.0);
      ASSERT_LT(e.measure(theta), 2 * kPi);
    }
  }
}

TEST(Encoder, QuantizationErrorStaysWithinOneLsbOverASweep) {
  const Encoder floor_enc(EncoderParams{2048, 0.0});
  EncoderParams pn{2048, 0.0};
  pn.rounding = EncoderParams::Rounding::kNearest;
  const Encoder near_enc(pn);
  const double lsb = floor_enc.lsb(), slack = 1e-12;  // |θ| ≤ 60 rad: rounding of θ·CPR/2π ≲ 1e-14 rad
  for (int i = -600000; i <= 600000; ++i) {
    const double theta = i * 1e-4 + 1.234e-7;
    const double ef = theta - floor_enc.measure(theta), en = theta - near_enc.measure(theta);
    ASSERT_GE(ef, -slack);
    ASSERT_LT(ef, lsb + slack);
    ASSERT_GE(en, -0.5 * lsb - slack);
    ASSERT_LT(en, 0.5 * lsb + slack);
  }
  EXPECT_EQ(floor_enc.counts(std::nan("")), 0);
}

// ---------------------------------------------------------------------------------------------- rate gyro

RateGyroParams gyro_with(Order order, double bandwidth_hz, double zeta, double T) {
  RateGyroParams p;
  p.sample_period = T;
  p.bandwidth = {order, bandwidth_hz, zeta};
  return p;
}

struct FilterCase {
  Order order;
  double zeta;
};
constexpr FilterCase kFilters[] = {{Order::kFirst, 0.0},  {Order::kSecond, std::numbers::sqrt2 / 2},
                                   {Order::kSecond, 0.5}, {Order::kSecond, 1.0},
                                   {Order::kSecond, 2.0}, {Order::kSecond, 1.0 + 1e-9}};

TEST(RateGyro, DcGainIsOne) {
  for (const FilterCase& f : kFilters) {
    RateGyro g(gyro_with(f.order, 50.0, f.zeta, 1e-3));
    random::SeededRng rng(1);
    double y = 0.0;
    for (int k = 0; k < 5000; ++k)
      y = g.measure(0.37, rng);  // 5 s ≫ the slowest time constant (ζ = 2: 30 ms)
    EXPECT_NEAR(y, 0.37, 1e-14) << "zeta " << f.zeta;
    EXPECT_NEAR(std::abs(g.filter().frequency_response(0.0)), 1.0, 1e-14);
  }
}

// Gain at the bandwidth from the steady response to a sampled sine (least-squares fit over whole periods).
double measured_gain(RateGyro& g, double w, double T, int periods_settle, int periods_fit) {
  random::SeededRng rng(1);
  const int per =
      static_cast<int>(std::lround(2 * kPi / (w * T)));  // samples per period (integer by choice of w)
  for (int k = 0; k < per * periods_settle; ++k) g.measure(std::sin(w * k * T), rng);
  double ss = 0.0, sc = 0.0;
  const int k0 = per * periods_settle, n = per * periods_fit;
  for (int k = k0; k < k0 + n; ++k) {
    const double y = g.measure(std::sin(w * k * T), rng);
    ss += y * std::sin(w * k * T);
    sc += y * std::cos(w * k * T);
  }
  return 2.0 * std::hypot(ss, sc) / n;  // exact for a sinusoid over whole periods (orthogonality on the grid)
}

TEST(RateGyro, GainIsMinus3dBAtTheBandwidth) {
  // Bandwidth 50 Hz at 1 kHz (fs/20) and at 10 kHz (fs/200). Two claims:
  // (1) the measured gain equals the filter's exact discrete response |H(e^{iωT})| to 1e-9 (the steady-state
  //     fit is exact up to the decayed transient, < e^{-ω₀·1 s} ≈ 1e-100);
  // (2) that gain is −3.0103 dB within 0.05 dB at fs/20 and 0.0005 dB at fs/200: the ZOH equivalent departs
  //     from H(iω) by O((ωT)²) — measured +0.036 dB (first order) at ωT = 0.31, 100× less at ωT = 0.031.
  for (const auto& [T, tol_db] : {std::pair{1e-3, 0.05}, {1e-4, 5e-4}}) {
    for (const FilterCase& f : kFilters) {
      RateGyro g(gyro_with(f.order, 50.0, f.zeta, T));
      const double w = 2 * kPi * 50.0;
      const double gain = measured_gain(g, w, T, 50, 20);
      const double exact = std::abs(g.filter().frequency_response(w));
      const double db = 20 * std::log10(gain);
      std::printf("T=%g order=%d zeta=%.4f: gain at f_bw %.9f (%.4f dB), discrete response %.9f\n", T,
                  f.order == Order::kFirst ? 1 : 2, f.zeta, gain, db, exact);
      EXPECT_NEAR(gain, exact, 1e-9);
      EXPECT_NEAR(db, -10 * std::log10(2.0), tol_db);
    }
  }
}

TEST(RateGyro, StepResponseEqualsTheContinuousFilterAtEverySample) {
  // The ZOH equivalent is exact for an input held over each sample interval, so a unit step read from sample
  // 1 on (held over (0, T]) must give the continuous step response s(kT) at every sample — to rounding (1e-13
  // over 400 samples). s(t) written per regime, independently of the filter's e^{AT} construction.
  const double T = 1e-3;
  for (const FilterCase& f : kFilters) {
    RateGyro g(gyro_with(f.order, 50.0, f.zeta, T));
    random::SeededRng rng(1);
    const double wn = f.order == Order::kFirst ? 2 * kPi * 50.0 : g.filter().natural_frequency();
    for (int k = 1; k <= 400; ++k) {
      const double t = k * T, y = g.measure(1.0, rng);
      double s = 0.0;
      if (f.order == Order::kFirst) {
        s = 1 - std::exp(-wn * t);
      } else if (f.zeta < 1.0) {
        const double z = f.zeta, wd = wn * std::sqrt(1 - z * z);
        s = 1 - std::exp(-z * wn * t) * (std::cos(wd * t) + z / std::sqrt(1 - z * z) * std::sin(wd * t));
      } else if (f.zeta == 1.0) {
        s = 1 - std::exp(-wn * t) * (1 + wn * t);
      } else {  // overdamped: 1 − e^{−ζωn t}(cosh νt + ζωn sinh(νt)/ν), ν = ωn√(ζ² − 1), in overflow-free
                // form
        const double z = f.zeta, nu = wn * std::sqrt(z * z - 1), ep = std::exp((nu - z * wn) * t),
                     em = std::exp((-nu - z * wn) * t);
        s = nu * t < 1.0  // small νt: sinh(νt)/ν directly (the difference ep − em would cancel)
                ? 1 - std::exp(-z * wn * t) * (std::cosh(nu * t) + z * wn * std::sinh(nu * t) / nu)
                : 1 - (0.5 * (ep + em) + z * wn * 0.5 * (ep - em) / nu);
      }
      const double tol = 1e-13;
      ASSERT_NEAR(y, s, tol) << "order " << (f.order == Order::kFirst ? 1 : 2) << " zeta " << f.zeta << " k "
                             << k;
    }
  }
}

TEST(RateGyro, WhiteNoiseStandardDeviationIsDensityOverRootT) {
  // N = 0.005 rad/s/√Hz (0.29 °/s/√Hz). σ = N/√T. For n = 1e6 Gaussian samples the sample standard deviation
  // has relative standard error 1/√(2n) = 7.1e-4: bound 5× = 3.5e-3. Mean within 5σ/√n; lag-1 autocorrelation
  // within 5/√n (white).
  for (const double T : {1e-3, 2e-4}) {
    RateGyroParams p;
    p.sample_period = T;
    p.noise.white_density = 0.005;
    RateGyro g(p);
    random::SeededRng rng(T == 1e-3 ? 42 : 43);
    const int n = 1000000;
    double s1 = 0, s2 = 0, lag = 0, prev = 0;
    for (int k = 0; k < n; ++k) {
      const double y = g.measure(0.0, rng);
      s1 += y;
      s2 += y * y;
      lag += y * prev;
      prev = y;
    }
    const double sigma = 0.005 / std::sqrt(T), mean = s1 / n, sd = std::sqrt(s2 / n - mean * mean);
    std::printf(
        "T=%g: sigma expected %.6f, measured %.6f (rel %+.2e, bound 3.5e-3), mean %.2e (bound %.2e), "
        "lag-1 corr %+.2e (bound 5e-3)\n",
        T, sigma, sd, sd / sigma - 1, mean, 5 * sigma / std::sqrt(n), lag / s2);
    EXPECT_NEAR(sd / sigma, 1.0, 5.0 / std::sqrt(2.0 * n));
    EXPECT_NEAR(mean, 0.0, 5 * sigma / std::sqrt(n));
    EXPECT_NEAR(lag / s2, 0.0, 5.0 / std::sqrt(n));
  }
}

TEST(RateGyro, ConstantBiasAddsExactlyAndBiasRandomWalkHasTheStatedIncrements) {
  {
    RateGyroParams p;
    p.noise.bias = 0.02;
    RateGyro g(p);
    random::SeededRng rng(3);
    for (int k = 0; k < 100; ++k) ASSERT_EQ(g.measure(0.5, rng), 0.5 + 0.02);
  }
  {
    // K = 1e-4 rad/s²/√Hz at T = 1 ms: increments σ_b = K√T. 1e6 increments: sample sd within 5/√(2n).
    RateGyroParams p;
    p.noise.bias_random_walk = 1e-4;
    RateGyro g(p);
    random::SeededRng rng(4);
    const int n = 1000000;
    double s2 = 0.0, b = g.noise().bias();
    for (int k = 0; k < n; ++k) {
      g.measure(0.0, rng);
      const double d = g.noise().bias() - b;
      b = g.noise().bias();
      s2 += d * d;
    }
    const double sb = 1e-4 * std::sqrt(1e-3);
    std::printf("bias increments: expected sd %.4e, measured %.4e (rel %+.2e, bound %.1e)\n", sb,
                std::sqrt(s2 / n), std::sqrt(s2 / n) / sb - 1, 5 / std::sqrt(2.0 * n));
    EXPECT_NEAR(std::sqrt(s2 / n) / sb, 1.0, 5.0 / std::sqrt(2.0 * n));
  }
  {
    // Ensemble of 2000 gyros over 1 s: Var b(t) = K² t. Relative standard error of a sample variance from
    // M = 2000 normal values is √(2/M) = 3.2 %: bound 5× = 16 %.
    RateGyroParams p;
    p.noise.bias_random_walk = 1e-4;
    random::SeededRng rng(5);
    const int M = 2000;
    double s2 = 0.0;
    for (int m = 0; m < M; ++m) {
      RateGyro g(p);
      for (int k = 0; k < 1000; ++k) g.measure(0.0, rng);
      s2 += g.noise().bias() * g.noise().bias();
    }
    std::printf("bias after 1 s: variance %.4e vs K^2 t = %.4e (rel %+.3f, bound 0.16)\n", s2 / M, 1e-8,
                s2 / M / 1e-8 - 1);
    EXPECT_NEAR(s2 / M / 1e-8, 1.0, 5 * std::sqrt(2.0 / M));
  }
}

TEST(RateGyro, ReadsTheBaseRateAboutItsInputAxisWithScaleFactorAndOutputStage) {
  RateGyroParams p;
  p.input_axis_B = dynamics::Vec3(0, 1, 1).normalized();
  p.scale_factor_error = 0.01;
  p.output = {1e-3, 0.5};  // LSB 1 mrad/s, ±0.5 rad/s
  RateGyro g(p);
  random::SeededRng rng(6);
  models::BaseSample b;
  b.w_B = {0.3, 0.1, 0.2};
  const double truth = (0.1 + 0.2) / std::sqrt(2.0);
  EXPECT_EQ(g.measure(b, rng), 1e-3 * std::round(1.01 * truth / 1e-3));
  b.w_B = {0, 3, 3};
  EXPECT_EQ(g.measure(b, rng), 0.5);  // saturated
  b.w_B = {0, -3, -3};
  EXPECT_EQ(g.measure(b, rng), -0.5);
  EXPECT_TRUE(std::isnan(g.measure(std::nan(""), rng)));  // NaN reaches the fault monitor
}

// ----------------------------------------------------------------------------------------------
// accelerometer

TEST(Accelerometer, ReadsGravityAlongItsAxisAtRestPlusBias) {
  sensors::AccelerometerParams p;
  p.input_axis_B = dynamics::Vec3(1, 0, 1).normalized();
  p.noise.bias = 0.05;
  sensors::Accelerometer a(p);
  random::SeededRng rng(7);
  const models::BaseSample at_rest = models::FixedBase{}(0.0);
  EXPECT_NEAR(a.measure(at_rest, rng), 9.80665 / std::sqrt(2.0) + 0.05, 1e-14);
}

}  // namespace sensors_test
}  // namespace gyrostab
