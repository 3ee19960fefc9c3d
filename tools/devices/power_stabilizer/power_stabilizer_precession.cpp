// The power stabilizer in the precession model P0 (10.19)-(10.22). In process, the full model runs the scene
// first with α, β traced, and P0 is then compared with it tick by tick (tools/loop/model_comparison.hpp); a
// plant process or a re-simulation runs P0 alone.
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_run.hpp"
#include "tools/loop/closed_loop.hpp"
#include "tools/loop/model_comparison.hpp"

namespace gyrostab::tools {
namespace {

using Controller = firmware::BasicPowerStabilizerController<firmware::posix::MonotonicClock>;

template <class Motor>
std::unique_ptr<PlantPort> make(const PowerStabilizerScene& scene, const PlantOptions& options) {
  using Reduced = PowerStabilizerRun<Motor, models::RigidStructure, false, dynamics::Rk4, models::PrecessionOnly>;
  using Full = PowerStabilizerRun<Motor, models::RigidStructure, false, dynamics::GyroscopicExponential>;
  if (!options.in_process) return make_plant_port<Reduced>(scene);
  // The full model on the same scene, with the loop its own step validation needs.
  auto full_scene = std::make_unique<PowerStabilizerScene>(scene);
  full_scene->loop = scene.full_loop;
  auto full = std::make_unique<Full>(*full_scene);
  LoopConfig cfg = full_scene->loop;
  if (options.ticks >= 0) cfg.duration_s = static_cast<double>(options.ticks) * cfg.tick_s();
  auto trace = std::make_unique<ComparisonTrace>();
  trace->size_for(cfg.ticks(), Full::kComparedSignals);
  PlantPortOf<TracingDevice<Full>> tracing(*full, *trace);
  ControllerPortOf<Controller> controller(full_scene->controller);
  const LoopOutcome fo = run_closed_loop(tracing, controller, cfg, nullptr, false);
  ComparisonSetup setup;
  setup.expected = scene.reduced_expected;
  setup.full_wall_s = fo.wall_s;
  setup.full_ticks = fo.ticks_run;
  setup.full_diverged = fo.diverged;
  setup.full_diverged_tick = fo.diverged_tick;
  setup.full_substeps = cfg.substeps;
  setup.full_integrator = cfg.integrator;
  return make_plant_port<ComparingDevice<Reduced>>(std::move(trace), std::move(setup), scene);
}

}  // namespace

std::unique_ptr<PlantPort> make_power_stabilizer_precession(const PowerStabilizerScene& s, const PlantOptions& o) {
  return s.back_emf() ? make<models::BackEmfMotor>(s, o) : make<models::TorqueMotors>(s, o);
}

}  // namespace gyrostab::tools
