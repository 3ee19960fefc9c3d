#include "tools/build_paths.hpp"
#include "tools/accuracy/study_report.hpp"

#include "tools/run/output_dir.hpp"

#include <algorithm>
#include <boost/version.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include <Eigen/Core>

#include "tools/accuracy/cvode_peer.hpp"
#include "tools/accuracy/work_precision.hpp"

namespace gyrostab::tools::accuracy {
namespace {

constexpr const char* kHowTiming =
    "run time = the thread's CPU time (CLOCK_THREAD_CPUTIME_ID) of integrating the whole window tick by tick "
    "(inputs set each tick, state stored each tick boundary, the same loop for every method), per simulated "
    "second; median over the repeats, which are interleaved (every method once per repeat). CPU time because "
    "the machine is shared: wall time (also in the outputs) counts the waits for a core";
constexpr const char* kHowSpeedUp =
    "per method, the front of its runs (time rising, error falling; failed runs left out; a run below the "
    "reference floor counts as erring by the floor if the reference is at round-off, else is left out); T_m(e) = log-log linear interpolation of time against error between the two front points "
    "bracketing e, the cheapest time if the cheapest run already meets e, undefined below the most accurate run "
    "(no extrapolation); best of a family = least T_m(e); speed-up(e) = T_best peer(e) / T_best ours(e). The "
    "headline is at e = the error of the scene's own integrator and step (the floor if it lies below it); its "
    "spread is over the repeats (each repeat's own times). Where no peer run reaches e the ratio is null and "
    "ratio_at_least = T(the peers' most accurate run) / T_best ours(e) bounds it from below (a peer would need a "
    "setting tighter than any tried, which costs at least that)";
constexpr const char* kHowPeers =
    "inputs switch at every tick (zero-order hold): odeint-rk4 steps on the tick grid; odeint-dopri5 is reset() "
    "at every tick and its last step cut to the tick boundary (step size carried over); CVODE is restarted with "
    "CVodeReInit at every tick with the stop time at the next; rtol = atol = tol; CVODE BDF: Newton + dense "
    "direct solver with difference-quotient Jacobian; CVODE Adams: fixed-point iteration";

double quantile(std::vector<double> v, double f) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = f * static_cast<double>(v.size() - 1);
  const auto i = static_cast<std::size_t>(pos);
  const double frac = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - frac) + v[i + 1] * frac : v[i];
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

const RunResult* scene_run(const StudyResult& s) {
  for (const RunResult& r : s.runs) {
    if (r.scene_configuration) return &r;
  }
  return nullptr;
}

// The speed-up at `error` for quantity q: median-time figure plus one per repeat.
nlohmann::json speed_up_json(const StudyResult& s, std::size_t q, double error) {
  const SpeedUp m = speed_up_at(s, q, error);
  std::vector<double> per_repeat, bound_per_repeat;
  for (int r = 0; r < s.repeats; ++r) {
    const SpeedUp x = speed_up_at(s, q, error, r);
    per_repeat.push_back(x.ratio);
    bound_per_repeat.push_back(x.ratio_at_least);
  }
  nlohmann::json j{{"error", error},
                   {"ours_method", m.ours_method},
                   {"peer_method", m.peer_method},
                   {"ours_s_per_simulated_s", number_or_null(m.ours_time)},
                   {"peer_s_per_simulated_s", number_or_null(m.peer_time)},
                   {"ratio", number_or_null(m.ratio)},
                   {"ratio_min", number_or_null(quantile(per_repeat, 0.0))},
                   {"ratio_median", number_or_null(quantile(per_repeat, 0.5))},
                   {"ratio_max", number_or_null(quantile(per_repeat, 1.0))}};
  nlohmann::json reps = nlohmann::json::array();
  for (double x : per_repeat) reps.push_back(number_or_null(x));
  j["ratio_per_repeat"] = reps;
  j["peer_best_error"] = number_or_null(m.peer_best_error);
  j["peer_best_method"] = m.peer_best_method;
  j["peer_best_s_per_simulated_s"] = number_or_null(m.peer_best_time);
  if (!std::isfinite(m.peer_time)) {
    // Undefined as a ratio, bounded below: a peer would have to go past its most accurate run.
    j["ratio_at_least"] = number_or_null(m.ratio_at_least);
    j["ratio_at_least_min"] = number_or_null(quantile(bound_per_repeat, 0.0));
    j["ratio_at_least_median"] = number_or_null(quantile(bound_per_repeat, 0.5));
    j["ratio_at_least_max"] = number_or_null(quantile(bound_per_repeat, 1.0));
    char b[240];
    std::snprintf(b, sizeof b,
                  "no peer run reaches this error: the speed-up is at least %.3g× (the peers' most accurate run, "
                  "%s, errs %.3g at %.3g s per simulated s)",
                  m.ratio_at_least, m.peer_best_method.c_str(), m.peer_best_error, m.peer_best_time);
    j["note"] = std::isfinite(m.ratio_at_least) ? std::string(b) : std::string("no peer run reaches this error");
  }
  if (!std::isfinite(m.ours_time)) j["note"] = "none of our runs reaches this error";
  return j;
}

std::string sci(double x) {
  char b[32];
  if (!std::isfinite(x)) return x > 0 ? "inf" : "-";
  std::snprintf(b, sizeof b, "%.2e", x);
  return b;
}

}  // namespace

