// `gyrostab accuracy` on a power-stabilizer scene: the closed loop recorded through a tap on the scene's own
// plant (the rigid gyro with torque motors: the variants that add states or step a drive inside the tick are
// not in the study), then the study's grid over the power-stabilizer problem (power_stabilizer_problem.hpp).
#include "tools/devices/power_stabilizer/power_stabilizer_study.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/power_stabilizer_outputs.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "tools/accuracy/accuracy_study.hpp"
#include "tools/accuracy/study_entry.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_problem.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_scene.hpp"
#include "tools/loop/closed_loop.hpp"

namespace gyrostab::tools {
namespace {

using Controller = firmware::BasicPowerStabilizerController<firmware::posix::MonotonicClock>;

// The scene's plant, recording after every tick what it held over the tick and the state it reached.
template <template <class> class Integrator>
class RecordingPlant {
 public:
  using Plant = plants::PowerStabilizerPlant<models::TorqueMotors, models::RigidStructure, false, Integrator>;
  RecordingPlant(const PowerStabilizerScene& s, PowerStabilizerStudySetup& out)
      : plant_(s.plant, s.loop.plant_timing()), out_(out) {}
  using SensorFrame = typename Plant::SensorFrame;
  using ActuatorFrame = typename Plant::ActuatorFrame;
  using Record = msg::power_stabilizer::Record;
  void sense(std::int64_t tick, SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const ActuatorFrame& cmd) { plant_.actuate(cmd); }
  void advance(std::int64_t tick) {
    plant_.begin_tick(tick);
    plant_.integrate(tick, peaks_);
    plant_.end_tick(tick);
    out_.inputs.push_back(plant_.inputs());
    out_.states.push_back(plant_.state());
  }
  bool finite() const { return plant_.finite(); }
  void record(Record&) const {}
  nlohmann::json figures() const { return nlohmann::json::object(); }

