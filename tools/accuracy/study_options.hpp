// The grid of a work-precision study (which methods at which steps or tolerances, and the reference) and how
// it runs (repeats, progress).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace gyrostab::tools::accuracy {

struct StudyGrid {
  std::vector<std::pair<std::string, std::vector<int>>> ours;  // our method → sub-steps per tick
  std::vector<int> odeint_rk4_substeps;
  std::vector<double> odeint_dopri5_tolerances;
  std::vector<double> cvode_bdf_tolerances;
  std::vector<double> cvode_adams_tolerances;
  int reference_substeps{64};  // rk4 at this and at twice this many steps per tick
};

struct StudyOptions {
  int repeats{3};
  bool progress{true};  // one line per run on stderr
};

}  // namespace gyrostab::tools::accuracy
