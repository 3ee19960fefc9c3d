#include <benchmark/benchmark.h>
#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/sensors/rate_gyro.hpp"
using namespace gyrostab;
template <int N>
static motion::IrregularSea<N> make_sea(int n) {
  random::SeededRng rng(1);
  motion::IrregularSeaParams p; p.components = n; p.grid_period = 1e-3;
  return motion::IrregularSea<N>(motion::WaveSpectrum{}, p, rng);
}
static void BM_SeaGridSequential64(benchmark::State& st) {
  auto sea = make_sea<64>(64); std::int64_t n = 0;
  for (auto _ : st) benchmark::DoNotOptimize(sea.sample(n++).value);
}
BENCHMARK(BM_SeaGridSequential64);
static void BM_SeaGridSequential128(benchmark::State& st) {
  auto sea = make_sea<128>(128); std::int64_t n = 0;
  for (auto _ : st) benchmark::DoNotOptimize(sea.sample(n++).value);
}
BENCHMARK(BM_SeaGridSequential128);
static void BM_SeaDirect64(benchmark::State& st) {
  auto sea = make_sea<64>(64); double t = 0;
  for (auto _ : st) { benchmark::DoNotOptimize(sea.at(t).value); t += 1e-3; }
}
BENCHMARK(BM_SeaDirect64);
static void BM_SeaRk4StepOfFourCalls64(benchmark::State& st) {
  random::SeededRng rng(1);
  motion::IrregularSeaParams p; p.components = 64; p.grid_period = 1e-3;
  const motion::IrregularSea<64> sea(motion::WaveSpectrum{}, p, rng);
  std::int64_t k = 0;
  for (auto _ : st) { const double t = static_cast<double>(k) * 1e-3; ++k;
    benchmark::DoNotOptimize(sea(t) + sea(t + 0.5e-3) + sea(t + 0.5e-3) + sea(t + 1e-3)); }
}
BENCHMARK(BM_SeaRk4StepOfFourCalls64);
static void BM_RateGyroSecondOrderNoiseBias(benchmark::State& st) {
  sensors::RateGyroParams gp; gp.bandwidth = {sensors::LowpassParams::Order::kSecond, 40.0, 0.7};
  gp.noise = {0.002, 0.001, 1e-4}; gp.output = {1e-5, 5.0};
  sensors::RateGyro g(gp); random::SeededRng rng(3); double u = 0.1;
  for (auto _ : st) { benchmark::DoNotOptimize(g.measure(u, rng)); u += 1e-9; }
}
BENCHMARK(BM_RateGyroSecondOrderNoiseBias);
static void BM_Gaussian(benchmark::State& st) { random::SeededRng rng(3);
  for (auto _ : st) benchmark::DoNotOptimize(rng.gaussian()); }
BENCHMARK(BM_Gaussian);
static void BM_PrescribedRotation(benchmark::State& st) {
  motion::PrescribedBaseRotation<2> m; m.roll.count = 2; m.roll.harmonics[0] = {0.1, 0.6, 0}; m.roll.harmonics[1] = {0.02, 1.3, 0};
  m.pitch.count = 1; m.pitch.harmonics[0] = {0.05, 0.8, 0}; double t = 0;
  for (auto _ : st) { benchmark::DoNotOptimize(m(t)); t += 1e-3; }
}
BENCHMARK(BM_PrescribedRotation);
