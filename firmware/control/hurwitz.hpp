// Hurwitz stability test for the cubic and quartic characteristic equations of the ch. 14 control loops:
// every root has a negative real part iff all coefficients are positive and the Hurwitz determinants are.
//
//   cubic   a3 λ³ + a2 λ² + a1 λ + a0:            D2 = a2 a1 − a3 a0
//   quartic a4 λ⁴ + a3 λ³ + a2 λ² + a1 λ + a0:    D2 = a3 a2 − a4 a1,   D3 = a1 D2 − a3² a0
// (Magnus §5.2.2 / 14.3; with all coefficients positive, D3 > 0 of the quartic implies D2 > 0). These are
// the D^II, D^III of (14.25) for (14.23) and the D^II of (14.30) for the cubic factor of (14.29), up to
// the positive factors the book keeps.
// O(1), no heap, no exceptions; a NaN coefficient makes every test false (comparisons with NaN are false).
// Used by firmware/control/power_stabilizer_loops.hpp; tested through tests/oracle/power_stabilizer_test.cpp.
// Docs: docs/models/power-stabilizer.md#equations
#pragma once

namespace gyrostab::firmware {

struct HurwitzResult {
  bool coefficients_positive{false};  // every a_i > 0 (necessary)
  double D2{0.0};                     // second Hurwitz determinant
  double D3{0.0};                     // third (quartic only; 0 for a cubic)
  bool stable{false};                 // all roots in the open left half-plane
};

constexpr HurwitzResult hurwitz_cubic(double a3, double a2, double a1, double a0) {
  HurwitzResult r;
  r.coefficients_positive = a3 > 0.0 && a2 > 0.0 && a1 > 0.0 && a0 > 0.0;
  r.D2 = a2 * a1 - a3 * a0;
  r.stable = r.coefficients_positive && r.D2 > 0.0;
  return r;
}

constexpr HurwitzResult hurwitz_quartic(double a4, double a3, double a2, double a1, double a0) {
  HurwitzResult r;
  r.coefficients_positive = a4 > 0.0 && a3 > 0.0 && a2 > 0.0 && a1 > 0.0 && a0 > 0.0;
  r.D2 = a3 * a2 - a4 * a1;
  r.D3 = a1 * r.D2 - a3 * a3 * a0;
  r.stable = r.coefficients_positive && r.D2 > 0.0 && r.D3 > 0.0;
  return r;
}

}  // namespace gyrostab::firmware
