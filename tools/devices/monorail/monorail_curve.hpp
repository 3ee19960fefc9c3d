// The monorail's loop in a curve (Magnus §14.1, (14.3), (14.6)): curve running is (14.2) with c → c − HΩ3,
// q → q − HΩ3, so the firmware law's gain window and the roots of the characteristic quartic follow from the
// straight track's with the shifted stiffnesses. Used by the scene check (monorail_schema.cpp) and the
// figures (monorail_run.cpp); the window itself: firmware/control/monorail_motor_law.hpp. Test: none of its
// own yet (tests/oracle/monorail_test.cpp checks the same quartic's roots with its own companion matrix).
#pragma once

#include "firmware/control/monorail_motor_law.hpp"
#include "sim/dynamics/eigenvalues.hpp"
#include "sim/models/monorail.hpp"

namespace gyrostab::tools {

// The firmware law's view of the plant in a curve at Ω3 [rad/s].
inline firmware::MonorailMotorParams law_in_curve(firmware::MonorailMotorParams l, double Omega3) {
  l.c -= l.H * Omega3;
  l.q -= l.H * Omega3;
  return l;
}

// Largest real part of the roots of (14.3) with c → c − HΩ3, q → q − HΩ3 (14.6), the gain k [N m/rad] and d
// the total damper [N m s/rad]; < 0: the loop decays at that rate [1/s].
inline double max_real_root(const models::MonorailParams& p, double k, double d, double Omega3) {
  const double c = p.c - p.H * Omega3, q = p.q - p.H * Omega3;
  const double a[5] = {p.A * p.B, p.A * d, p.H * p.H - q * p.A - c * p.B, k * p.H - c * d, c * q};
  Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 4; ++i) companion(0, i) = -a[i + 1] / a[0];
  for (int i = 1; i < 4; ++i) companion(i, i - 1) = 1.0;
  return dynamics::eigenvalues<4>(companion).real().maxCoeff();
}

}  // namespace gyrostab::tools
