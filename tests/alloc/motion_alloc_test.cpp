// Zero heap allocations in the per-tick path of the suspension motion and sensor models, over 1e6 ticks after
// construction (docs/architecture.md, allocation-free rules). Construction itself is also allocation-free
// (fixed-size arrays only).
#include <gtest/gtest.h>

#include <numbers>

#include "sim/motion/base_vibration.hpp"
#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/motion/regular_wave_moment.hpp"
#include "sim/sensors/accelerometer.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/rate_gyro.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gyrostab {
namespace {

TEST(MotionAlloc, MillionTicksOfSeaBaseMotionAndSensorsAllocateNothing) {
  gyrostab::testing::AllocationCounter construction;
  random::SeededRng sea_rng(1, 0), sensor_rng(1, 1);
  const motion::WaveSpectrum spectrum(
      {motion::WaveSpectrumParams::Kind::kJonswap, 3.0, 9.0, 3.3, 0.07, 0.09});
  motion::IrregularSeaParams sp;
  sp.components = 64;
  sp.grid_period = 1e-3;  // the plant step: RK4 stages on and between grid points
  const motion::IrregularSea<64> sea(spectrum, sp, sea_rng, motion::WaveRollMomentTransfer{1.1772e7, 0.8});
  const motion::RegularWaveMoment regular{2e5, 0.6, 0.0};
  motion::VibratingBase<motion::PrescribedBaseRotation<3>, 2> base;
  base.rotation.roll.count = 3;
  base.rotation.roll.harmonics = {{{0.15, 0.6, 0.0}, {0.03, 1.4, 0.5}, {0.01, 3.0, 1.0}}};
  base.rotation.yaw.rate = 0.01;
  base.rotation.lever_arm_B = {0, 0, 8.0};
  base.vibration.count = 1;
  base.vibration.harmonics[0] = {dynamics::Vec3(0, 0, 1e-4), 2 * std::numbers::pi * 30, 0.0};
  sensors::RateGyroParams gp;
  gp.bandwidth = {sensors::LowpassParams::Order::kSecond, 40.0, 0.7};
  gp.noise = {0.002, 0.001, 1e-4};
  gp.output = {1e-5, 5.0};
  sensors::RateGyro gyro(gp);
  sensors::AccelerometerParams ap;
  ap.noise = {1e-3, 0.01, 1e-5};
  sensors::Accelerometer accel(ap);
  const sensors::Encoder encoder({8192, 0.1});
  EXPECT_EQ(construction.count(), 0u);

  double sink = 0.0;
  gyrostab::testing::AllocationCounter c;
  for (std::int64_t k = 0; k < 1000000; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    // The plant's RK4 stages: t, t + h/2 (twice), t + h on the sea's half-step grid.
    sink += sea(t) + sea(t + 0.5e-3) + sea(t + 0.5e-3) + sea(t + 1e-3);
    sink += regular(t);
    const models::BaseSample b = base(t);
    sink += gyro.measure(b, sensor_rng) + accel.measure(b, sensor_rng);
    sink += static_cast<double>(encoder.counts(sink));
    if (k % 100000 == 0) sink += sea.sample(7 * k + 3).value + sea.at(t).value;  // random access, direct sum
  }
  EXPECT_EQ(c.count(), 0u);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace gyrostab
