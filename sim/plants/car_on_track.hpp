// The monorail car of Magnus §14.1 (sim/models/monorail.hpp, (14.1)-(14.7), its analog law k = 0) on a track
// (sim/motion/monorail_track.hpp): the path's Ω3(t), the gust and the centrifugal moments of the curve
// evaluated at every integrator stage, the firmware's motor torque held over the tick, the brake on axis 2 as
// a viscous torque −brake β', and the ground (project()). State as the model's: [φ (rad), β (rad),
// φ' (rad/s), β' (rad/s)].
//
// Centrifugal terms, which the model neglects (the tilt of the apparent vertical by the lateral acceleration
// a = v Ω3): in the path frame car and case feel the uniform field m (0, −a, −g), i.e. the potential of the
// model plus (a/g)(−(c − q) sinφ − q sinφ cosβ), which adds
//   M1 += (a/g)(c cosφ − q cosφ (1 − cosβ)),     M2 += −(a/g) q sinφ sinβ
// (the large-angle counterpart of the gravity terms; to first order the moment c a/g on the car).
// Docs: docs/models/monorail.md. Test: no test of its own yet; the shipped scene sim/scenes/monorail.toml
// runs it in tests/determinism and tests/alloc.
#pragma once

#include <cmath>
#include <numbers>

#include "sim/models/monorail.hpp"
#include "sim/motion/monorail_track.hpp"
#include "sim/motion/wave_transfer.hpp"

namespace gyrostab::plants {

struct CarOnTrack {
  static constexpr int kStateSize = 4;
  using Car = models::Monorail;
  using State = Car::State;
  mutable Car car;
  const motion::MonorailTrack* track;
  double brake_Nms{0.0};   // [N m s/rad]
  double command_Nm{0.0};  // motor torque on axis 2 [N m]

  // The lateral acceleration of the path in units of g, a/g = v Ω3(t)/g [-].
  double lateral_g(double t) const { return track->speed_m_s * track->curve(t) / motion::kStandardGravity; }

  void derivative(double t, const State& x, State& dx) const {
    const models::MonorailParams& p = car.params();
    const double a_g = lateral_g(t);
    double M1 = track->gust(t), M2 = command_Nm - brake_Nms * x[Car::kCaseRate];
    if (a_g != 0.0) {
      const double cp = std::cos(x[Car::kTilt]), sp = std::sin(x[Car::kTilt]);
      const double cb = std::cos(x[Car::kCase]), sb = std::sin(x[Car::kCase]);
      M1 += a_g * (p.c * cp - p.q * cp * (1.0 - cb));
      M2 -= a_g * p.q * sp * sb;
    }
    car.inputs.Omega3 = track->curve(t);
    car.inputs.M1 = M1;
    car.inputs.M2 = M2;
    car.derivative(t, x, dx);
  }
  // A car that has overturned (|φ| reaches π/2, where the model stops applying) lies on its side: inelastic
  // contact, φ held at ±π/2 and no tilt rate away from upright; the case moves on.
  void project(State& x) const {
    constexpr double kLying = 0.5 * std::numbers::pi;
    if (std::fabs(x[Car::kTilt]) >= kLying) {
      x[Car::kTilt] = std::copysign(kLying, x[Car::kTilt]);
      if (x[Car::kTiltRate] * x[Car::kTilt] > 0.0) x[Car::kTiltRate] = 0.0;
    }
  }
};

}  // namespace gyrostab::plants