 private:
  Plant plant_;
  analysis::DrivePeaks peaks_;
  PowerStabilizerStudySetup& out_;
};

template <template <class> class Integrator>
int record_study_inputs(const PowerStabilizerScene& scene, const LoopConfig& loop, PowerStabilizerStudySetup& out) {
  const std::int64_t ticks = loop.ticks();
  out.inputs.reserve(static_cast<std::size_t>(ticks));
  out.states.reserve(static_cast<std::size_t>(ticks));
  PlantPortOf<RecordingPlant<Integrator>> plant(scene, out);
  ControllerPortOf<Controller> controller(scene.controller);
  const LoopOutcome o = run_closed_loop(plant, controller, loop, nullptr);
  out.closed_loop_wall_s = o.wall_s;
  return o.diverged ? 3 : 0;
}

// The nutation ω_N = H/sqrt(AB) is the fastest mode (115 rad/s for the shipped scene, 1155 for the fast
// rotor). The reference takes ω_N h ≤ 0.0025 at its coarser step (RK4's error there is ~1e-13 of the nutation
// amplitude); the sweeps reach one or two decades below the scene's own error.
accuracy::StudyGrid power_stabilizer_grid(bool quick, double nutation_rad_s, double tick_s) {
  const double wh = nutation_rad_s * tick_s;  // ω_N h at one step per tick
  accuracy::StudyGrid g;
  g.reference_substeps = std::max(quick ? 32 : 64, accuracy::pow2_at_least(wh / 0.0025));
  if (quick) {
    g.ours = {{"gyro-exponential", {1, 2}}, {"rk4", {1, 2}}, {"implicit-midpoint", {1}}};
    g.odeint_rk4_substeps = {1, 2};
    g.odeint_dopri5_tolerances = {1e-8};
    g.cvode_bdf_tolerances = {1e-8};
    g.cvode_adams_tolerances = {1e-8};
    return g;
  }
  const bool fast = wh > 0.5;
  const std::vector<int> rk4 = fast ? std::vector<int>{1, 2, 4, 8, 16, 32} : std::vector<int>{1, 2, 4, 8};
  g.ours = {{"gyro-exponential", {1, 2, 4, 8}}, {"rk4", rk4}, {"implicit-midpoint", {1, 4}}};
  g.odeint_rk4_substeps = rk4;
  // The fast rotor's own error is ~7e-12: Dopri5 to 1e-13 so that a peer run reaches it.
  g.odeint_dopri5_tolerances = fast ? std::vector<double>{1e-5, 1e-7, 1e-9, 1e-11, 1e-12, 1e-13}
                                    : std::vector<double>{1e-5, 1e-7, 1e-9, 1e-11};
  g.cvode_bdf_tolerances = {1e-5, 1e-7, 1e-9};
  g.cvode_adams_tolerances = {1e-5, 1e-7, 1e-9};
  return g;
}

}  // namespace

int power_stabilizer_study_setup(SceneReader& reader, std::int64_t ticks, PowerStabilizerStudySetup& out,
                                 std::string& why) {
  auto scene = std::make_unique<PowerStabilizerScene>();
  if (!read_power_stabilizer_scene(reader, *scene)) return 2;
  if (scene->elastic() || scene->back_emf() || scene->dc_drive() || scene->precession()) {
    why = "the accuracy study takes the rigid power stabilizer with torque motors; this scene has " +
          std::string(scene->elastic()    ? "an elastic platform"
                      : scene->back_emf() ? "a back-EMF motor"
                      : scene->dc_drive() ? "dc drives"
                                          : "the precession model (fidelity = \"precession\")");
    return 4;
  }
  out.loop = scene->loop;
  out.scene_duration_s = scene->loop.duration_s;
  if (ticks >= 0) out.loop.duration_s = static_cast<double>(ticks) * out.loop.tick_s();
  out.plant_gyro = scene->plant.gyro;
  if (scene->plant.base.kind != motion::BaseMotionKind::kHarmonicRoll || scene->plant.base.vibration.count > 0) {
    why = "the accuracy study takes the harmonic base roll ([base]) alone; this scene's [motion] adds another motion";
    return 4;
  }
  out.base = scene->plant.base.harmonic;
  out.H = scene->plant.H;
  if (scene->loop.integrator == "rk4") return record_study_inputs<dynamics::Rk4>(*scene, out.loop, out);
  return record_study_inputs<dynamics::GyroscopicExponential>(*scene, out.loop, out);
}

int power_stabilizer_accuracy(SceneReader& reader, const AccuracyRequest& req) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  // Read once with no ticks to learn the tick, then record exactly the window (default: the whole scene).
  auto setup = std::make_unique<PowerStabilizerStudySetup>();
  std::string why;
  int rc = power_stabilizer_study_setup(reader, 0, *setup, why);
  if (rc == 0) {
    const std::int64_t n =
        accuracy::window_ticks(req, setup->scene_duration_s, setup->scene_duration_s, setup->loop);
    setup = std::make_unique<PowerStabilizerStudySetup>();
    SceneReader again;
    again.open(req.scene_path);
    rc = power_stabilizer_study_setup(again, n, *setup, why);
  }
  for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
  if (rc == 4) std::fprintf(stderr, "%s: %s\n", req.scene_path.c_str(), why.c_str());
  if (rc != 0) return rc == 3 ? 3 : 2;
  const double setup_s = std::chrono::duration<double>(Clock::now() - start).count();
  accuracy::PowerStabilizerProblem problem(*setup);
  accuracy::StudyResult result;
  accuracy::fill_scene(result, setup->loop, setup->closed_loop_wall_s);
  const double nutation = setup->H / std::sqrt(setup->plant_gyro.A() * setup->plant_gyro.B());
  accuracy::run_study(problem, power_stabilizer_grid(req.quick, nutation, setup->loop.tick_s()),
                      accuracy::study_options(req), result, &setup->states);
  return accuracy::finish_study(req, result, setup_s);
}

}  // namespace gyrostab::tools
