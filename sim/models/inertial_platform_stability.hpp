// The servo modes of a three-axis inertial platform taken as a whole: the linear system of its three axes
// with every cross term (Magnus §16.3, the matrix form (16.14) M x'' + D x' + F x = s), at rest in a
// non-rotating frame, without the three tilts e (they feed nothing back: the book's "α, β, γ enter only
// through their derivatives"). That leaves the book's 9th order for three rate-integrating gyros
// (sim/models/inertial_platform.hpp) and 11th for two position gyros
// (sim/models/inertial_platform_position_gyros.hpp), whose two rotors' relative azimuth is neutral
// (one zero root: the platform follows the mean of the two azimuth readings).
// The platform is stable when every root but the neutral ones has a negative real part; the single-axis bound
// (16.5) k < H d/B is this test for one decoupled axis, and the coupled roots can refuse gains it accepts.
// Host only (the eigenvalue solver allocates): for the scene checks and the oracle tests.
// Oracle: tests/oracle/inertial_platform_coupling_test.cpp. Docs: docs/models/inertial-platform.md
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>

#include "sim/dynamics/eigenvalues.hpp"
#include "sim/models/inertial_platform.hpp"
#include "sim/models/inertial_platform_position_gyros.hpp"

namespace gyrostab::models {

// The system matrix of the servo states (x without the tilts) of `Model` (ThreeAxisPlatform,
// TwoPositionGyroPlatform) with parameters p: exact, column by column (the model is linear in them; the
// constant torques and drifts are set to zero).
template <class Model, class Params>
Eigen::MatrixXd servo_matrix(const Params& p) {
  Params q = p;
  for (PlatformAxisParams& a : q.axis) a.disturbance = a.drift = 0.0;
  Model m(q);
  m.inputs = {};
  constexpr int n = Model::kStateSize - 3;
  Eigen::MatrixXd A(n, n);
  for (int j = 0; j < n; ++j) {
    typename Model::State x = Model::State::Zero(), dx;
    x[3 + j] = 1.0;
    m.derivative(0.0, x, dx);
    A.col(j) = dx.template tail<n>();
  }
  return A;
}

struct ServoStability {
  bool stable{false};
  std::complex<double> worst{};  // the non-neutral root with the largest real part [1/s]
  int neutral{0};                // roots at zero (|λ| below 1e-9 of the largest)
};

inline ServoStability servo_stability(const Eigen::VectorXcd& roots) {
  ServoStability s;
  double big = 0.0;
  for (const std::complex<double>& l : roots) big = std::max(big, std::abs(l));
  bool any = false;
  for (const std::complex<double>& l : roots) {
    if (std::abs(l) <= 1e-9 * big) {
      ++s.neutral;
      continue;
    }
    if (!any || l.real() > s.worst.real()) s.worst = l;
    any = true;
  }
  s.stable = any && s.worst.real() < 0.0;
  return s;
}

template <class Model, class Params>
ServoStability servo_stability(const Params& p) {
  return servo_stability(dynamics::eigenvalues(servo_matrix<Model>(p)));
}

}  // namespace gyrostab::models
