// Corrections of the directional (heading) gyro: the torques its two torquers apply — drift compensation and
// heading correction about the inner gimbal axis (M2), inter-gimbal correction about the outer, normal axis
// (M1) — each a pure function, and their sum with the turn cut-out and the torque limit.
//
// Book: Magnus §12.2 (docs/models/directional-gyro.md), precession equations H β' = M1, −H α' = M2:
//   (12.22)  compensation  M2 = −H (ω^E sin φ + (v/R) sin ψ tan φ)      cancels the apparent drift α'^R
//   (12.23)  heading correction  M2 = H κ (ψ − ψ_soll)   ⇒  ψ' = −κ (ψ − ψ_soll): the indication approaches
//            the reference (compass) exponentially, time constant 1/κ; κ is given as the correction rate
//            at 1° of error, κ = (°/min at 1°)/60 per s — the book's practical rates 0.1 … 4 °/min
//   (12.24)  inter-gimbal correction  M1 = −k β  ⇒  β' = −(k/H) β: keeps the inner gimbal ⟂ the outer one
// The compensation is set, like an instrument's latitude nut, for a latitude φ_c and a ground speed v_c
// (configuration; the law has no navigation input), with the heading ψ = the gyro's own indication; away
// from φ_c, v_c it leaves the drift difference of (12.22). The turn cut-out (the book: "some gyros switch
// the correction off during turns", (12.34)) removes both corrections — not the compensation — while the
// turn-rate signal reads at least turn_cutout_rate.
// Signals: reads the indicated heading ψ, the reference ψ_soll (both wrapped to (−π, π]) [rad], β [rad], the
// turn rate [rad/s]; writes M1, M2 [N m], clipped to ±torque_limit_Nm. Pure functions, O(1), no heap; sin,
// cos from firmware/math/deterministic_math.hpp.
// Sampled-data check (period T): the corrections are first-order loops of rates κ and k/H; κT ≤ 0.5 and
// kT/H ≤ 0.5 (the discrete pole 1 − rate·T stays in [0.5, 1): no sign-alternating correction); the
// compensation alone must fit in the torque limit; |φ_c| ≤ 85° (tan φ).
// Tests: tests/oracle/directional_gyro_test.cpp (closed loop against (12.22), (12.23), (12.29), (12.32)).
// Docs: docs/models/directional-gyro.md#firmware-law
#pragma once

#include <cmath>

#include "firmware/control/config_check.hpp"
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

struct DirectionalGyroCorrectionParams {
  double H{0.1};                   // spin momentum the law assumes [N m s]
  bool compensate{true};           // (12.22) on
  double earth_rate{7.292115e-5};  // ω^E [rad/s]
  double earth_radius{6.371e6};    // R [m]
  double latitude{0.0};            // φ_c the compensation is set for [rad]
  double speed{0.0};               // v_c the compensation is set for [m/s]
  double heading_rate{0.0};        // κ of (12.23) [1/s]; 0: off
  double k{0.0};                   // (12.24) M1 = −k β [N m/rad]; 0: off
  double turn_cutout_rate{0.0};    // corrections off while |turn rate| ≥ this; 0: never [rad/s]
  double torque_limit_Nm{0.01};    // |M1|, |M2| ≤ this [N m]
};

struct DirectionalGyroSignals {
  double heading{0.0};      // ψ, the gyro's indication [rad]
  double beta{0.0};         // β, inner-gimbal pick-off [rad]
  double heading_ref{0.0};  // ψ_soll, the reference (compass) [rad]
  double turn_rate{0.0};    // vehicle turn rate (cut-out input) [rad/s]
};

struct DirectionalGyroTorques {
  double M1{0.0};  // [N m]
  double M2{0.0};  // [N m]
  bool cut_out{false};  // the turn cut-out removed correction torque this call
  bool limited{false};  // a torque was clipped to ±torque_limit_Nm
};

inline constexpr double kDirectionalGyroPi = 3.14159265358979323846;

// a − b wrapped to (−π, π] for a, b in (−π, π] [rad].
constexpr double heading_difference(double a, double b) {
  double e = a - b;
  if (e > kDirectionalGyroPi) e -= 2.0 * kDirectionalGyroPi;
  if (e <= -kDirectionalGyroPi) e += 2.0 * kDirectionalGyroPi;
  return e;
}

// (12.22): the apparent drift rate α'^R of an uncorrected gyro at latitude φ, speed v, heading ψ [rad/s].
inline double apparent_drift_rate(double earth_rate, double radius, double latitude, double speed, double heading) {
  const double tan_phi = math::sin(latitude) / math::cos(latitude);
  return -earth_rate * math::sin(latitude) - (speed / radius) * math::sin(heading) * tan_phi;
}

// (12.22): the compensating torque about the inner axis at the indicated heading [N m]. O(1).
inline double drift_compensation_torque(const DirectionalGyroCorrectionParams& p, double heading) {
  if (!p.compensate) return 0.0;
  return p.H * apparent_drift_rate(p.earth_rate, p.earth_radius, p.latitude, p.speed, heading);
}

