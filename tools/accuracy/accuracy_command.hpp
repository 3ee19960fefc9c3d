// `gyrostab accuracy SCENE [--out DIR]`: error against run time for a scene's plant (docs/accuracy.md).
// Records the scene's closed-loop inputs, integrates the plant open loop with those inputs by our integrators
// and by the peers (Boost.Odeint, SUNDIALS CVODE) over a grid of steps and tolerances, and writes the
// work-precision table (stdout), accuracy.csv, report.json and work_precision.png. Which devices the study
// takes, with their problem and grid: the registry's accuracy entries (tools/devices/<device>/*_study.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>


namespace gyrostab::tools {

struct AccuracyRequest {
  std::string scene_path;
  std::string out_dir{"out-accuracy"};
  double duration_s{-1.0};   // window from t = 0 [s]; < 0: the device's default (docs/accuracy.md)
  int repeats{3};            // timings per run (the speed-up's spread is over them)
  bool quick{false};         // a small grid (tests): two steps per method, one tolerance per peer
  bool progress{true};
  bool plot{true};
  bool write_outputs{true};
  nlohmann::json* report_out{nullptr};  // receives report.json's content (tests)
};

// Exit code: 0 ok; 2 scene refused or not supported by the study; 3 the closed loop diverged or an output
// could not be written; 4 the reference did not converge (outputs written, the comparison flagged).
int run_accuracy(const AccuracyRequest& request);

}  // namespace gyrostab::tools
