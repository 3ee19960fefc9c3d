// Per-tick cost of the power stabilizer's loop with and without each plant component ("only what
// a scene needs"): the same scene (power-stabilizer.toml's gyro and gains) assembled with one component
// more at a time, run as `gyrostab run` runs it (tools::run_scene, outputs in memory); the time is the closed
// loop's CPU time only (RunRequest::before_loop/after_loop), items_per_second = ticks per CPU second.
// plant_tick/<variant>:
//   minimal        rigid, torque motors, full gimbal model, base at rest, no noise, no filter, no friction
//   +noise         rate gyro white noise (two Gaussians per tick)
//   +filter        second-order rate gyro bandwidth (two filter states per gyro)
//   +friction      bearing viscous friction d1, d2 (inside the exact flow: should cost nothing)
//   +base_roll     harmonic base roll (sin/cos and a rotation per derivative evaluation)
//   +electrics     dc drives on both axes (winding current, gear, stick-slip, current loops)
//   +elastic       elastic platform (14.31): 2 more states, RK4
//   precession     the reduced model P0 (3 states, RK4) — the comparison run with the full model is
//                  set-up, outside the timed loop
//   full_100x / precession_100x   spin 100× nominal: the full model needs 3 sub-steps per tick, P0 one
// plant_step/<model>: one plant step alone (integrator + model, no loop), 1 ms.
//   build/bin/gyrostab-bench --benchmark_filter='^plant_' --benchmark_repetitions=5
//                            --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <time.h>

#include <nlohmann/json.hpp>
#include <string>

#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/models/power_stabilizer.hpp"
#include "tools/commands.hpp"

namespace {

using namespace gyrostab;

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
double cpu_start = 0.0, cpu_end = 0.0;
void loop_start() { cpu_start = thread_cpu_s(); }
void loop_end() { cpu_end = thread_cpu_s(); }

constexpr std::int64_t kTicks = 100'000;

const char* kScene = R"(
[scene]
name = "composition"
device = "power_stabilizer"
duration_s = 100.0
seed = 7
[loop]
tick_us = 1000
INTEGRATOR
[gyro]
CR = 0.1
rpm = RPM
AR = 0.5
AJ = 0.5
BJ = 1.0
CJ = 0.3
AA = 1.0
GYRO
[disturbance]
M1_Nm = 20.0
M2_Nm = -10.0
M2_time_s = 3.0
[sensors]
SENSORS
[controller]
k1 = 200.0
k2 = 200.0
d1 = 5.0
d2 = 5.0
SECTIONS
[output]
plots = false
record_every = 100
)";

struct Variant {
  const char* name;
  const char* gyro;
  const char* sensors;
  const char* sections;
  const char* integrator;
  const char* rpm;
};

const char* kDc = R"(
[drive]
kind = "dc_motor"
R_ohm = 0.4
L_H = 0.8e-3
k_t_Nm_per_A = 0.12
J_m_kg_m2 = 6.0e-5
voltage_limit_V = 48.0
current_limit_A = 12.0
gear_ratio = 80.0
current_loop_bandwidth_rad_s = 250.0
)";

const Variant kVariants[] = {
    {"minimal", "", "rate_noise_density = 0.0", "", "", "19098.6"},
    {"+noise", "", "rate_noise_density = 1e-4", "", "", "19098.6"},
    {"+filter", "", "rate_noise_density = 0.0\nrate_bandwidth_hz = 200.0", "", "", "19098.6"},
    {"+friction", "d1 = 0.05\nd2 = 0.05", "rate_noise_density = 0.0", "", "", "19098.6"},
    {"+base_roll", "", "rate_noise_density = 0.0", "[base]\nroll_amplitude_rad = 0.05", "", "19098.6"},
    {"+electrics", "", "rate_noise_density = 0.0", kDc, "", "19098.6"},
    {"+elastic", "structure = \"elastic\"\nc = 2.0e4\nAP = 200.0", "rate_noise_density = 0.0", "", "", "19098.6"},
    {"precession", "fidelity = \"precession\"", "rate_noise_density = 0.0", "", "", "19098.6"},
    {"full_100x", "", "rate_noise_density = 0.0", "", "plant_substeps = 3", "1909860.0"},
    {"precession_100x", "fidelity = \"precession\"", "rate_noise_density = 0.0", "", "", "1909860.0"},
};

std::string text_of(const Variant& v) {
  std::string s = kScene;
  const auto put = [&s](const std::string& key, const std::string& value) { s.replace(s.find(key), key.size(), value); };
  put("INTEGRATOR", v.integrator);
  put("RPM", v.rpm);
  put("GYRO", v.gyro);
  put("SENSORS", v.sensors);
  put("SECTIONS", v.sections);
  return s;
}

