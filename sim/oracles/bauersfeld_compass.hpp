// Closed forms of the tuned two-rotor spatial compass (Magnus §13.4; docs/models/bauersfeld-compass.md) for
// the run's report and the oracle test (tests/oracle/bauersfeld_compass_test.cpp).
//
// Tuned and started per (13.64), a1 = −up exactly, so a1' = −up' = −ω_IG × G3 with ω_IG the absolute rate
// of the geographic trihedron, (16.51): ω_IG_G = (−v_N/R, v_E/R + ω^E cosφ, (v_E/R) tanφ + ω^E sinφ). Then
//   a1' = −ω2 G1 + ω1 G2,   a2 = a1'/|a1'|,   a3 = a1 × a2 = (ω1 G1 + ω2 G2)/sqrt(ω1² + ω2²):
// a3 lies along the horizontal part of the vertical's absolute rate, and its azimuth (the compass error)
//   ψ_F = atan2(ω1, ω2) = atan2(−v_N, v_E + ω^E R cosφ)
// — the speed deviation (13.18), here exact (any speed and course, during accelerations too); and
//   sin δ = H sqrt(ω1² + ω2²) / (2 f),  at rest H ω^E cosφ / (2 f).
// Perturbed (13.61)-(13.63): each tilt component swings with T = 2π sqrt(|R^M|/g). The book's derivation
// works in inertial axes; read in the rotating geographic axes at rest on the Equator the components
// separate: the north tilt (along G2, the Earth's axis there, fixed in I) swings at exactly
// ω = sqrt(g/|R^M|), the east tilt at sqrt(ω² − (ω^E)²) (along G1, which turns with the Earth).
// Units: rad, rad/s, s, m/s, m.
#pragma once

#include <cmath>
#include <numbers>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::oracles {

// (13.63): T = 2π sqrt(|R^M|/g) [s].
inline double bauersfeld_period(double radius_M, double gravity) {
  return 2.0 * std::numbers::pi * std::sqrt(radius_M / gravity);
}

// The east tilt's period at rest on the Equator of an Earth turning at ω^E: 2π/sqrt(g/|R^M| − ω^E²) [s].
inline double bauersfeld_equator_east_period(double radius_M, double gravity, double earth_rate) {
  return 2.0 * std::numbers::pi / std::sqrt(gravity / radius_M - earth_rate * earth_rate);
}

// The tuned compass's azimuth error ψ_F = atan2(ω1, ω2) from ω_IG in G axes (ENU) [rad]; 0 where the
// vertical does not turn (the azimuth is undetermined there).
inline double bauersfeld_azimuth_book(const dynamics::Vec3& w_IG_G) {
  return std::atan2(w_IG_G.x(), w_IG_G.y());
}

// The same from the vehicle's ground velocity: atan2(−v_N, v_E + ω^E R cosφ) [rad].
inline double bauersfeld_speed_deviation(double v_north, double v_east, double latitude, double radius,
                                         double earth_rate) {
  return std::atan2(-v_north, v_east + earth_rate * radius * std::cos(latitude));
}

// sin δ of the tuned compass: H |ω_IG horizontal| / (2 f) [-].
inline double bauersfeld_sin_delta_book(const dynamics::Vec3& w_IG_G, double H, double f) {
  return H * std::hypot(w_IG_G.x(), w_IG_G.y()) / (2.0 * f);
}

}  // namespace gyrostab::oracles