std::string format_table(const StudyResult& s) {
  const std::size_t nq = s.quantities.size();
  const std::vector<int> rank = error_time_ranks(s, 0);
  std::string out;
  char b[512];
  std::snprintf(b, sizeof b, "accuracy study: %s (%s), window %.4g s = %lld ticks of %.4g ms, %d repeat%s\n",
                s.scene.c_str(), s.device.c_str(), s.window_s, static_cast<long long>(s.ticks),
                1e-6 * static_cast<double>(s.tick_ns), s.repeats, s.repeats == 1 ? "" : "s");
  out += b;
  std::snprintf(b, sizeof b, "%-18s %-13s", "method", "step/tol");
  out += b;
  for (const Quantity& q : s.quantities) {
    std::snprintf(b, sizeof b, " %13.13s", q.name);
    out += b;
  }
  out += "   ms/sim-s  f/tick  rank(err x time)\n";
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    const RunResult& r = s.runs[i];
    std::snprintf(b, sizeof b, "%-18s %-13s", r.spec.method.c_str(), r.spec.setting().c_str());
    out += b;
    for (std::size_t q = 0; q < nq; ++q) {
      std::string e = r.outcome.ok ? sci(r.errors[q]) : "failed";
      if (r.outcome.ok && r.below_floor[q]) e += "~";
      std::snprintf(b, sizeof b, " %13s", e.c_str());
      out += b;
    }
    const double ms = 1e3 * r.time_per_simulated_s(s.window_s);
    const double fpt = static_cast<double>(r.outcome.rhs_evaluations) / static_cast<double>(std::max<std::int64_t>(1, s.ticks));
    std::snprintf(b, sizeof b, " %10.3f %7.1f  %s%s\n", ms, fpt, rank[i] > 0 ? std::to_string(rank[i]).c_str() : "-",
                  r.scene_configuration ? "   <- the scene's own integrator and step" : "");
    out += b;
  }
  out += "(ms/sim-s: thread CPU time per simulated second, median of the repeats; f/tick: right-hand sides per tick;\n"
         " ~ below the reference floor: compared as erring by the floor if the reference is at round-off, else left out)\n";
  const ReferenceInfo& ref = s.reference;
  if (ref.analytic) {
    out += "reference: analytic oracle\n";
  } else {
    std::snprintf(b, sizeof b, "reference: %s at tick/%d; convergence: tick/%d vs tick/%d differ by", ref.method.c_str(),
                  ref.fine_substeps, ref.coarse_substeps, ref.fine_substeps);
    out += b;
    for (std::size_t q = 0; q < nq; ++q) out += " " + sci(ref.difference[q]) + " (" + s.quantities[q].name + ")";
    out += "\n  smallest error reported / that difference:";
    for (std::size_t q = 0; q < nq; ++q) {
      out += " " + sci(ref.margin[q]) + (ref.at_roundoff[q] ? " (difference at round-off: <= 1e-12 x " + sci(ref.scale[q]) + ")" : "");
    }
    out += ref.converged ? "\n  -> converged" : "\n  -> NOT CONVERGED: errors below 10x the difference are left out";
    out += " (" + std::to_string(ref.runs_below_floor) + " run(s) below the floor)\n";
  }
  out += std::string("scene reproduction: ") + (s.reproduces_scene_run ? "yes" : "NO") + " (" + s.reproduction_note + ")\n";
  if (const RunResult* sr = scene_run(s); sr != nullptr && sr->usable(0)) {
    const double e = sr->comparison_error[0];
    const SpeedUp m = speed_up_at(s, 0, e);
    std::vector<double> per;
    for (int r = 0; r < s.repeats; ++r) per.push_back(speed_up_at(s, 0, e, r).ratio);
    std::snprintf(b, sizeof b,
                  "speed-up at equal %s error %.2e (the scene's own): best ours %s %.3g ms/sim-s, best peer %s %.3g "
                  "ms/sim-s: %.3gx (repeats: min %.3g, median %.3g, max %.3g)\n",
                  s.quantities[0].name, e, m.ours_method.c_str(), 1e3 * m.ours_time,
                  m.peer_method.empty() ? "(none reaches it)" : m.peer_method.c_str(), 1e3 * m.peer_time, m.ratio,
                  quantile(per, 0.0), quantile(per, 0.5), quantile(per, 1.0));
    out += b;
  }
  for (double e : comparison_levels(s, 0)) {
    const SpeedUp m = speed_up_at(s, 0, e);
    if (!std::isfinite(m.ratio) || m.ours_method.empty() || m.peer_method.empty()) {
      // One side never reaches this error in the grid (a --quick grid is small): no ratio to state.
      std::snprintf(b, sizeof b, "  at %s error %.0e: %s reaches it in this grid\n", s.quantities[0].name, e,
                    m.ours_method.empty() && m.peer_method.empty() ? "neither side"
                    : m.ours_method.empty()                       ? "only a peer"
                                                                  : "none of the peers");
      out += b;
      continue;
    }
    std::snprintf(b, sizeof b, "  at %s error %.0e: ours %s, peer %s: %.3gx\n", s.quantities[0].name, e,
                  m.ours_method.c_str(), m.peer_method.c_str(), m.ratio);
    out += b;
  }
  std::snprintf(b, sizeof b, "study wall time %.1f s (closed-loop recording %.2f s, reference %.2f s)\n", s.total_wall_s,
                s.closed_loop_wall_s, s.reference.wall_s);
  out += b;
  return out;
}

