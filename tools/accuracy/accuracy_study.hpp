// The grid runner: one study problem integrated by every method of the grid (ours × sub-steps per tick,
// odeint RK4 × sub-steps, odeint Dopri5 × tolerances, CVODE BDF and Adams × tolerances), each run timed
// `repeats` times and measured against one reference with the problem's own error measure.
//
// Timing: the thread's CPU time (CLOCK_THREAD_CPUTIME_ID) of integrating the whole window, tick by tick, with
// the inputs set at every tick and the state stored at every tick boundary — the same loop for every method.
// CPU time, not wall time, because the study shares a 2-core machine: wall time also counts the time the
// thread waited for a core (the wall time is kept in the outputs). The repeats are interleaved (repeat r runs
// the whole grid before repeat r + 1 starts), so a slow spell of the machine hits every method alike; a run's
// time is the median of its repeats, and the speed-up's spread is taken over the repeats (work_precision.hpp).
// Reference: the problem's analytic oracle if it has one, else our rk4 at `reference_substeps` and twice
// that per tick — the finer run is the reference and the difference of the two shows its convergence
// (study_result.hpp, ReferenceInfo).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "tools/accuracy/cvode_peer.hpp"
#include "tools/accuracy/odeint_peer.hpp"
#include "tools/accuracy/our_methods.hpp"
#include "tools/accuracy/study_problem.hpp"
#include "tools/accuracy/study_options.hpp"
#include "tools/accuracy/study_result.hpp"

namespace gyrostab::tools::accuracy {

inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}


template <class Problem>
IntegrationOutcome integrate_spec(const RunSpec& s, Problem& p, Trajectory<typename Problem::State>& out) {
  if (s.family == Family::kOurs) return integrate_ours(s.method, p, s.substeps, out);
  if (s.method == "odeint-rk4") return integrate_odeint_rk4(p, s.substeps, out);
  if (s.method == "odeint-dopri5") return integrate_odeint_dopri5(p, s.tolerance, out);
  if (s.method == "cvode-bdf") return integrate_cvode(p, CvodeMethod::kBdf, s.tolerance, out);
  if (s.method == "cvode-adams") return integrate_cvode(p, CvodeMethod::kAdams, s.tolerance, out);
  IntegrationOutcome o;
  o.error = "unknown method " + s.method;
  return o;
}

template <class Problem>
std::vector<RunSpec> grid_specs(const StudyGrid& g) {
  std::vector<RunSpec> specs;
  for (const auto& [method, substeps] : g.ours) {
    if (!our_method_applies<Problem>(method)) continue;
    for (int n : substeps) specs.push_back({method, Family::kOurs, n, 0.0});
  }
  for (int n : g.odeint_rk4_substeps) specs.push_back({"odeint-rk4", Family::kPeer, n, 0.0});
  for (double t : g.odeint_dopri5_tolerances) specs.push_back({"odeint-dopri5", Family::kPeer, 0, t});
  for (double t : g.cvode_bdf_tolerances) specs.push_back({"cvode-bdf", Family::kPeer, 0, t});
  for (double t : g.cvode_adams_tolerances) specs.push_back({"cvode-adams", Family::kPeer, 0, t});
  return specs;
}

