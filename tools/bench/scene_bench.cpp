// Closed-loop throughput of every shipped scene, and the per-tick pieces of the ship roll damper's loop.
//
// scene/<name>: `gyrostab run` in-process (tools::run_scene, write_outputs = false, no progress) on each
// sim/scenes/*.toml found at start-up (GYROSTAB_SCENES_DIR overrides the folder), as shipped, for
// min(the scene's own ticks, 200 000) ticks (GYROSTAB_BENCH_TICKS overrides). The time is the closed loop
// only (RunRequest::before_loop/after_loop, manual time): parsing, set-up (sea components, allocations) and
// the report are left out. The benchmark's time is the loop's CPU time (CLOCK_THREAD_CPUTIME_ID: this VM's 2
// cores are shared, and CPU time is what other processes disturb least), so items_per_second = ticks per
// CPU second; wall_tps = ticks per wall second of the same loops; report_tps = the last run's own
// report.json timing.ticks_per_second (wall).
//   build/bin/gyrostab-bench --benchmark_filter='^scene/' --benchmark_repetitions=5
//                            --benchmark_report_aggregates_only=true
//
// ship/<piece>: one tick's share of each piece of the ship scene's loop
// (sim/plants/ship_roll_damper_plant.hpp builds the same objects from the shipped scene's parameters): the
// irregular sea (96 of 256 components), the plant's RK4 step (stabilized ship and the locked reference ship,
// each 4 stages, sea evaluated at every stage), the sensors, the firmware controller (with the
// CLOCK_MONOTONIC counters the run uses and without).
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "firmware/app/ship_roll_damper_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/models/ship_roll_damper.hpp"
#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/wave_spectrum.hpp"
#include "sim/motion/wave_transfer.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/commands.hpp"
#include "sim/plants/ship_in_sea.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_scene.hpp"
#include "tools/scene/loop_config.hpp"
#include "tools/scene/scene_reader.hpp"

