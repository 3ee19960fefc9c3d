// `gyrostab accuracy` on a ship-roll-damper scene: the closed loop recorded through a tap on the scene's own
// plant, then the study's grid over the ship problem (ship_problem.hpp).
#include "tools/devices/ship_roll_damper/ship_roll_damper_study.hpp"

#include <chrono>
#include <cstdio>
#include <memory>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "tools/accuracy/accuracy_study.hpp"
#include "tools/accuracy/study_entry.hpp"
#include "tools/devices/ship_roll_damper/ship_problem.hpp"
#include "tools/loop/closed_loop.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::ShipRollDamperPlant;
using Controller = firmware::BasicShipRollDamperController<firmware::posix::MonotonicClock>;

// The scene's plant, recording after every tick what it held over the tick and the state it reached.
class RecordingShip {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;

  RecordingShip(const ShipRollDamperScene& s, ShipRollDamperStudySetup& out)
      : plant_(s.plant, s.loop.plant_timing()), out_(out) {}
  void sense(std::int64_t tick, SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const ActuatorFrame& cmd) { plant_.actuate(cmd); }
  void advance(std::int64_t tick) {
    out_.inputs.push_back(plant_.held_inputs());
    plant_.advance(tick);
    out_.states.push_back(plant_.state());
  }
  bool finite() const { return plant_.finite(); }
  nlohmann::json figures() const { return nlohmann::json::object(); }

 private:
  Plant plant_;
  ShipRollDamperStudySetup& out_;
};

// Slow modes (roll 0.6 rad/s, coupling H/sqrt(AB) 1.5 rad/s); the 1 ms tick is the finest time scale of the
// inputs, so every method takes at least one step per tick, and RK4 is at round-off there already.
accuracy::StudyGrid ship_grid(bool quick) {
  accuracy::StudyGrid g;
  g.reference_substeps = 8;
  if (quick) {
    g.ours = {
        {"rk4", {1}}, {"held-input-adams4", {1, 2}}, {"gyro-exponential", {1, 2}}, {"implicit-midpoint", {1}}};
    g.odeint_rk4_substeps = {1};
    g.odeint_dopri5_tolerances = {1e-8};
    g.cvode_bdf_tolerances = {1e-8};
    g.cvode_adams_tolerances = {1e-8};
    return g;
  }
  g.ours = {{"rk4", {1, 2, 4}},
            {"held-input-adams4", {1, 2, 4, 8}},
            {"gyro-exponential", {1, 2, 4, 8}},
            {"implicit-midpoint", {1, 4}}};
  g.odeint_rk4_substeps = {1, 2, 4};
  g.odeint_dopri5_tolerances = {1e-6, 1e-8, 1e-10};
  g.cvode_bdf_tolerances = {1e-6, 1e-9};
  g.cvode_adams_tolerances = {1e-6, 1e-9};
  return g;
}

}  // namespace

int ship_roll_damper_study_setup(SceneReader& reader, std::int64_t ticks, ShipRollDamperStudySetup& out) {
  if (!read_ship_roll_damper_scene(reader, out.scene)) return 2;
  out.scene_duration_s = out.scene.loop.duration_s;
  if (ticks >= 0) out.scene.loop.duration_s = static_cast<double>(ticks) * out.scene.loop.tick_s();
  const std::int64_t n = out.scene.loop.ticks();
  out.inputs.reserve(static_cast<std::size_t>(n));
  out.states.reserve(static_cast<std::size_t>(n));
  PlantPortOf<RecordingShip> plant(out.scene, out);
  ControllerPortOf<Controller> controller(out.scene.controller);
  const LoopOutcome o = run_closed_loop(plant, controller, out.scene.loop, nullptr);
  out.closed_loop_wall_s = o.wall_s;
  return o.diverged ? 3 : 0;
}

int ship_roll_damper_accuracy(SceneReader& reader, const AccuracyRequest& req) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto setup = std::make_unique<ShipRollDamperStudySetup>();
  // The ship scenes run 900 s; the study's default window is the first 30 s (three roll periods).
  int rc = ship_roll_damper_study_setup(reader, 0, *setup);
  if (rc == 0) {
    const std::int64_t n = accuracy::window_ticks(req, 30.0, setup->scene_duration_s, setup->loop());
    setup = std::make_unique<ShipRollDamperStudySetup>();
    SceneReader again;
    again.open(req.scene_path);
    rc = ship_roll_damper_study_setup(again, n, *setup);
  }
  for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
  if (rc != 0) return rc == 3 ? 3 : 2;
  const double setup_s = std::chrono::duration<double>(Clock::now() - start).count();
  accuracy::ShipProblem problem(*setup);
  accuracy::StudyResult result;
  accuracy::fill_scene(result, setup->loop(), setup->closed_loop_wall_s);
  accuracy::run_study(problem, ship_grid(req.quick), accuracy::study_options(req), result, &setup->states);
  return accuracy::finish_study(req, result, setup_s);
}

}  // namespace gyrostab::tools
