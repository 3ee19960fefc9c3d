// The accuracy study held to closed forms: its error on a problem with an analytic oracle equals a hand
// computation, its reference-convergence check refuses an unconverged reference, and the peers (Boost.Odeint,
// SUNDIALS CVODE) integrate a linear oscillator with tick-held forcing to their tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "tools/accuracy/accuracy_study.hpp"
#include "tools/accuracy/oscillator_problem.hpp"

namespace gyrostab::tools::accuracy {
namespace study_oracle_test {

using State = OscillatorProblem::State;

// The oscillator without its oracle: the study must then build and check a converged reference.
class OscillatorWithoutOracle {
 public:
  using Model = OscillatorModel;
  static constexpr int kStateSize = 2;
  using State = Model::State;
  static constexpr int kQuantities = 2;
  explicit OscillatorWithoutOracle(OscillatorProblem p) : p_(std::move(p)) {}
  Model& model() { return p_.model(); }
  void set_tick(std::int64_t k) { p_.set_tick(k); }
  State initial_state() const { return p_.initial_state(); }
  std::int64_t ticks() const { return p_.ticks(); }
  std::int64_t tick_ns() const { return p_.tick_ns(); }
  auto quantities() const { return p_.quantities(); }
  void errors(const Trajectory<State>& run, const Trajectory<State>& ref, double* out) const { p_.errors(run, ref, out); }
  void scales(const Trajectory<State>& ref, double* out) const { p_.scales(ref, out); }

