// Gyro-stabilized monorail car: car tilt φ coupled to the precession β of a top-heavy gyro case, with the
// damper and the motor law of the book, and curve running (path turning at Ω3), with large-angle terms.
//
// Book: Magnus §14.1, equations (14.1)-(14.7) (docs/models/monorail.md). Small angles, (14.2), (14.6):
//   A φ'' + H β' + (H Ω3 − c) φ = M1,     B β'' + d β' + (H Ω3 − q) β − H φ' − k φ = M2
// (Ω3 = 0 and M1 = M2 = 0: (14.2)). Geometry (Fig. 14.2): the case G pivots on the car about axis 2,
// perpendicular to the track and horizontal at β = 0; the rotor axis 3 is vertical at β = 0 and the centre of
// mass of case + rotor lies above axis 2 (q > 0: statically unstable like the car, c > 0, as (14.4/2)
// requires); the car tilts by φ about the rail (axis 1, along the track; the OCR's "transverse axis" for A is
// read as the longitudinal one, docs/models/monorail.md). A damper d and a motor act on axis 2; the book's
// motor law is M^M = k φ. This is the two-gimbal gyro of (10.4) with the car as the outer gimbal, on a base
// (the path frame) turning about the vertical at Ω3. Implemented, with I(β) = A − Q sin²β:
//   I(β) φ'' − Q sin2β φ'β' + H cosβ β' + H Ω3 sinφ cosβ = c sinφ − q sinφ (1 − cosβ) + M1
//   B β'' + Q sinβ cosβ φ'² − H cosβ φ' + H Ω3 cosφ sinβ = q cosφ sinβ − d β' + k φ + M2
// Large-angle terms, each reducing to (14.2)/(14.6) at first order:
//   - gyroscopic coupling H cosβ (the rotor axis leaves the vertical by β), as in (10.4), (14.41);
//   - inertia terms of case + rotor, Q = A^R + A^J − C^J of (10.4) (0 by default);
//   - overturning gravity of the car c sinφ (c = m g h of the whole car at β = 0, so the case's weight
//     appears only through its change with β, −q sinφ (1 − cosβ)) and of the case q cosφ sinβ (q = G s);
//     the potential is V = −(c − q)(1 − cosφ) − q (1 − cosφ cosβ);
//   - the frame-rate terms of the spin momentum: with e3 = (sinβ, −sinφ cosβ, cosφ cosβ) the rotor axis in
//     path axes, the turn adds H Ω3 (z × e3) to dH/dt, whose components on the two gimbal axes are
//     H Ω3 sinφ cosβ and H Ω3 cosφ sinβ — a potential −H Ω3 cosφ cosβ (the "tendency to parallelism" of
//     §10.2), giving c − HΩ3 and q − HΩ3 of (14.6) at first order.
// As in (14.6) (and (10.22) with AΩ3, BΩ3 ≪ H) only the spin momentum feels the turn: the bodies' own
// frame-rate terms (centrifugal (C − B)Ω3² sinφ cosφ of the car, B Ω3 φ'-type terms of the case) and the
// tilt of the apparent vertical by the centripetal acceleration v Ω3 (which shifts the equilibrium to a
// lean into the curve but leaves (14.6)'s stability unchanged) are neglected. Ω3 is held constant between
// steps (its rate Ω3' does not enter).
// The motor law k φ is the book's continuous (analog) loop and is part of this plant when k ≠ 0; when the
// firmware closes the loop (firmware/ monorail law) set k = 0 and drive the motor through the input M2.
//
// State x = [φ (rad), β (rad), φ' (rad/s), β' (rad/s)].
// Parameters (book symbols, SI): A car (with installation) inertia about the rail at β = 0 [kg m²]; c
// overturning stiffness m g h of the car [N m/rad]; B case + rotor about axis 2 [kg m²]; Q [kg m²];
// q overturning stiffness of the case G s [N m/rad]; H spin momentum [N m s]; d damper on axis 2
// [N m s/rad]; k motor law gain [N m/rad].
// Inputs (zero-order hold): Omega3 path turning rate about the vertical, positive in the rotor's spin sense
// [rad/s]; M1 disturbance torque on the car (wind, load shift) [N m]; M2 motor torque on axis 2 [N m].
// Assumptions: rigid car tilting about the rail (no derailment, |φ| < π/2: beyond, the car lies on the
// ground and the model no longer applies); spin constant; no case end stops (the monorail's stability
// window is the subject; stops as in ship_roll_damper.hpp if needed).
// Defaults: the constructed reference car (docs/models/monorail.md): A 3000, c 2e4, B 50, q 500, H 4000,
// d 200; k = 0.
// Oracle: tests/oracle/monorail_test.cpp — growth rates just inside/outside the gain window
// d(c + Aω_P²)/H < k < d(c + Aω_N²)/H vs the roots of (14.3); curve running with c > HΩ3 > q (14.7)
// overturns at the rate of (14.6)'s positive root; energy conservation with the large-angle terms.
// Docs: docs/models/monorail.md
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace gyrostab::models {

struct MonorailParams {
  double A{3000.0};  // car inertia about the rail, β = 0 [kg m²]
  double c{2.0e4};   // overturning stiffness of the car m g h [N m/rad]
  double B{50.0};    // case + rotor about axis 2 [kg m²]
  double Q{0.0};     // A^R + A^J − C^J of (10.4): I(β) = A − Q sin²β [kg m²]
  double q{500.0};   // overturning stiffness of the case G s [N m/rad]
  double H{4000.0};  // rotor spin momentum [N m s]
  double d{200.0};   // damper on axis 2 [N m s/rad]
  double k{0.0};     // motor law M = k φ (book's analog loop; 0 when the firmware drives M2) [N m/rad]

  // nullptr if the parameters are physically possible, else the reason (for scene validation).
  const char* invalid_reason() const {
    if (!(A > 0.0)) return "A (car inertia) must be > 0";
    if (!(B > 0.0)) return "B (case inertia) must be > 0";
    if (!(A - Q > 0.0)) return "A - Q must be > 0 (I(beta) = A - Q sin^2 beta)";
    if (!(c >= 0.0) || !(q >= 0.0)) return "c, q must be >= 0 (overturning stiffnesses of (14.2))";
    if (!(H >= 0.0)) return "H must be >= 0";
    if (!(d >= 0.0)) return "d must be >= 0";
    return nullptr;
  }
};

struct MonorailInputs {
  double Omega3{0.0};  // path turning rate about the vertical, + in the spin sense [rad/s]
  double M1{0.0};      // disturbance torque on the car [N m]
  double M2{0.0};      // motor torque on the case axis 2 [N m]
};

class Monorail {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  static constexpr const char* kName = "monorail";
  // The state's components, by name.
  static constexpr int kTilt = 0, kCase = 1, kTiltRate = 2, kCaseRate = 3;

  explicit Monorail(const MonorailParams& p = {}) : p_(p) {}

  MonorailInputs inputs{};  // held between steps

  const MonorailParams& params() const { return p_; }

  static State make_state(double phi, double beta, double phi_rate, double beta_rate) {
    State x;
    x << phi, beta, phi_rate, beta_rate;
    return x;
  }

  void derivative(double /*t*/, const State& x, State& dx) const {
    const double sp = std::sin(x[0]), cp = std::cos(x[0]);
    const double sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double u = x[2], v = x[3];
    const double HW = p_.H * inputs.Omega3;
    const double tilt = inputs.M1 + p_.c * sp - p_.q * sp * (1.0 - cb) - HW * sp * cb +
                        2.0 * p_.Q * sb * cb * u * v - p_.H * cb * v;
    const double precession = inputs.M2 + p_.k * x[0] - p_.d * v + p_.q * cp * sb - HW * cp * sb +
                              p_.H * cb * u - p_.Q * sb * cb * u * u;
    dx[0] = u;
    dx[1] = v;
    dx[2] = tilt / (p_.A - p_.Q * sb * sb);
    dx[3] = precession / p_.B;
  }
  void project(State& /*x*/) const {}

  // Energy in the path frame [J]: ½ I(β) φ'² + ½ B β'² + V, V = −(c − q)(1 − cosφ) − q (1 − cosφ cosβ)
  // − HΩ3 (cosφ cosβ − 1). Conserved with d = k = 0, M1 = M2 = 0 and constant Ω3.
  double energy(const State& x) const {
    const double cp = std::cos(x[0]), sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double V =
        -(p_.c - p_.q) * (1.0 - cp) - p_.q * (1.0 - cp * cb) - p_.H * inputs.Omega3 * (cp * cb - 1.0);
    return 0.5 * (p_.A - p_.Q * sb * sb) * x[2] * x[2] + 0.5 * p_.B * x[3] * x[3] + V;
  }

 private:
  MonorailParams p_;
};

}  // namespace gyrostab::models