std::string format_csv(const StudyResult& s) {
  const std::vector<int> rank = error_time_ranks(s, 0);
  std::string out = "method,family,setting,substeps,tolerance";
  for (const Quantity& q : s.quantities) out += std::string(",") + q.name + "," + q.name + "_below_floor";
  out += ",cpu_s_median,cpu_s_per_simulated_s,wall_s_median,rhs_evaluations,rhs_per_tick,steps,rank_error_x_time,"
         "scene_configuration,ok";
  for (int r = 0; r < s.repeats; ++r) out += ",cpu_s_repeat" + std::to_string(r + 1);
  out += "\n";
  char b[64];
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    const RunResult& r = s.runs[i];
    out += r.spec.method + "," + (r.spec.family == Family::kOurs ? "ours" : "peer") + "," + r.spec.setting() + ",";
    out += std::to_string(r.spec.substeps) + ",";
    std::snprintf(b, sizeof b, "%.3g", r.spec.tolerance);
    out += b;
    for (std::size_t q = 0; q < s.quantities.size(); ++q) {
      std::snprintf(b, sizeof b, ",%.6e,%d", r.errors[q], r.outcome.ok && r.below_floor[q] ? 1 : 0);
      out += b;
    }
    std::snprintf(b, sizeof b, ",%.6e,%.6e,%.6e", r.median_cpu_s(), r.time_per_simulated_s(s.window_s), r.median_wall_s());
    out += b;
    out += "," + std::to_string(r.outcome.rhs_evaluations);
    std::snprintf(b, sizeof b, ",%.3f", static_cast<double>(r.outcome.rhs_evaluations) / static_cast<double>(std::max<std::int64_t>(1, s.ticks)));
    out += b;
    out += "," + std::to_string(r.outcome.steps) + "," + std::to_string(rank[i]) + "," +
           (r.scene_configuration ? "1" : "0") + "," + (r.outcome.ok ? "1" : "0");
    for (double w : r.cpu_s) {
      std::snprintf(b, sizeof b, ",%.6e", w);
      out += b;
    }
    out += "\n";
  }
  return out;
}

