// The book's closed forms for the gimbal angles of a position gyro (Magnus, Kreisel §12.1): what the
// kinematics of sim/models/position_gyro_gimbal_error.hpp must reproduce, per mounting configuration, and
// the heading gyro's turn error.
//   "321" (12.11)  tanα = (sψcφ − cψsϑsφ)/(cψcϑ),            sinβ = sψsφ + cψsϑcφ
//   "123" (12.16)  α = φ, β = ϑ
//   "213" (12.17)  tanα = tanϑ / cosφ,                        sinβ = sφcϑ
//   "132" (12.18)  tanα = (sφcψ − sψsϑcφ)/(cφcψ + sψsϑsφ),    sinβ = sψcϑ
//   "312" (12.19)  tanα = (sψsφ + cψsϑcφ)/(cψcϑ),             sinβ = sψcφ − cψsϑsφ
//   "231" (12.20)  tanα = sψcϑ/(cψcφ + sψsϑsφ),               sinβ = sφcψ − sψsϑcφ
// (12.20)'s numerator is sψ cosϑ: the only form the kinematics gives and the one that reads α = ψ at ϑ = φ = 0.
// Each tanα is returned as the pair (numerator, denominator) whose atan2 is α itself, not α mod π: with the
// det +1 mountings of the model the numerator and denominator are −v2 and v3 exactly (cosβ > 0).
// Heading gyro "321" in a level turn (ϑ = 0), Δψ = α − ψ (12.12):
//   (12.13) tanα = tanψ cosφ,   (12.14) tanΔψ = −tanψ (1 − cosφ)/(1 + cosφ tan²ψ),   (12.15) Δψ ≈ −¼ φ² sin2ψ;
//   its extreme (the derivative of (12.14) in ψ vanishes at tan²ψ = 1/cosφ): tanΔψ = −(1 − cosφ)/(2√cosφ).
// Docs: docs/models/gimbal-error.md. Test: tests/oracle/gimbal_error_test.cpp.
#pragma once

#include <cmath>

#include "sim/models/position_gyro_gimbal_error.hpp"

namespace gyrostab::oracles {

struct GimbalClosedForm {
  double tan_num{0.0}, tan_den{0.0};  // tanα = tan_num / tan_den; α = atan2(tan_num, tan_den)
  double sin_beta{0.0};
  double alpha() const { return std::atan2(tan_num, tan_den); }
};

// ψ yaw, ϑ pitch, φ roll [rad] (12.2).
inline GimbalClosedForm gimbal_closed_form(models::GimbalMounting m, double psi, double theta, double phi) {
  const double sps = std::sin(psi), cps = std::cos(psi), sth = std::sin(theta), cth = std::cos(theta);
  const double sph = std::sin(phi), cph = std::cos(phi);
  using M = models::GimbalMounting;
  switch (m) {
    case M::k321: return {sps * cph - cps * sth * sph, cps * cth, sps * sph + cps * sth * cph};
    case M::k123: return {sph * cth, cph * cth, sth};  // tanα = tanφ with cosϑ > 0: α = φ
    case M::k213: return {sth, cth * cph, sph * cth};  // tanϑ / cosφ, times cosϑ > 0
    case M::k132: return {sph * cps - sps * sth * cph, cph * cps + sps * sth * sph, sps * cth};
    case M::k312: return {sps * sph + cps * sth * cph, cps * cth, sps * cph - cps * sth * sph};
    case M::k231: return {sps * cth, cps * cph + sps * sth * sph, sph * cps - sps * sth * cph};
  }
  return {};
}

// (12.14) multiplied through by cos²ψ, so that ψ = ±90° needs no tan: Δψ = α − ψ [rad], bank φ [rad].
inline double heading_gyro_turn_error(double psi, double phi) {
  const double s = std::sin(psi), c = std::cos(psi), cph = std::cos(phi);
  return std::atan2(-s * c * (1.0 - cph), c * c + cph * s * s);
}

// (12.15), small bank [rad].
inline double heading_gyro_turn_error_small_bank(double psi, double phi) {
  return -0.25 * phi * phi * std::sin(2.0 * psi);
}

struct TurnErrorExtreme {
  double error{0.0};    // Δψ at the extreme, ψ in (0, 90°): negative [rad]
  double heading{0.0};  // ψ where it occurs, tan²ψ = 1/cosφ [rad]
};
inline TurnErrorExtreme heading_gyro_turn_error_extreme(double phi) {
  const double cph = std::cos(phi);
  return {std::atan(-(1.0 - cph) / (2.0 * std::sqrt(cph))), std::atan(1.0 / std::sqrt(cph))};
}

}  // namespace gyrostab::oracles