// Fills result.quantities, .reference, .runs (result's scene fields are the caller's). `scene_states`, if
// given, are the closed-loop states after every tick: the scene configuration's run must reproduce them.
template <class Problem>
void run_study(Problem& p, const StudyGrid& grid, const StudyOptions& opt, StudyResult& result,
               const std::vector<typename Problem::State>* scene_states = nullptr) {
  using State = typename Problem::State;
  using Clock = std::chrono::steady_clock;
  const auto study_start = Clock::now();
  const std::size_t nq = Problem::kQuantities;
  const auto qs = p.quantities();
  result.quantities.assign(qs.begin(), qs.end());
  result.ticks = p.ticks();
  result.tick_ns = p.tick_ns();
  result.window_s = 1e-9 * static_cast<double>(p.ticks() * p.tick_ns());
  result.repeats = std::max(1, opt.repeats);
  const auto size = static_cast<std::size_t>(p.ticks() + 1);

  // Reference.
  Trajectory<State> ref(size), traj(size);
  ReferenceInfo& info = result.reference;
  info.difference.assign(nq, 0.0);
  const auto ref_start = Clock::now();
  if constexpr (HasOracle<Problem>) {
    info.analytic = true;
    info.method = "analytic oracle";
    p.exact(ref);
  } else {
    info.method = "rk4";
    info.coarse_substeps = grid.reference_substeps;
    info.fine_substeps = 2 * grid.reference_substeps;
    const IntegrationOutcome fine = integrate_ours("rk4", p, info.fine_substeps, ref);
    const IntegrationOutcome coarse = integrate_ours("rk4", p, info.coarse_substeps, traj);
    p.errors(traj, ref, info.difference.data());
    if (!fine.ok || !coarse.ok) info.difference.assign(nq, INFINITY);
  }
  info.wall_s = std::chrono::duration<double>(Clock::now() - ref_start).count();

  // The grid, repeats interleaved.
  const std::vector<RunSpec> specs = grid_specs<Problem>(grid);
  result.runs.assign(specs.size(), RunResult{});
  std::vector<State> last(specs.size());
  for (int r = 0; r < result.repeats; ++r) {
    for (std::size_t i = 0; i < specs.size(); ++i) {
      RunResult& run = result.runs[i];
      const auto t0 = Clock::now();
      const double c0 = thread_cpu_seconds();
      const IntegrationOutcome o = integrate_spec(specs[i], p, traj);
      const double cpu = thread_cpu_seconds() - c0;
      const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
      run.cpu_s.push_back(cpu);
      run.wall_s.push_back(wall);
      if (r == 0) {
        run.spec = specs[i];
        run.outcome = o;
        run.scene_configuration = specs[i].family == Family::kOurs && specs[i].method == result.scene_method &&
                                  specs[i].substeps == result.scene_substeps;
        run.errors.assign(nq, INFINITY);
        if (o.ok) p.errors(traj, ref, run.errors.data());
        last[i] = traj.back();
        if (run.scene_configuration && scene_states != nullptr) {
          bool same = scene_states->size() + 1 == traj.size();
          for (std::size_t k = 0; same && k < scene_states->size(); ++k) same = (*scene_states)[k] == traj[k + 1];
          result.reproduces_scene_run = same;
          result.reproduction_note = same ? "the scene's integrator and step reproduce its closed-loop states bit for bit"
                                          : "the open-loop re-run departs from the closed-loop states";
        }
      } else if (!(traj.back() == last[i]) && !(o.ok == false && run.outcome.ok == false)) {
        run.deterministic = false;
      }
      if (opt.progress) {
        std::fprintf(stderr, "\r  [%d/%d] %-18s %-14s %8.3f s   ", r + 1, result.repeats, specs[i].method.c_str(),
                     specs[i].setting().c_str(), cpu);
      }
    }
  }
  if (opt.progress) std::fprintf(stderr, "\r%*s\r", 70, "");

  // Reference floor, round-off level and convergence (study_result.hpp, ReferenceInfo).
  info.floor.assign(nq, 0.0);
  info.scale.assign(nq, 0.0);
  info.at_roundoff.assign(nq, false);
  info.smallest_error.assign(nq, INFINITY);
  info.margin.assign(nq, INFINITY);
  p.scales(ref, info.scale.data());
  std::vector<bool> strict(nq, true);
  for (std::size_t q = 0; q < nq; ++q) {
    if (info.analytic) continue;
    info.floor[q] = 10.0 * info.difference[q];
    info.at_roundoff[q] = info.difference[q] <= 1e-12 * info.scale[q];
  }
  info.runs_below_floor = 0;
  for (RunResult& run : result.runs) {
    run.below_floor.assign(nq, false);
    run.comparison_error.assign(nq, NAN);
    bool below = false;
    for (std::size_t q = 0; q < nq; ++q) {
      if (!run.outcome.ok) continue;
      info.smallest_error[q] = std::min(info.smallest_error[q], run.errors[q]);
      run.below_floor[q] = !info.analytic && !(run.errors[q] >= info.floor[q]);
      if (!run.below_floor[q]) {
        run.comparison_error[q] = run.errors[q];
      } else {
        below = true;
        strict[q] = false;
        if (info.at_roundoff[q]) run.comparison_error[q] = info.floor[q];
      }
    }
    info.runs_below_floor += below ? 1 : 0;
  }
  info.converged = true;
  for (std::size_t q = 0; q < nq; ++q) {
    if (!info.analytic) info.margin[q] = info.smallest_error[q] / info.difference[q];
    if (!(strict[q] || info.at_roundoff[q]) || !std::isfinite(info.difference[q])) info.converged = false;
  }
  result.total_wall_s = std::chrono::duration<double>(Clock::now() - study_start).count();
}

}  // namespace gyrostab::tools::accuracy