void BM_PlantTick(benchmark::State& state, const Variant* v) {
  nlohmann::json report;
  tools::RunRequest req;
  req.scene_path = std::string("composition-") + v->name + ".toml";
  req.scene_text = text_of(*v);
  req.progress = false;
  req.write_outputs = false;
  req.ticks = kTicks;
  req.before_loop = loop_start;
  req.after_loop = loop_end;
  req.report_out = &report;
  for (auto _ : state) {
    if (tools::run_scene(req) != 0) {
      state.SkipWithError("scene refused");
      return;
    }
    state.SetIterationTime(cpu_end - cpu_start);
  }
  state.SetItemsProcessed(state.iterations() * kTicks);
  state.counters["state_size"] = report["plant"].value("state_size", 0);
  state.counters["device_bytes"] = report["plant"].value("device_bytes", 0);
  state.counters["ns_per_tick"] = benchmark::Counter(static_cast<double>(kTicks) * 1e-9,
                                                     benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}

const bool registered = [] {
  for (const Variant& v : kVariants) {
    benchmark::RegisterBenchmark((std::string("plant_tick/") + v.name).c_str(), BM_PlantTick, &v)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

// ---- one plant step alone --------------------------------------------------------------------------------

models::GimbalGyroParams gyro() {
  models::GimbalGyroParams p;
  p.CR = 0.1;
  p.AR = 0.5;
  p.AJ = 0.5;
  p.BJ = 1.0;
  p.CJ = 0.3;
  p.AA = 1.0;
  p.d1 = p.d2 = 0.05;
  return p;
}

template <class Plant, template <class> class Integrator>
void BM_PlantStep(benchmark::State& state, Plant plant, typename Plant::State x) {
  Integrator<Plant> integ(plant);
  plant.inputs.M1S = 20.0;
  std::int64_t k = 0;
  for (auto _ : state) {
    plant.inputs.M1K = -200.0 * x[1];
    integ.step(1e-3 * static_cast<double>(k++), 1e-3, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.SetItemsProcessed(state.iterations());
}

using Rolling = models::HarmonicBaseRotation;
using Full = models::PowerStabilizer<Rolling, models::TorqueMotors, models::RigidStructure>;
using Fixed = models::PowerStabilizer<models::FixedBase, models::TorqueMotors, models::RigidStructure>;
using P0 = models::PowerStabilizer<Rolling, models::TorqueMotors, models::RigidStructure, models::PrecessionOnly>;
using Elastic = models::PowerStabilizer<Rolling, models::TorqueMotors, models::ElasticPlatform>;
const Rolling kStill{dynamics::Vec3::UnitX(), 0.0, 0.8, dynamics::Vec3::UnitZ()};
const Rolling kRolling{dynamics::Vec3::UnitX(), 0.05, 0.8, dynamics::Vec3::UnitZ()};

void BM_StepFixedBaseFull(benchmark::State& st) {
  BM_PlantStep<Fixed, dynamics::GyroscopicExponential>(st, Fixed(gyro()), Fixed::make_state(0, 0, 0, 0, 200.0));
}
void BM_StepStillBaseFull(benchmark::State& st) {
  BM_PlantStep<Full, dynamics::GyroscopicExponential>(st, Full(gyro(), {}, {}, kStill), Full::make_state(0, 0, 0, 0, 200.0));
}
void BM_StepRollingBaseFull(benchmark::State& st) {
  BM_PlantStep<Full, dynamics::GyroscopicExponential>(st, Full(gyro(), {}, {}, kRolling),
                                                      Full::make_state(0, 0, 0, 0, 200.0));
}
void BM_StepStillBaseFullRk4(benchmark::State& st) {
  BM_PlantStep<Full, dynamics::Rk4>(st, Full(gyro(), {}, {}, kStill), Full::make_state(0, 0, 0, 0, 200.0));
}
void BM_StepStillBasePrecession(benchmark::State& st) {
  BM_PlantStep<P0, dynamics::Rk4>(st, P0(gyro(), {}, {}, kStill), P0::make_state(0, 0, 200.0));
}
void BM_StepStillBaseElastic(benchmark::State& st) {
  BM_PlantStep<Elastic, dynamics::Rk4>(st, Elastic(gyro(), {}, {2.0e4, 200.0}, kStill),
                                       Elastic::make_state(0, 0, 0, 0, 200.0, 0, 0));
}
BENCHMARK(BM_StepFixedBaseFull)->Name("plant_step/fixed_base_full_gyro_exponential");
BENCHMARK(BM_StepStillBaseFull)->Name("plant_step/still_harmonic_base_full_gyro_exponential");
BENCHMARK(BM_StepRollingBaseFull)->Name("plant_step/rolling_base_full_gyro_exponential");
BENCHMARK(BM_StepStillBaseFullRk4)->Name("plant_step/still_base_full_rk4");
BENCHMARK(BM_StepStillBasePrecession)->Name("plant_step/still_base_precession_rk4");
BENCHMARK(BM_StepStillBaseElastic)->Name("plant_step/still_base_elastic_rk4");

}  // namespace