nlohmann::json study_json(const StudyResult& s) {
  const std::size_t nq = s.quantities.size();
  nlohmann::json j;
  j["scene"] = {{"name", s.scene},
                {"device", s.device},
                {"window_s", s.window_s},
                {"ticks", s.ticks},
                {"tick_s", 1e-9 * static_cast<double>(s.tick_ns)},
                {"scene_integrator", s.scene_method},
                {"scene_substeps", s.scene_substeps}};
  j["machine"] = {{"compiler", __VERSION__},
                  {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                                std::to_string(EIGEN_MINOR_VERSION)},
                  {"boost", BOOST_LIB_VERSION},
                  {"sundials", sundials_version()},
                  {"hardware_threads", std::thread::hardware_concurrency()}};
  nlohmann::json quantities = nlohmann::json::array();
  for (const Quantity& q : s.quantities) {
    quantities.push_back({{"name", q.name}, {"unit", q.unit}, {"definition", q.definition}});
  }
  j["quantities"] = quantities;
  j["how"] = {{"timing", kHowTiming}, {"speed_up", kHowSpeedUp}, {"peers", kHowPeers}};
  const ReferenceInfo& ref = s.reference;
  nlohmann::json rj{{"kind", ref.analytic ? "analytic oracle" : "converged reference"},
                    {"method", ref.method},
                    {"converged", ref.converged},
                    {"wall_s", ref.wall_s}};
  if (!ref.analytic) {
    rj["fine_substeps"] = ref.fine_substeps;
    rj["coarse_substeps"] = ref.coarse_substeps;
    rj["runs_below_floor"] = ref.runs_below_floor;
    for (std::size_t q = 0; q < nq; ++q) {
      rj["difference"][s.quantities[q].name] = number_or_null(ref.difference[q]);
      rj["floor"][s.quantities[q].name] = number_or_null(ref.floor[q]);
      rj["scale"][s.quantities[q].name] = ref.scale[q];
      rj["difference_at_roundoff"][s.quantities[q].name] = static_cast<bool>(ref.at_roundoff[q]);
      rj["smallest_error_reported"][s.quantities[q].name] = number_or_null(ref.smallest_error[q]);
      rj["margin"][s.quantities[q].name] = number_or_null(ref.margin[q]);
    }
    rj["rule"] = "floor = 10x the difference of the two reference runs; per quantity converged if every error of the "
                 "grid lies above the floor, or if the difference is at round-off (<= 1e-12 x the quantity's scale), "
                 "when runs below the floor are compared as erring by the floor; otherwise they are left out";
  }
  j["reference"] = rj;
  j["reproduces_scene_run"] = s.reproduces_scene_run;
  j["reproduction_note"] = s.reproduction_note;
  const std::vector<int> rank = error_time_ranks(s, 0);
  nlohmann::json runs = nlohmann::json::array();
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    const RunResult& r = s.runs[i];
    nlohmann::json rr{{"method", r.spec.method},
                      {"family", r.spec.family == Family::kOurs ? "ours" : "peer"},
                      {"setting", r.spec.setting()},
                      {"ok", r.outcome.ok},
                      {"cpu_s", r.cpu_s},
                      {"cpu_s_median", r.median_cpu_s()},
                      {"s_per_simulated_s", r.time_per_simulated_s(s.window_s)},
                      {"wall_s", r.wall_s},
                      {"rhs_evaluations", r.outcome.rhs_evaluations},
                      {"steps", r.outcome.steps},
                      {"rank_error_x_time", rank[i]},
                      {"scene_configuration", r.scene_configuration},
                      {"deterministic", r.deterministic}};
    if (r.spec.adaptive()) {
      rr["tolerance"] = r.spec.tolerance;
    } else {
      rr["substeps"] = r.spec.substeps;
    }
    if (!r.outcome.ok) rr["failure"] = r.outcome.error;
    for (std::size_t q = 0; q < nq; ++q) {
      rr["errors"][s.quantities[q].name] = number_or_null(r.errors[q]);
      rr["below_reference_floor"][s.quantities[q].name] = r.outcome.ok && r.below_floor[q];
      rr["comparison_error"][s.quantities[q].name] = number_or_null(r.outcome.ok ? r.comparison_error[q] : NAN);
    }
    runs.push_back(rr);
  }
  j["runs"] = runs;
  nlohmann::json su{{"quantity", s.quantities[0].name}, {"how", kHowSpeedUp}};
  if (const RunResult* sr = scene_run(s); sr != nullptr && sr->usable(0)) {
    su["at_scene_error"] = speed_up_json(s, 0, sr->comparison_error[0]);
    nlohmann::json per_q;
    for (std::size_t q = 0; q < nq; ++q) {
      if (sr->usable(q)) {
        const SpeedUp m = speed_up_at(s, q, sr->comparison_error[q]);
        per_q[s.quantities[q].name] = {{"error", sr->comparison_error[q]}, {"ratio", number_or_null(m.ratio)},
                                       {"ours_method", m.ours_method}, {"peer_method", m.peer_method}};
      }
    }
    su["per_quantity_at_scene_error"] = per_q;
  } else {
    su["at_scene_error"] = nullptr;
    su["note"] = "the scene's own configuration has no usable error (failed, or below an unconverged reference's floor)";
  }
  nlohmann::json levels = nlohmann::json::array();
  for (double e : comparison_levels(s, 0)) levels.push_back(speed_up_json(s, 0, e));
  su["by_error_level"] = levels;
  j["speed_up"] = su;
  j["timing"] = {{"study_wall_s", s.total_wall_s},
                 {"closed_loop_recording_wall_s", s.closed_loop_wall_s},
                 {"reference_wall_s", s.reference.wall_s},
                 {"how", kHowTiming}};
  return j;
}

bool write_study_outputs(const StudyResult& s, const std::string& out_dir, bool plot, std::vector<std::string>& written,
                         std::string& error) {
  OutputSet out(out_dir, {"report.json", "accuracy.csv", "work_precision.png"});
  if (!out.open(error)) return false;
  if (!out.write("accuracy.csv", format_csv(s), error)) return false;
  if (!out.write("report.json", study_json(s).dump(2) + "\n", error)) return false;
  if (plot) {
    const char* here = std::getenv("GYROSTAB_WORK_PRECISION_SCRIPT");
    const std::string script = here ? here : std::string(build_source_dir()) + "/tools/plot/plot_work_precision.py";
    std::string why;
    if (run_program({"/usr/bin/python3", script, out.staging_dir()}, why) != 0) {
      std::fprintf(stderr, "gyrostab: work_precision.png not written (needs /usr/bin/python3 with python3-matplotlib%s); "
                           "report.json and accuracy.csv are complete\n",
                   why.empty() ? "" : ("; " + why).c_str());
    }
  }
  return out.commit(written, error);
}

}  // namespace gyrostab::tools::accuracy
