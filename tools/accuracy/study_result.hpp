// Everything one accuracy study measured: the grid's runs, the reference they were measured against and
// how well converged it is, and the set-up (window, repeats) needed to read the numbers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/accuracy/study_problem.hpp"
#include "tools/accuracy/study_run.hpp"

namespace gyrostab::tools::accuracy {

// The reference every error is measured against.
//   analytic:   the problem's exact solution (uncertainty: round-off only, taken as 0);
//   converged:  `method` at `fine_substeps` per tick; its uncertainty is shown by a second run at half the
//               step (`coarse_substeps`): `difference` is the error measure of the coarse run against the
//               fine one, per quantity, an upper bound of the fine run's own error (for RK4 ≈ 15× larger).
// The floor is 10 × difference: an error above it is measured to within 10 % by this reference; an error
// below it is not resolved. Per quantity the reference is converged when
//   (a) every error of the grid lies above the floor (the two finer runs agree to well below the smallest
//       error reported), or
//   (b) the difference is at double-precision round-off: ≤ 1e-12 × the quantity's scale (the largest
//       magnitude of the signal it measures) — a finer reference cannot do better; runs below the floor
//       then err by at most the floor and are compared as if at it (in the table: "~").
// Not converged: runs below the floor are left out of every comparison and the study exits with code 4.
struct ReferenceInfo {
  bool analytic{false};
  std::string method;
  int coarse_substeps{0}, fine_substeps{0};
  std::vector<double> difference;      // per quantity
  std::vector<double> floor;           // per quantity: 10 × difference
  std::vector<double> scale;           // per quantity: the largest magnitude of the measured signal
  std::vector<bool> at_roundoff;       // per quantity: (b) holds
  std::vector<double> smallest_error;  // per quantity, over the runs that integrated to the end
  std::vector<double> margin;          // smallest_error / difference (inf for analytic)
  int runs_below_floor{0};
  bool converged{true};
  double wall_s{0.0};                  // both reference runs [s]
};

struct StudyResult {
  std::string scene;                   // scene name
  std::string device;
  std::string scene_method;            // the scene's [loop] integrator
  int scene_substeps{1};
  double window_s{0.0};                // simulated time per run [s], from t = 0
  std::int64_t ticks{0};
  std::int64_t tick_ns{0};
  int repeats{1};
  std::vector<Quantity> quantities;    // quantity 0 is the primary one
  std::vector<RunResult> runs;
  ReferenceInfo reference;
  // The problem, integrated with the scene's own integrator and step, reproduces the scene's closed-loop
  // states bit for bit (the open-loop re-run holds the same inputs as the closed loop did).
  bool reproduces_scene_run{false};
  std::string reproduction_note;
  double closed_loop_wall_s{0.0};      // the scene's closed-loop run that recorded the inputs [s]
  double total_wall_s{0.0};            // the whole study, set-up and reference included [s]
};

}  // namespace gyrostab::tools::accuracy
