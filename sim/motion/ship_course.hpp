// The ship's course relative to a long-crested sea: speed U, the angle μ between the ship's heading and the
// waves' direction of travel, and a steady turn at the yaw rate Ω3. What the roll moment of the waves
// (sea_roll_moment.hpp) needs from it:
//   μ(t) = μ0 − Ω3 t                       (μ counterclockwise seen from above; Ω3 > 0 turns the bow to port)
//   x_w(t) = ∫0^t U cos μ dt               (the ship's travel along the waves' direction [m])
//          = U cos μ0 t                    (Ω3 = 0)
//          = (U/Ω3)(sin μ0 − sin μ(t))     (Ω3 ≠ 0: the ship's track is a circle of radius U/|Ω3|)
//   a wave component η = a cos(ω t − k x + φ), k = ω²/g (deep water), seen from the ship: phase
//   ω t − k x_w(t) + φ, so on a straight course the encounter frequency is ω_e = ω − k U cos μ0
//   (head seas μ = 180°: ω_e > ω; following seas μ = 0: ω_e < ω, zero or negative for slow long waves);
//   its slope across the ship (axis 2, to port) is k a sin μ × the beam-sea slope: the effective-slope roll
//   moment of wave_transfer.hpp scales with sin μ (μ = 90°: waves from starboard, Magnus's beam sea (14.9)).
// Units: U [m/s], μ [rad], Ω3 [rad/s], g [m/s²]. Stateless; the defaults (U = 0, μ = 90°, Ω3 = 0) leave a
// beam sea unchanged bit for bit (sin(π/2) = 1 and ω − 0 = ω in double).
// Docs: docs/models/ship-roll-damper.md#course. Tests: tests/oracle/ship_course_response_test.cpp.
#pragma once

#include <cmath>
#include <numbers>

#include "sim/motion/wave_transfer.hpp"

namespace gyrostab::motion {

struct ShipCourse {
  double speed{0.0};                            // U [m/s]
  double heading{0.5 * std::numbers::pi};       // μ0, waves' direction of travel from the bow [rad]
  double turn_rate{0.0};                        // Ω3 [rad/s], about the upward vertical

  // Ship velocity along the waves' direction of travel on a straight course [m/s].
  double velocity_along_waves() const { return speed * std::cos(heading); }
  // ω_e of a wave of frequency ω on a straight course [rad/s].
  double encounter_frequency(double omega, double g = kStandardGravity) const {
    return omega - omega * omega / g * velocity_along_waves();
  }
  // μ(t) [rad].
  double heading_at(double t) const { return heading - turn_rate * t; }
  // x_w(t) [m] for Ω3 ≠ 0 (the straight course uses encounter_frequency()). Written as
  // (2U/Ω3) cos(μ0 − ε/2) sin(ε/2), ε = Ω3 t: the difference of sines would cancel catastrophically for a
  // slow turn (a relative error ulp(μ0)/ε in x_w).
  double track_along_waves(double t) const {
    const double half = 0.5 * turn_rate * t;
    return 2.0 * speed / turn_rate * std::cos(heading - half) * std::sin(half);
  }
  bool turning() const { return turn_rate != 0.0; }
};

}  // namespace gyrostab::motion
