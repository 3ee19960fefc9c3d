// Closed forms of platform alignment (Magnus §16.5, (16.52); docs/models/platform-alignment.md): the
// oracle of tests/oracle/platform_alignment_test.cpp, the reference figures of the platform-alignment scenes
// and the scene check's latitude limit. All from the linearised loop of
// firmware/control/platform_alignment_loops.hpp on the kinematics of sim/models/platform_alignment.hpp.
//   levelling (one channel, θ(0) = θ0, I(0) = 0, ζ < 1, σ = ζω_L, ω_d = ω_L sqrt(1 − ζ²)):
//     θ(t) = θ0 e^{−σt} (cos ω_d t − (σ/ω_d) sin ω_d t)
//   azimuth loop: s³ + K1 s² + (K2 + Ω_N²) s + k_a K2 Ω_N = 0, its slow real root s_A (Newton from
//     −k_a K2 Ω_N/(K2 + Ω_N²)); ψ − ψ_ss ∝ e^{s_A t} once the levelling roots have decayed
//   steady misalignment (everything constant, azimuth phase):
//     θ_E = −b_N/g,  θ_N = b_E/g,  ψ = −ε_E/Ω_N − θ_N tanφ − (ε_U + Ω_N θ_E)/(k_a Ω_N)
//   alignment time (|ψ| ≤ tol): t_switch + ln(tan(|ψ0 − ψ_ss|/2)/tan(room/2)) / |s_A|, room = tol ∓ ψ_ss
//     (the band's edge on ψ0's side), infinite if |ψ_ss| ≥ tol or a steady tilt ≥ its tolerance (the
//     quasi-static azimuth loop ψ' = s_A sin(ψ − ψ_ss), levelling settled: tan(ψ/2) ∝ e^{s_A t});
//     ∝ 1/cosφ through s_A ≈ −k_a ω^E cosφ and ψ_ss ≈ −ε_E/(ω^E cosφ)
//   latitude limit: the largest |φ| whose alignment time is ≤ the scene's maximum (bisection; the time
//     grows monotonically with |φ|).
// Docs: docs/models/platform-alignment.md
#pragma once

#include <cmath>
#include <limits>

#include "firmware/control/platform_alignment_loops.hpp"
#include "sim/models/platform_alignment.hpp"

namespace gyrostab::oracles {

// The levelling channel's response to an initial tilt θ0 (header) [rad].
inline double levelling_response(double theta0, double bandwidth, double damping, double t) {
  const double s = damping * bandwidth, wd = bandwidth * std::sqrt(1.0 - damping * damping);
  return theta0 * std::exp(-s * t) * (std::cos(wd * t) - (s / wd) * std::sin(wd * t));
}

// The slow real root of s³ + K1 s² + (K2 + Ω_N²) s + k_a K2 Ω_N [1/s].
inline double azimuth_slow_root(const firmware::PlatformAlignmentGains& g) {
  const double a2 = g.K1, a1 = g.K2 + g.Omega_N * g.Omega_N, a0 = g.k_a * g.K2 * g.Omega_N;
  double s = -a0 / a1;
  for (int i = 0; i < 60; ++i) {
    const double p = ((s + a2) * s + a1) * s + a0, dp = (3.0 * s + 2.0 * a2) * s + a1;
    const double next = s - p / dp;
    if (next == s) break;
    s = next;
  }
  return s;
}

// The loop's gains for a site at latitude φ (the controller configured for that latitude).
inline firmware::PlatformAlignmentGains gains_at(firmware::PlatformAlignmentLoopParams p, double latitude) {
  p.latitude = latitude;
  return firmware::platform_alignment_gains(p);
}

// The steady misalignment (header).
inline models::PlatformMisalignment steady_misalignment(const firmware::PlatformAlignmentGains& g,
                                                        const models::PlatformAlignmentParams& m, double gravity) {
  models::PlatformMisalignment s;
  s.tilt_east = -m.accel_bias.y() / gravity;
  s.tilt_north = m.accel_bias.x() / gravity;
  s.heading_error = -m.drift.x() / g.Omega_N - s.tilt_north * g.Omega_U / g.Omega_N -
                    (m.drift.z() + g.Omega_N * s.tilt_east) / (g.k_a * g.Omega_N);
  return s;
}

struct AlignmentTimeInputs {
  firmware::PlatformAlignmentLoopParams loop{};  // the controller's (its latitude is replaced by the site's)
  models::PlatformAlignmentParams platform{};    // drifts and biases (its latitude is replaced)
  double gravity{9.81};                          // [m/s²]
  double heading_error0{0.0};                    // ψ0 [rad]
  double heading_tolerance{1e-3};                // [rad]
  double tilt_tolerance{1e-4};                   // [rad]
  double switch_time{0.0};                       // start of the azimuth phase [s]
};

// Alignment time at latitude φ (header) [s]; +inf when the residual heading error reaches the tolerance.
inline double alignment_time(const AlignmentTimeInputs& in, double latitude) {
  const firmware::PlatformAlignmentGains g = gains_at(in.loop, latitude);
  models::PlatformAlignmentParams m = in.platform;
  m.latitude = latitude;
  const models::PlatformMisalignment ss = steady_misalignment(g, m, in.gravity);
  const double psi_ss = ss.heading_error;
  if (!(std::fabs(psi_ss) < in.heading_tolerance && std::fabs(ss.tilt_east) < in.tilt_tolerance &&
        std::fabs(ss.tilt_north) < in.tilt_tolerance))
    return std::numeric_limits<double>::infinity();
  // ψ approaches ψ_ss from ψ0's side and enters the band at ±tol on that side.
  const double side = in.heading_error0 >= psi_ss ? 1.0 : -1.0;
  const double room = in.heading_tolerance - side * psi_ss;
  const double start = std::fabs(in.heading_error0 - psi_ss);
  const double decay =
      start > room ? std::log(std::tan(0.5 * start) / std::tan(0.5 * room)) / std::fabs(azimuth_slow_root(g)) : 0.0;
  return in.switch_time + decay;
}

// The largest |φ| ≤ 85° in the hemisphere of `hemisphere` (its sign) at which alignment_time ≤ max_time [rad];
// −1 when even the equator is too slow.
inline double latitude_limit(const AlignmentTimeInputs& in, double max_time, double hemisphere = 1.0) {
  constexpr double kTop = 85.0 * 3.14159265358979323846 / 180.0;
  const double sign = hemisphere < 0.0 ? -1.0 : 1.0;
  if (!(alignment_time(in, 0.0) <= max_time)) return -1.0;
  if (alignment_time(in, sign * kTop) <= max_time) return kTop;
  double lo = 0.0, hi = kTop;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (alignment_time(in, sign * mid) <= max_time ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace gyrostab::oracles
