// What the track does to a monorail car (Magnus §14.1, curve running (14.6)): the path's turning rate Ω3(t) —
// straight, a linear transition (a clothoid at constant speed) into a curve at Ω3, the curve, the same
// transition back — the car's speed v (the lateral acceleration in the curve is v Ω3), and a side-wind gust,
// a roll moment M1(t) on the car that rises linearly, holds and falls. Times in s, rates in rad/s, moments in
// N m; a start at +∞ means never. Pure functions of t, evaluated at every integrator stage by
// sim/plants/car_on_track.hpp. Docs: docs/models/monorail.md. Test: no test of its own yet; the shipped scene
// sim/scenes/monorail.toml runs it in tests/determinism and tests/alloc.
#pragma once

#include <algorithm>
#include <limits>

namespace gyrostab::motion {

// The time of an event that does not happen [s].
inline constexpr double kNeverS = std::numeric_limits<double>::infinity();

// Fraction in [0, 1] of a linear ramp that starts at t0 and lasts `ramp` seconds (a step when ramp = 0).
inline double ramp_fraction(double t, double t0, double ramp) {
  if (t < t0) return 0.0;
  return ramp > 0.0 ? std::min(1.0, (t - t0) / ramp) : 1.0;
}

// Ω3(t): straight until start_s, Ω3 growing linearly over transition_s, the curve at Omega3, and from end_s
// the same transition back to straight.
struct CurveProfile {
  double Omega3{0.0};        // in the curve, + in the rotor's spin sense [rad/s]
  double start_s{kNeverS};   // entry: start of the entry transition [s]
  double end_s{kNeverS};     // exit: start of the exit transition [s]
  double transition_s{2.0};  // [s]

  double operator()(double t) const {
    return Omega3 *
           std::min(ramp_fraction(t, start_s, transition_s), 1.0 - ramp_fraction(t, end_s, transition_s));
  }
};

// M1(t): rises linearly over rise_s from start_s, holds, and falls over rise_s from start_s + duration_s.
struct Gust {
  double M1{0.0};           // + tilts the car to + φ [N m]
  double start_s{kNeverS};  // onset [s]
  double duration_s{10.0};  // from onset to the start of the decay [s]
  double rise_s{0.5};       // rise and decay time [s]

  double operator()(double t) const {
    return M1 *
           std::min(ramp_fraction(t, start_s, rise_s), 1.0 - ramp_fraction(t, start_s + duration_s, rise_s));
  }
};

struct MonorailTrack {
  CurveProfile curve{};
  Gust gust{};
  double speed_m_s{0.0};  // v along the track [m/s]
};

}  // namespace gyrostab::motion
