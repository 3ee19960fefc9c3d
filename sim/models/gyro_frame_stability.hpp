// Stability at rest of a closed loop on the master equation (10.22) (gyro_in_rotating_frame.hpp): the
// linearization with Ω' = 0 and the torques −K [α; β] − diag(d1, d2) [α'; β'] (frame-rate and pendulous
// terms folded into K), state [α, β, α', β'] (rad, rad/s):
//   A α'' + H β' + d1 α' + k11 α + k12 β = 0,   B β'' − H α' + d2 β' + k21 α + k22 β = 0.
// A non-symmetric K (k12 ≠ k21) is a circulatory force: the precession theory does not see that it feeds
// the nutation, which then grows (gyro_vertical.hpp, gyrocompass.hpp headers). Start-up only (Eigen solver).
// Test: tests/oracle/gyro_vertical_test.cpp and gyrocompass_test.cpp (the growth without bearing damping).
#pragma once

#include <algorithm>

#include "sim/dynamics/eigenvalues.hpp"
#include "sim/models/gyro_in_rotating_frame.hpp"

namespace gyrostab::models {

// Positional torques −K [α; β] of the closed loop linearized at rest [N m/rad].
struct GyroFrameStiffness {
  double k11, k12, k21, k22;
};

// Largest real part of the linearization's eigenvalues [1/s]; > 0: a mode grows. d1, d2 [N m s/rad].
inline double gyro_frame_growth_rate(const GyroFrameParams& p, const GyroFrameStiffness& K, double d1,
                                     double d2) {
  const double A = p.A, B = p.B, H = p.H;
  Eigen::Matrix4d J;
  J << 0, 0, 1, 0,                              //
      0, 0, 0, 1,                               //
      -K.k11 / A, -K.k12 / A, -d1 / A, -H / A,  //
      -K.k21 / B, -K.k22 / B, H / B, -d2 / B;
  const dynamics::EigenvaluesOf<4> ev = dynamics::eigenvalues<4>(J);
  double growth = -1e300;
  for (int i = 0; i < 4; ++i) growth = std::max(growth, ev[i].real());
  return growth;
}

}  // namespace gyrostab::models
