#include "tools/accuracy/accuracy_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "tools/accuracy/accuracy_study.hpp"
#include "tools/accuracy/power_stabilizer_problem.hpp"
#include "tools/accuracy/ship_problem.hpp"
#include "tools/accuracy/study_report.hpp"
#include "tools/devices/power_stabilizer_study.hpp"
#include "tools/devices/ship_roll_damper_study.hpp"

namespace gyrostab::tools {
namespace {

using accuracy::StudyGrid;
using accuracy::StudyOptions;
using accuracy::StudyResult;

// The smallest power of two ≥ x (x ≥ 1).
int pow2_at_least(double x) {
  int n = 1;
  while (n < x && n < (1 << 20)) n *= 2;
  return n;
}

// Power stabilizer: the nutation ω_N = H/sqrt(AB) is the fastest mode (115 rad/s for the shipped scene, 1155 for
// the fast rotor). The reference takes ω_N h ≤ 0.0025 at its coarser step (RK4's error there is ~1e-13 of
// the nutation amplitude); the sweeps reach one or two decades below the scene's own error.
StudyGrid power_stabilizer_grid(bool quick, double nutation_rad_s, double tick_s) {
  const double wh = nutation_rad_s * tick_s;  // ω_N h at one step per tick
  StudyGrid g;
  g.reference_substeps = std::max(quick ? 32 : 64, pow2_at_least(wh / 0.0025));
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
  g.odeint_dopri5_tolerances = {1e-5, 1e-7, 1e-9, 1e-11};
  g.cvode_bdf_tolerances = {1e-5, 1e-7, 1e-9};
  g.cvode_adams_tolerances = {1e-5, 1e-7, 1e-9};
  return g;
}

// Ship: slow modes (roll 0.6 rad/s, coupling H/sqrt(AB) 1.5 rad/s); the 1 ms tick is the finest time scale
// of the inputs, so every method takes at least one step per tick, and RK4 is at round-off there already.
StudyGrid ship_grid(bool quick) {
  StudyGrid g;
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

std::int64_t window_ticks(const AccuracyRequest& req, double default_s, double scene_s, const LoopConfig& loop) {
  const double s = req.duration_s > 0.0 ? req.duration_s : std::min(default_s, scene_s);
  return std::max<std::int64_t>(1, std::llround(s / loop.tick_s()));
}

void fill_scene(StudyResult& r, const LoopConfig& loop, double closed_loop_wall_s) {
  r.scene = loop.name;
  r.device = loop.device;
  r.scene_method = loop.integrator;
  r.scene_substeps = loop.substeps;
  r.closed_loop_wall_s = closed_loop_wall_s;
}

void print_problems(const SceneReader& reader) {
  for (const auto& e : reader.errors()) std::fprintf(stderr, "%s\n", e.c_str());
}

int finish(const AccuracyRequest& req, StudyResult& result, double setup_wall_s) {
  result.total_wall_s += setup_wall_s;
  std::printf("%s", accuracy::format_table(result).c_str());
  if (req.report_out) *req.report_out = accuracy::study_json(result);
  if (req.write_outputs) {
    std::string error;
    if (!accuracy::write_study_outputs(result, req.out_dir, req.plot, error)) {
      std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
      return 3;
    }
    std::printf("%s: wrote %s/report.json, accuracy.csv%s\n", req.scene_path.c_str(), req.out_dir.c_str(),
                req.plot ? ", work_precision.png" : "");
  }
  if (!result.reference.converged) {
    std::fprintf(stderr, "gyrostab: %s: the reference is not converged: see report.json \"reference\" and docs/accuracy.md\n",
                 req.scene_path.c_str());
    return 4;
  }
  return 0;
}

}  // namespace

int run_accuracy(const AccuracyRequest& req) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  SceneReader reader;
  if (!reader.open(req.scene_path)) {
    print_problems(reader);
    return 2;
  }
  const std::string device = reader.text("scene", "device", "", "device model");
  StudyOptions opt;
  opt.repeats = req.quick ? 1 : std::max(1, req.repeats);
  opt.progress = req.progress;
  if (device == "power_stabilizer") {
    // Read once with no ticks to learn the tick, then record exactly the window (default: the whole scene).
    auto setup = std::make_unique<PowerStabilizerStudySetup>();
    std::string why;
    int rc = power_stabilizer_study_setup(reader, 0, *setup, why);
    if (rc == 0) {
      const std::int64_t n = window_ticks(req, setup->scene_duration_s, setup->scene_duration_s, setup->loop);
      setup = std::make_unique<PowerStabilizerStudySetup>();
      SceneReader again;
      again.open(req.scene_path);
      rc = power_stabilizer_study_setup(again, n, *setup, why);
    }
    print_problems(reader);
    if (rc == 4) std::fprintf(stderr, "%s: %s\n", req.scene_path.c_str(), why.c_str());
    if (rc != 0) return rc == 3 ? 3 : 2;
    const double setup_s = std::chrono::duration<double>(Clock::now() - start).count();
    accuracy::PowerStabilizerProblem problem(*setup);
    StudyResult result;
    fill_scene(result, setup->loop, setup->closed_loop_wall_s);
    const double nutation = setup->H / std::sqrt(setup->plant_gyro.A() * setup->plant_gyro.B());
    accuracy::run_study(problem, power_stabilizer_grid(req.quick, nutation, setup->loop.tick_s()), opt, result,
                        &setup->states);
    return finish(req, result, setup_s);
  }
  if (device == "ship_roll_damper") {
    auto setup = std::make_unique<ShipRollDamperStudySetup>();
    // The ship scenes run 900 s; the study's default window is the first 30 s (three roll periods).
    int rc = ship_roll_damper_study_setup(reader, 0, *setup);
    if (rc == 0) {
      const std::int64_t n = window_ticks(req, 30.0, setup->scene_duration_s, setup->loop);
      setup = std::make_unique<ShipRollDamperStudySetup>();
      SceneReader again;
      again.open(req.scene_path);
      rc = ship_roll_damper_study_setup(again, n, *setup);
    }
    print_problems(reader);
    if (rc != 0) return rc == 3 ? 3 : 2;
    const double setup_s = std::chrono::duration<double>(Clock::now() - start).count();
    accuracy::ShipProblem problem(*setup);
    StudyResult result;
    fill_scene(result, setup->loop, setup->closed_loop_wall_s);
    accuracy::run_study(problem, ship_grid(req.quick), opt, result, &setup->states);
    return finish(req, result, setup_s);
  }
  print_problems(reader);
  std::fprintf(stderr, "%s: the accuracy study takes power_stabilizer and ship_roll_damper scenes, not \"%s\"\n",
               req.scene_path.c_str(), device.c_str());
  return 2;
}

}  // namespace gyrostab::tools
