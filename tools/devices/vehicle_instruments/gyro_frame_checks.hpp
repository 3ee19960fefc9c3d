// Start-up checks of the instruments that are a gyro in a rotating frame ((10.22),
// sim/models/gyro_in_rotating_frame.hpp: the gyro vertical, the gyrocompass), as their schemas' rules use
// them: the nutation the precession theory does not see (sim/models/gyro_frame_stability.hpp) and the plant
// sub-step against the model's fastest mode (sim/dynamics/step_validation.hpp). Each returns "" or the
// problem. Start-up only (Eigen solvers, strings).
#pragma once

#include <cstdio>
#include <string>

#include "sim/dynamics/step_validation.hpp"
#include "sim/models/gyro_frame_stability.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

// "%.3g" of v (the checks' messages).
inline std::string format_3g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// A closed loop whose nutation grows: "<cause> makes the nutation grow at <rate> /s (a circulatory force,
// model header): <remedy>".
inline std::string growing_nutation(const models::GyroFrameParams& p, const models::GyroFrameStiffness& K,
                                    double d1, double d2, const char* cause, const std::string& remedy) {
  const double growth = models::gyro_frame_growth_rate(p, K, d1, d2);
  if (!(growth > 0.0)) return "";
  return std::string(cause) + " makes the nutation grow at " + format_3g(growth) +
         " /s (a circulatory force, model header): " + remedy;
}

// A plant sub-step too long for RK4 on the model's fastest mode at rest.
template <class Model>
std::string long_rk4_substep(const LoopConfig& loop, const Model& m) {
  const double h_sub = loop.tick_s() / loop.substeps;
  const dynamics::StepCheck step = dynamics::check_step(
      dynamics::Method::kRk4, dynamics::fastest_mode(m, 0.0, Model::make_state(0, 0)), h_sub);
  return step.ok ? "" : step.message;
}

}  // namespace gyrostab::tools
