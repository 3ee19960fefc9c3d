// The accuracy study on the shipped scenes: the study's open-loop problem is the scene's plant (same inputs,
// same right-hand side: the scene's integrator and step reproduce the closed-loop states bit for bit), the
// quick study runs end to end with a converged reference, and every `gyrostab run` report carries a
// deterministic error estimate whose half-step comparison is right on a closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sim/dynamics/rk4.hpp"
#include "tools/accuracy/accuracy_command.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "tools/accuracy/our_methods.hpp"
#include "tools/accuracy/oscillator_problem.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_problem.hpp"
#include "tools/devices/ship_roll_damper/ship_problem.hpp"
#include "tools/loop/error_estimate_report.hpp"
#include "tools/commands.hpp"

namespace gyrostab::tools::accuracy {
namespace accuracy_scene_test {

const std::string kScenes = GYROSTAB_SOURCE_DIR "/sim/scenes/";

TEST(AccuracyScene, PowerStabilizerProblemReplaysTheClosedLoopBitForBit) {
  SceneReader reader;
  ASSERT_TRUE(reader.open(kScenes + "power-stabilizer.toml"));
  PowerStabilizerStudySetup setup;
  std::string why;
  ASSERT_EQ(power_stabilizer_study_setup(reader, 4000, setup, why), 0) << why;
  ASSERT_EQ(setup.inputs.size(), 4000u);
  PowerStabilizerProblem problem(setup);
  Trajectory<PowerStabilizerProblem::State> traj(4001);
  ASSERT_TRUE(integrate_ours(setup.loop.integrator, problem, setup.loop.substeps, traj).ok);
  for (std::size_t k = 0; k < setup.states.size(); ++k) ASSERT_EQ(traj[k + 1], setup.states[k]) << "tick " << k;
  // Not vacuous: the disturbance step at 1 s and the loop's response moved the gimbals.
  EXPECT_GT(std::abs(setup.states.back()[1]), 1e-3);
  // Another method integrates the same inputs to a nearby but different trajectory.
  Trajectory<PowerStabilizerProblem::State> rk4(4001);
  ASSERT_TRUE(integrate_ours("rk4", problem, 4, rk4).ok);
  EXPECT_NE(rk4.back(), traj.back());
  EXPECT_NEAR(rk4.back()[1], traj.back()[1], 1e-5);
}

TEST(AccuracyScene, ShipProblemReplaysTheClosedLoopBitForBit) {
  for (const char* scene : {"ship-roll-damper-active.toml", "ship-roll-damper-passive.toml"}) {
    SceneReader reader;
    ASSERT_TRUE(reader.open(kScenes + scene));
    ShipRollDamperStudySetup setup;
    ASSERT_EQ(ship_roll_damper_study_setup(reader, 20000, setup), 0) << scene;
    ShipProblem problem(setup);
    Trajectory<ShipProblem::State> traj(20001);
    ASSERT_TRUE(integrate_ours("rk4", problem, setup.loop().substeps, traj).ok);
    for (std::size_t k = 0; k < setup.states.size(); ++k) ASSERT_EQ(traj[k + 1], setup.states[k]) << scene << " tick " << k;
    EXPECT_GT(std::abs(setup.states.back()[0]), 1e-4) << scene;  // the sea rolled the ship
  }
}

TEST(AccuracyScene, QuickStudyOfThePowerStabilizerRunsEndToEnd) {
  AccuracyRequest req;
  req.scene_path = kScenes + "power-stabilizer.toml";
  req.duration_s = 2.0;
  req.quick = true;
  req.progress = false;
  req.write_outputs = false;
  nlohmann::json report;
  req.report_out = &report;
  ASSERT_EQ(run_accuracy(req), 0);
  EXPECT_TRUE(report["reproduces_scene_run"].get<bool>());
  EXPECT_TRUE(report["reference"]["converged"].get<bool>());
  EXPECT_EQ(report["scene"]["ticks"].get<int>(), 2000);
  bool has_ours = false, has_odeint = false, has_cvode = false;
  for (const auto& run : report["runs"]) {
    EXPECT_TRUE(run["ok"].get<bool>()) << run.dump();
    const std::string m = run["method"];
    has_ours = has_ours || run["family"] == "ours";
    has_odeint = has_odeint || m.rfind("odeint", 0) == 0;
    has_cvode = has_cvode || m.rfind("cvode", 0) == 0;
  }
  EXPECT_TRUE(has_ours && has_odeint && has_cvode);
  // The speed-up machinery ran: at the scene's error (the quick grid's peers may not reach it: then null with
  // a note) and at every decade both families reach (its size is timing: not asserted).
  ASSERT_TRUE(report["speed_up"]["at_scene_error"].is_object());
  EXPECT_EQ(report["speed_up"]["at_scene_error"]["ours_method"], "gyro-exponential");
  ASSERT_FALSE(report["speed_up"]["by_error_level"].empty());
  for (const auto& level : report["speed_up"]["by_error_level"]) EXPECT_GT(level["ratio"].get<double>(), 0.0);
}

TEST(AccuracyScene, StudyRefusesASceneItDoesNotTake) {
  AccuracyRequest req;
  req.scene_path = kScenes + "monorail.toml";
  req.quick = true;
  req.progress = false;
  req.write_outputs = false;
  EXPECT_EQ(run_accuracy(req), 2);
}

nlohmann::json run_report(const std::string& scene, std::int64_t ticks) {
  RunRequest req;
  req.scene_path = kScenes + scene;
  req.ticks = ticks;
  req.write_outputs = false;
  req.progress = false;
  nlohmann::json report;
  req.report_out = &report;
  EXPECT_EQ(run_scene(req), 0) << scene;
  return report;
}

TEST(SceneRunErrorEstimate, RunReportsCarryADeterministicHalfStepEstimate) {
  // Power stabilizer: the window is 1 s from the first disturbance step (1 s).
  const nlohmann::json a = run_report("power-stabilizer.toml", 2500);
  const nlohmann::json& e = a["error_estimate"];
  ASSERT_TRUE(e["available"].get<bool>()) << e.dump();
  EXPECT_TRUE(e["reproduces_run"].get<bool>());
  EXPECT_EQ(e["window_ticks"].get<int>(), 1000);
  EXPECT_EQ(e["order"].get<int>(), 2);  // gyro-exponential
  const double alpha = e["max_abs_error"]["alpha_rad"].get<double>();
  EXPECT_GT(alpha, 0.0);
  EXPECT_LT(alpha, 1e-4);  // the 0.1 rad response at 1 kHz: gyro-exponential errs far below 1e-3 of it
  EXPECT_EQ(run_report("power-stabilizer.toml", 2500)["error_estimate"].dump(), e.dump());
  // Ship: the window starts at the statistics (120 s); a shorter run says it did not reach it.
  const nlohmann::json s = run_report("ship-roll-damper-active.toml", 60000);
  EXPECT_FALSE(s["error_estimate"]["available"].get<bool>());
  const nlohmann::json full = run_report("ship-roll-damper-active.toml", 131000);
  ASSERT_TRUE(full["error_estimate"]["available"].get<bool>()) << full["error_estimate"].dump();
  EXPECT_TRUE(full["error_estimate"]["reproduces_run"].get<bool>());
  EXPECT_EQ(full["error_estimate"]["window_ticks"].get<int>(), 10000);
  EXPECT_GT(full["error_estimate"]["max_abs_error"]["roll_rad"].get<double>(), 0.0);
}

// The half-step window on the oscillator: RK4's error over the window, from the saved state, is known in
// closed form (OscillatorProblem::exact); Richardson's (x_h − x_{h/2})·16/15 estimates it to O(ωh) relative.
TEST(SceneRunErrorEstimate, HalfStepWindowEstimatesTheWindowErrorOfRk4) {
  const double omega = 40.0;
  const std::int64_t tick_ns = 5'000'000;  // ωh = 0.2
  OscillatorModel model;
  model.omega2 = omega * omega;
  analysis::HalfStepWindow<OscillatorModel, double> window(100, 200);
  dynamics::Rk4<OscillatorModel> rk4(model);
  dynamics::SubstepDriver<dynamics::Rk4<OscillatorModel>> driver(rk4, tick_ns, 1);
  OscillatorModel::State x(1.0, 0.0);
  OscillatorModel::State at_window = OscillatorModel::State::Zero();
  for (std::int64_t k = 0; k < 400; ++k) {
    model.u = k < 150 ? 0.0 : 300.0;
    if (k == 100) at_window = x;
    window.before_tick(k, x, model.u);
    driver.advance_tick(k, x);
    window.after_tick(k, x);
  }
  const auto apply = [](OscillatorModel& m, const double& u) { m.u = u; };
  const nlohmann::json e =
      error_estimate_json<2>(window.estimate<dynamics::Rk4>(model, apply, tick_ns, 1, 4), {"x", "v"}, "energy, unused here");
  ASSERT_TRUE(e["reproduces_run"].get<bool>());
  // The true error of the run over the window: the run's states against the exact flow from at_window.
  std::vector<double> force(200);
  for (std::size_t i = 0; i < force.size(); ++i) force[i] = 100 + i < 150 ? 0.0 : 300.0;
  OscillatorProblem exact(omega, tick_ns, force, at_window);
  Trajectory<OscillatorModel::State> truth(201), run(201);
  exact.exact(truth);
  OscillatorProblem replay = exact;
  integrate_ours("rk4", replay, 1, run);
  double worst = 0.0;
  for (std::size_t k = 1; k < run.size(); ++k) worst = std::max(worst, std::abs(run[k][0] - truth[k][0]));
  // Richardson's estimate is exact to O(h) relative: at ωh = 0.2 within 15 % (measured ~3 %).
  EXPECT_NEAR(e["max_abs_error"]["x"].get<double>(), worst, 0.15 * worst);
  EXPECT_GT(worst, 1e-6);
}

}  // namespace accuracy_scene_test
}  // namespace gyrostab::tools::accuracy
