// One point of the work-precision grid: which method with which step or tolerance, what it cost and how
// far from the reference it ended, per error quantity.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace gyrostab::tools::accuracy {

enum class Family { kOurs, kPeer };

struct RunSpec {
  std::string method;    // "gyro-exponential", "rk4", "odeint-rk4", "odeint-dopri5", "cvode-bdf", ...
  Family family{Family::kOurs};
  int substeps{0};       // fixed-step methods: steps per controller tick (h = tick / substeps)
  double tolerance{0.0}; // adaptive methods: rtol = atol

  bool adaptive() const { return tolerance > 0.0; }
  std::string setting() const;  // "h = tick/4" or "tol 1e-08"
};

// What an integration over the whole window returns besides the trajectory.
struct IntegrationOutcome {
  bool ok{false};
  std::string error;                 // why not ok
  std::int64_t rhs_evaluations{0};   // right-hand-side evaluations (incl. difference-quotient Jacobians)
  std::int64_t steps{0};             // accepted steps (adaptive), steps (fixed)
};

struct RunResult {
  RunSpec spec;
  IntegrationOutcome outcome;
  std::vector<double> cpu_s;         // one per repeat: the thread's CPU time [s] (the run time compared)
  std::vector<double> wall_s;        // one per repeat: wall time [s] (reported; on a shared machine it
                                     // also counts the time the thread waited for a core)
  std::vector<double> errors;        // one per quantity, as measured; +inf if the run failed
  std::vector<bool> below_floor;     // per quantity: the error lies below the reference floor
  // Per quantity, the error the comparisons use: the measured one when resolved; the floor itself when
  // below it and the reference is converged to round-off (the run is known to err by at most the floor);
  // NaN when below it and the reference is not converged (unknown: left out).
  std::vector<double> comparison_error;
  bool scene_configuration{false};   // the scene's own [loop] integrator and sub-steps
  bool deterministic{true};          // every repeat ended in the same bits

  double median_cpu_s() const { return median(cpu_s); }
  double median_wall_s() const { return median(wall_s); }
  double time_per_simulated_s(double window_s) const { return median_cpu_s() / window_s; }
  // Counts in the work-precision comparison of quantity q.
  bool usable(std::size_t q) const {
    return outcome.ok && q < comparison_error.size() && std::isfinite(comparison_error[q]) && comparison_error[q] > 0.0;
  }
  static double median(std::vector<double> v);
};

}  // namespace gyrostab::tools::accuracy