// (12.23): the heading correction about the inner axis [N m]. O(1).
constexpr double heading_correction_torque(const DirectionalGyroCorrectionParams& p, double heading,
                                           double heading_ref) {
  return p.H * p.heading_rate * heading_difference(heading, heading_ref);
}

// (12.24): the inter-gimbal correction about the outer axis [N m]. O(1).
constexpr double intergimbal_torque(const DirectionalGyroCorrectionParams& p, double beta) {
  return -p.k * beta;
}

// The three, the cut-out and the limit. O(1).
inline DirectionalGyroTorques directional_gyro_corrections(const DirectionalGyroCorrectionParams& p,
                                                           const DirectionalGyroSignals& s) {
  DirectionalGyroTorques out;
  double M1 = intergimbal_torque(p, s.beta);
  double M2c = heading_correction_torque(p, s.heading, s.heading_ref);
  const double turn = s.turn_rate < 0.0 ? -s.turn_rate : s.turn_rate;
  if (p.turn_cutout_rate > 0.0 && turn >= p.turn_cutout_rate) {
    out.cut_out = M1 != 0.0 || M2c != 0.0;
    M1 = 0.0;
    M2c = 0.0;
  }
  out.M1 = M1;
  out.M2 = drift_compensation_torque(p, s.heading) + M2c;
  const double L = p.torque_limit_Nm;
  if (out.M1 > L || out.M1 < -L || out.M2 > L || out.M2 < -L) out.limited = true;
  out.M1 = out.M1 > L ? L : (out.M1 < -L ? -L : out.M1);
  out.M2 = out.M2 > L ? L : (out.M2 < -L ? -L : out.M2);
  return out;
}

// Start-up check for control period T [s]. O(1).
inline ConfigCheck check_directional_gyro_corrections(const DirectionalGyroCorrectionParams& p, double T) {
  const auto finite = [](double x) { return std::isfinite(x); };
  if (!(finite(p.H) && p.H > 0.0)) return ConfigCheck::refused("directional gyro: H must be finite and > 0", p.H);
  if (!(finite(p.earth_rate) && finite(p.earth_radius) && p.earth_radius > 0.0)) {
    return ConfigCheck::refused("directional gyro: Earth rate finite and radius finite and > 0");
  }
  constexpr double kMaxLatitude = 85.0 * kDirectionalGyroPi / 180.0;
  if (!(finite(p.latitude) && p.latitude >= -kMaxLatitude && p.latitude <= kMaxLatitude)) {
    return ConfigCheck::refused("directional gyro: compensation latitude outside [-85, 85] deg (tan phi of (12.22))",
                                p.latitude, -kMaxLatitude, kMaxLatitude);
  }
  if (!(finite(p.speed) && p.speed >= 0.0)) {
    return ConfigCheck::refused("directional gyro: compensation speed must be finite and >= 0", p.speed);
  }
  if (!(finite(p.heading_rate) && p.heading_rate >= 0.0 && finite(p.k) && p.k >= 0.0 &&
        finite(p.turn_cutout_rate) && p.turn_cutout_rate >= 0.0)) {
    return ConfigCheck::refused("directional gyro: heading_rate, k and the cut-out rate must be finite and >= 0");
  }
  if (!(finite(p.torque_limit_Nm) && p.torque_limit_Nm > 0.0)) {
    return ConfigCheck::refused("directional gyro: torque_limit_Nm must be finite and > 0", p.torque_limit_Nm);
  }
  if (!(finite(T) && T > 0.0)) return ConfigCheck::refused("directional gyro: control period must be > 0", T);
  if (!(p.heading_rate * T <= 0.5)) {
    return ConfigCheck::refused("directional gyro: heading correction kappa T > 0.5, the sampled (12.23) overshoots",
                                p.heading_rate, 0.0, 0.5 / T);
  }
  if (!(p.k * T <= 0.5 * p.H)) {
    return ConfigCheck::refused("directional gyro: inter-gimbal k T / H > 0.5, the sampled (12.24) overshoots", p.k,
                                0.0, 0.5 * p.H / T);
  }
  if (p.compensate) {
    // The largest |(12.22)| over all headings at (φ_c, v_c).
    const double s = math::sin(p.latitude), c = math::cos(p.latitude);
    const double worst = p.H * ((p.earth_rate < 0.0 ? -p.earth_rate : p.earth_rate) * (s < 0.0 ? -s : s) +
                                (p.speed / p.earth_radius) * (s < 0.0 ? -s : s) / c);
    if (!(worst <= p.torque_limit_Nm)) {
      return ConfigCheck::refused("directional gyro: the (12.22) compensation alone exceeds torque_limit_Nm", worst,
                                  0.0, p.torque_limit_Nm);
    }
  }
  return ConfigCheck::accepted();
}

}  // namespace gyrostab::firmware
