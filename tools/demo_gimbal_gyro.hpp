// `gyrostab demo`: a gimbal gyro pendulum run at the controller tick, its nutation and precession
// frequencies measured from the simulated response and printed against Magnus (10.14)-(10.17).
#pragma once

#include <string>

namespace gyrostab::tools {

struct DemoOptions {
  double rpm{6000.0};           // rotor speed
  double CR{1.0};               // rotor axial moment [kg m²]
  double A{0.5}, B{0.5};        // gimbal-axis moments [kg m²]
  double Gs{-50.0};             // pendulous (hanging) unbalance [N m]
  double tick_us{1000.0};       // controller tick
  int substeps{1};              // plant steps per tick
  std::string method{"gyro-exponential"};
  bool force{false};            // run even if the step validation refuses the step
};

int run_demo(const DemoOptions& options);

}  // namespace gyrostab::tools
