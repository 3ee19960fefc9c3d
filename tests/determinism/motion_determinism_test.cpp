// Same seed ⇒ bit-identical suspension motion and sensor readings; a different seed ⇒ different ones.
// The "scene" here: a JONSWAP sea (roll moment), a ship attitude, base vibration, a rate gyro, an
// accelerometer and an encoder, each random consumer on its own stream of the scene seed.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "sim/motion/base_vibration.hpp"
#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/sensors/accelerometer.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/rate_gyro.hpp"

namespace gyrostab {
namespace motion_determinism_test {

std::vector<double> run_scene(std::uint64_t seed, int ticks) {
  random::SeededRng sea_rng(seed, 0), gyro_rng(seed, 1), accel_rng(seed, 2);
  const motion::WaveSpectrum spectrum(
      {motion::WaveSpectrumParams::Kind::kJonswap, 3.0, 9.0, 3.3, 0.07, 0.09});
  motion::IrregularSeaParams sp;
  sp.components = 64;
  sp.grid_period = 1e-3;
  const motion::IrregularSea<64> sea(spectrum, sp, sea_rng, motion::WaveRollMomentTransfer{1.1772e7, 0.8});

  motion::VibratingBase<motion::PrescribedBaseRotation<2>, 1> base;
  base.rotation.roll.count = 2;
  base.rotation.roll.harmonics[0] = {0.15, 0.6, 0.0};
  base.rotation.roll.harmonics[1] = {0.03, 1.4, 0.5};
  base.rotation.pitch.count = 1;
  base.rotation.pitch.harmonics[0] = {0.05, 0.8, 0.2};
  base.vibration.count = 1;
  base.vibration.harmonics[0] = {dynamics::Vec3(0, 0, 1e-4), 2 * std::numbers::pi * 30, 0.0};

  sensors::RateGyroParams gp;
  gp.bandwidth = {sensors::LowpassParams::Order::kSecond, 40.0, 0.7};
  gp.noise = {0.002, 0.001, 1e-4};
  gp.output = {1e-5, 5.0};
  sensors::RateGyro gyro(gp);
  sensors::AccelerometerParams ap;
  ap.input_axis_B = dynamics::Vec3::UnitY();
  ap.bandwidth = {sensors::LowpassParams::Order::kFirst, 100.0, 0.0};
  ap.noise = {1e-3, 0.01, 1e-5};
  sensors::Accelerometer accel(ap);
  const sensors::Encoder encoder({8192, 0.1});

  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(4 * ticks));
  for (int k = 0; k < ticks; ++k) {
    const double t = k * 1e-3;
    const models::BaseSample b = base(t);
    out.push_back(sea.sample(k).value);
    out.push_back(gyro.measure(b, gyro_rng));
    out.push_back(accel.measure(b, accel_rng));
    out.push_back(encoder.measure(b.w_B.x() * 10.0));
  }
  return out;
}

TEST(MotionDeterminism, SameSeedGivesBitIdenticalSequences) {
  const auto a = run_scene(2024, 200000), b = run_scene(2024, 200000);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

TEST(MotionDeterminism, DifferentSeedGivesDifferentSeaAndNoise) {
  const auto a = run_scene(2024, 20000), b = run_scene(2025, 20000);
  int sea_same = 0, gyro_same = 0, accel_same = 0;
  for (std::size_t i = 0; i < a.size(); i += 4) {
    sea_same += a[i] == b[i];
    gyro_same += a[i + 1] == b[i + 1];
    accel_same += a[i + 2] == b[i + 2];
  }
  // Continuous values from different phases and noise: no sample should coincide (allow a handful for the
  // quantized outputs crossing the same LSB).
  EXPECT_EQ(sea_same, 0);
  EXPECT_LT(gyro_same, 20);
  EXPECT_LT(accel_same, 20);
}

TEST(MotionDeterminism, StreamsOfOneSeedAreIndependentOfEachOthersUse) {
  // Drawing more from the gyro's stream must not change the sea built from stream 0.
  random::SeededRng s0(9, 0), s1(9, 1);
  for (int i = 0; i < 1000; ++i) s1.gaussian();
  random::SeededRng fresh(9, 0);
  const motion::WaveSpectrum spectrum;
  const motion::IrregularSea<32> a(spectrum, {32, 0, 0, 1.0, 1e-3}, s0),
      b(spectrum, {32, 0, 0, 1.0, 1e-3}, fresh);
  for (int i = 0; i < 32; ++i) EXPECT_EQ(a.phase(i), b.phase(i));
}

}  // namespace motion_determinism_test
}  // namespace gyrostab