 private:
  OscillatorProblem p_;
};

StudyGrid rk4_only(std::vector<int> substeps, int reference_substeps) {
  StudyGrid g;
  g.ours = {{"rk4", std::move(substeps)}};
  g.reference_substeps = reference_substeps;
  return g;
}

StudyOptions quiet() {
  StudyOptions o;
  o.repeats = 1;
  o.progress = false;
  return o;
}

// RK4 on x' = v, v' = −ω² x is z ← R(−iωh) z for z = x + i v/ω, R(w) = 1 + w + w²/2 + w³/6 + w⁴/24; the exact
// flow is z ← e^{−iωh} z. With x0 = 1, v0 = 0 the position error at tick k (n = k·substeps steps) is
// |Re R^n − cos(ω n h)| and the energy error ||R|^{2n} − 1|, both by hand below.
TEST(AccuracyStudy, ErrorAgainstTheAnalyticOracleMatchesRk4ByHand) {
  const double omega = 40.0;          // [rad/s]
  const std::int64_t tick_ns = 5'000'000;  // 5 ms: ωh = 0.2 per tick
  const int ticks = 400;              // 2 s, 12.7 periods
  OscillatorProblem problem(omega, tick_ns, std::vector<double>(ticks, 0.0), State(1.0, 0.0));
  StudyResult result;
  run_study(problem, rk4_only({1, 2, 4}, 0), quiet(), result);
  ASSERT_TRUE(result.reference.analytic);
  ASSERT_EQ(result.runs.size(), 3u);
  for (const RunResult& run : result.runs) {
    const double h = 5e-3 / run.spec.substeps;
    const std::complex<double> w(0.0, -omega * h);
    const std::complex<double> R = 1.0 + w + w * w / 2.0 + w * w * w / 6.0 + w * w * w * w / 24.0;
    double position = 0.0, energy = 0.0;
    for (int k = 0; k <= ticks; ++k) {
      const int n = k * run.spec.substeps;
      const std::complex<double> z = std::pow(R, n);
      position = std::max(position, std::abs(z.real() - std::cos(omega * n * h)));
      energy = std::max(energy, std::abs(std::norm(z) - 1.0));
    }
    // The study's numbers and the hand computation differ by round-off only: the real RK4 steps (≤ 1600),
    // the oracle's exact flow (400 ticks) and std::pow each accumulate ≲ n·ε ≈ 1600 · 1.1e-16 ≈ 2e-13 on a
    // unit amplitude. 1e-12 absolute sits above that and ≥ 300× below the smallest error here (3.5e-7:
    // ωh ≤ 0.2, RK4's phase error (ωh)^5/120 per step, 1e-3 over 400 steps at h = 5 ms, 16× less per halving).
    EXPECT_NEAR(run.errors[0], position, 1e-12) << run.spec.setting();
    EXPECT_NEAR(run.errors[1], energy, 1e-12) << run.spec.setting();
    EXPECT_GT(run.errors[0], 1e-9);  // not vacuous
  }
  // Fourth order: halving the step divides the position error by ~16 (2^4, within 10 % at these ωh).
  EXPECT_NEAR(result.runs[0].errors[0] / result.runs[1].errors[0], 16.0, 1.6);
  EXPECT_NEAR(result.runs[1].errors[0] / result.runs[2].errors[0], 16.0, 1.6);
}

TEST(AccuracyStudy, ReferenceConvergenceCheckRefusesAnUnconvergedReference) {
  const double omega = 40.0;
  std::vector<double> force(400);
  for (std::size_t k = 0; k < force.size(); ++k) force[k] = (k / 50) % 2 == 0 ? 300.0 : -200.0;  // steps every 0.25 s
  const OscillatorProblem exact(omega, 5'000'000, force, State(1.0, 0.0));
  StudyResult truth;
  OscillatorProblem with_oracle = exact;
  run_study(with_oracle, rk4_only({1, 2, 4}, 0), quiet(), truth);

  // Reference rk4 at tick/1 vs tick/2: the difference is as large as the errors it should resolve.
  OscillatorWithoutOracle bad_problem(exact);
  StudyResult bad;
  run_study(bad_problem, rk4_only({1, 2, 4}, 1), quiet(), bad);
  EXPECT_FALSE(bad.reference.converged);
  EXPECT_LT(bad.reference.margin[0], 10.0);
  EXPECT_TRUE(bad.runs[2].below_floor[0]);  // tick/4 is more accurate than that reference: not usable
  EXPECT_FALSE(bad.runs[2].usable(0));

  // Reference at tick/64 vs tick/128: converged, and the errors equal the oracle's to the reference's
  // uncertainty (its difference bounds the tick/64 run's error, ≈ 16× the tick/128 reference's own).
  OscillatorWithoutOracle good_problem(exact);
  StudyResult good;
  run_study(good_problem, rk4_only({1, 2, 4}, 64), quiet(), good);
  EXPECT_TRUE(good.reference.converged);
  EXPECT_GE(good.reference.margin[0], 10.0);
  for (std::size_t i = 0; i < good.runs.size(); ++i) {
    EXPECT_TRUE(good.runs[i].usable(0));
    EXPECT_NEAR(good.runs[i].errors[0], truth.runs[i].errors[0], good.reference.difference[0]) << i;
  }
}

// The peers on x'' = −ω² x + u_k with u switching every 50 ticks: each must land within its tolerance of
// the exact tick-by-tick flow, in the sense a local error control promises: every accepted step errs by at
// most ~tol·(1 + |x|) ≤ 2.2 tol (rtol = atol = tol, |x| ≲ 1.2), and a global error can at worst add those up,
// so it is bounded by 2.2 tol × (accepted steps). (CVODE restarts at order 1 at every tick, so it takes many
// small steps and its global error is tens to hundreds of tol: within that bound, and above a flat 100 tol.)
// Odeint's RK4 is the classical tableau, so its error equals ours to round-off.
TEST(AccuracyStudy, PeersIntegrateAnOscillatorWithTickHeldForcingToTheirTolerance) {
  const double omega = 40.0;
  std::vector<double> force(400);
  for (std::size_t k = 0; k < force.size(); ++k) force[k] = (k / 50) % 2 == 0 ? 300.0 : -200.0;
  OscillatorProblem problem(omega, 5'000'000, force, State(1.0, 0.0));
  StudyGrid g;
  g.ours = {{"rk4", {4}}};
  g.odeint_rk4_substeps = {4};
  g.odeint_dopri5_tolerances = {1e-6, 1e-9};
  g.cvode_bdf_tolerances = {1e-6, 1e-9};
  g.cvode_adams_tolerances = {1e-6, 1e-9};
  StudyResult r;
  run_study(problem, g, quiet(), r);
  ASSERT_EQ(r.runs.size(), 8u);
  for (const RunResult& run : r.runs) {
    ASSERT_TRUE(run.outcome.ok) << run.spec.method << " " << run.outcome.error;
    if (run.spec.adaptive()) {
      EXPECT_LT(run.errors[0], 2.2 * run.spec.tolerance * static_cast<double>(run.outcome.steps))
          << run.spec.method << " " << run.spec.setting() << " steps " << run.outcome.steps;
      EXPECT_GT(run.errors[0], 0.01 * run.spec.tolerance) << run.spec.method;  // the tolerance is what limits it
      EXPECT_GT(run.outcome.rhs_evaluations, 400) << run.spec.method;  // at least one evaluation per tick
    }
  }
  // odeint-rk4 = rk4 up to the order of the floating-point operations: ≲ 1600 steps · ε ≈ 2e-13.
  EXPECT_NEAR(r.runs[1].errors[0], r.runs[0].errors[0], 1e-12);
  for (const RunResult& run : r.runs) {
    std::printf("%-14s %-12s error %.3e  steps %lld  f %lld\n", run.spec.method.c_str(), run.spec.setting().c_str(),
                run.errors[0], static_cast<long long>(run.outcome.steps),
                static_cast<long long>(run.outcome.rhs_evaluations));
  }
  // Tightening the tolerance by 1000 gains accuracy for every adaptive peer (by ≥ 30×: not vacuous).
  for (std::size_t i = 2; i < 8; i += 2) {
    EXPECT_LT(r.runs[i + 1].errors[0], r.runs[i].errors[0] / 30.0) << r.runs[i].spec.method;
  }
}

}  // namespace study_oracle_test
}  // namespace gyrostab::tools::accuracy