namespace {

using namespace gyrostab;
using Clock = std::chrono::steady_clock;

// ---- whole scenes
// ------------------------------------------------------------------------------------------

constexpr std::int64_t kDefaultTicks = 200'000;

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Set by the run's hooks, around the closed loop only.
Clock::time_point wall_start, wall_end;
double cpu_start = 0.0, cpu_end = 0.0;
void mark_loop_start() {
  wall_start = Clock::now();
  cpu_start = thread_cpu_s();
}
void mark_loop_end() {
  cpu_end = thread_cpu_s();
  wall_end = Clock::now();
}

std::int64_t env_ticks() {
  const char* v = std::getenv("GYROSTAB_BENCH_TICKS");
  return v != nullptr ? std::max<std::int64_t>(1, std::atoll(v)) : kDefaultTicks;
}

// The scene's own tick count ([scene] duration_s / [loop] tick_us, with the loader's defaults).
std::int64_t scene_ticks(const std::string& path) {
  tools::SceneReader r;
  if (!r.open(path)) return -1;
  // Only duration and tick are wanted: the integrator list does not matter here, its complaint is ignored.
  return tools::read_loop_config(r, "", {""}).ticks();
}

void BM_Scene(benchmark::State& state, const std::string& path, std::int64_t ticks) {
  nlohmann::json report;
  tools::RunRequest req;
  req.scene_path = path;
  req.progress = false;
  req.write_outputs = false;
  req.ticks = ticks;
  req.before_loop = mark_loop_start;
  req.after_loop = mark_loop_end;
  req.report_out = &report;
  double report_tps = 0.0, wall_s = 0.0;
  for (auto _ : state) {
    const int rc = tools::run_scene(req);
    if (rc != 0) {
      state.SkipWithError(("run_scene returned " + std::to_string(rc)).c_str());
      return;
    }
    state.SetIterationTime(cpu_end - cpu_start);
    wall_s += std::chrono::duration<double>(wall_end - wall_start).count();
    report_tps = report["timing"].value("ticks_per_second", 0.0);
  }
  state.SetItemsProcessed(state.iterations() * ticks);
  state.counters["ticks"] = static_cast<double>(ticks);
  state.counters["report_tps"] = report_tps;
  state.counters["wall_tps"] = static_cast<double>(state.iterations() * ticks) / wall_s;
}

std::string scenes_dir() {
  const char* v = std::getenv("GYROSTAB_SCENES_DIR");
  return v != nullptr ? v : GYROSTAB_SOURCE_DIR "/sim/scenes";
}

// Registered before main (benchmark_main), one benchmark per scene file, in name order.
const bool scenes_registered = [] {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(scenes_dir(), ec)) {
    if (e.path().extension() == ".toml") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    const std::int64_t own = scene_ticks(f.string());
    const std::int64_t ticks = own > 0 ? std::min(own, env_ticks()) : env_ticks();
    benchmark::RegisterBenchmark(("scene/" + f.stem().string()).c_str(), BM_Scene, f.string(), ticks)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

// ---- ship roll damper: the pieces of one tick
// --------------------------------------------------------------

constexpr double kTick = 1e-3;

// The shipped active ship scene as the scene reader reads it (sim/scenes/ship-roll-damper-active.toml).
const tools::ShipRollDamperScene& ship_scene() {
  static const tools::ShipRollDamperScene scene = [] {
    tools::ShipRollDamperScene s;
    tools::SceneReader r;
    if (!r.open(GYROSTAB_SOURCE_DIR "/sim/scenes/ship-roll-damper-active.toml") ||
        !tools::read_ship_roll_damper_scene(r, s)) {
      std::fprintf(stderr, "scene_bench: the shipped ship scene does not read\n");
      std::abort();
    }
    return s;
  }();
  return scene;
}

// The scene's own sea moment (the one its plant and the accuracy study build).
motion::SeaRollMoment make_ship_sea() {
  const tools::ShipRollDamperScene& s = ship_scene();
  return motion::SeaRollMoment(s.plant.sea, kTick, random::SeededRng(s.loop.seed, plants::ShipRollDamperPlant::kSeaStream),
                               s.plant.ship.c);
}

models::ShipRollDamperParams ship_params(bool locked) {
  models::ShipRollDamperParams p = ship_scene().plant.ship;
  p.locked = locked;
  return p;
}

// The step without the sea's cost: a constant wave moment.
struct ConstantMoment {
  double operator()(double) const { return 1e5; }
};

// The sea's share of a tick: one grid step (sample n + 1) and the RK4 stage calls of both plants.
void BM_ShipSeaPerTick(benchmark::State& state) {
  const auto sea = make_ship_sea();
  std::int64_t k = 0;
  for (auto _ : state) {
    const double t = static_cast<double>(k) * kTick;
    ++k;
    double e = 0.0;
    for (int plant = 0; plant < 2; ++plant)
      e += sea(t) + sea(t + 0.5 * kTick) + sea(t + 0.5 * kTick) + sea(t + kTick);
    benchmark::DoNotOptimize(e);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShipSeaPerTick)->Name("ship/sea_8_stage_calls");

// One RK4 step of one plant, with the sea (`with_sea`) or a constant moment; locked = the reference ship.
template <bool kLocked, bool kWithSea>
void BM_ShipPlantStep(benchmark::State& state) {
  using Sea = std::conditional_t<kWithSea, motion::SeaRollMoment, ConstantMoment>;
  const Sea sea = [] {
    if constexpr (kWithSea) {
      return make_ship_sea();
    } else {
      return ConstantMoment{};
    }
  }();
  using Plant = plants::ShipInSeaOf<Sea>;
  Plant plant{models::ShipRollDamper(ship_params(kLocked)), &sea, 0.0, 0.0};
  dynamics::Rk4<Plant> rk4(plant);
  typename Plant::State x = Plant::State::Zero();
  x[models::ShipRollDamper::kRoll] = 0.05;
  x[models::ShipRollDamper::kPrecession] = 0.3;
  std::int64_t k = 0;
  for (auto _ : state) {
    plant.command_Nm = -1e4 * x[models::ShipRollDamper::kPrecessionRate];
    rk4.step(static_cast<double>(k) * kTick, kTick, x);
    ++k;
    benchmark::DoNotOptimize(x.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShipPlantStep<false, false>)->Name("ship/plant_rk4_step");
BENCHMARK(BM_ShipPlantStep<true, false>)->Name("ship/plant_rk4_step_locked");
BENCHMARK(BM_ShipPlantStep<false, true>)->Name("ship/plant_rk4_step_with_sea");

// The derivative alone (one RK4 stage): two sincos and the large-angle terms.
void BM_ShipDerivative(benchmark::State& state) {
  const models::ShipRollDamper ship(ship_params(false));
  models::ShipRollDamper::State x, dx;
  x << 0.05, 0.3, 0.01, 0.02;
  for (auto _ : state) {
    ship.derivative(0.0, x, dx);
    benchmark::DoNotOptimize(dx.data());
    x[models::ShipRollDamper::kRoll] += 1e-9;
    x[models::ShipRollDamper::kPrecession] += 1e-9;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShipDerivative)->Name("ship/plant_derivative");

// The sensor frame's noise and quantization: three Gaussian noises and one encoder read.
void BM_ShipSensors(benchmark::State& state) {
  sensors::SensorNoise angle({1e-4 * std::sqrt(kTick), 0.0, 0.0}, kTick), rate({1e-4, 0.0, 0.0}, kTick),
      prec({1e-4, 0.0, 0.0}, kTick);
  random::SeededRng r1(1, 2), r2(1, 3), r3(1, 4);
  const sensors::Encoder enc(
      {65536, 0.0, sensors::EncoderParams::Mode::kIncremental, sensors::EncoderParams::Rounding::kNearest});
  double beta = 0.1;
  for (auto _ : state) {
    const std::int64_t c = enc.counts(beta);
    benchmark::DoNotOptimize(angle.sample(r1) + rate.sample(r2) + prec.sample(r3) + enc.angle_of(c));
    beta += 1e-7;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShipSensors)->Name("ship/sensors");

// The firmware controller's step (fault monitor, scheduler, active law), with the run's clock or none.
template <class ClockT>
void BM_ShipController(benchmark::State& state) {
  firmware::ShipRollDamperConfig c;
  c.mode = firmware::ShipRollDamperMode::kActive;
  using Controller = firmware::BasicShipRollDamperController<ClockT>;
  if (!Controller::check(c).ok) {
    state.SkipWithError("controller config refused");
    return;
  }
  auto controller = std::make_unique<Controller>(c);
  typename Controller::SensorFrame f{};
  typename Controller::ActuatorFrame out{};
  std::uint64_t k = 0;
  for (auto _ : state) {
    f.tick = k;
    f.time_ns = static_cast<std::int64_t>(k) * 1'000'000;
    f.sample_time_ns = f.time_ns;
    f.sequence = static_cast<std::uint32_t>(k);
    f.roll_rate_rad_s = 0.01 * std::sin(1e-3 * static_cast<double>(k));
    f.precession_angle_rad = 0.2;
    f.precession_rate_rad_s = 0.01;
    controller->step(k, &f, out);
    ++k;
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShipController<firmware::posix::MonotonicClock>)->Name("ship/controller_step_monotonic_clock");
BENCHMARK(BM_ShipController<firmware::NullClock>)->Name("ship/controller_step_null_clock");

// What one CLOCK_MONOTONIC read costs here (the scheduler reads it twice per tick with one task).
void BM_MonotonicClockRead(benchmark::State& state) {
  const firmware::posix::MonotonicClock clock;
  for (auto _ : state) benchmark::DoNotOptimize(clock());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MonotonicClockRead)->Name("ship/clock_gettime_monotonic");

}  // namespace
