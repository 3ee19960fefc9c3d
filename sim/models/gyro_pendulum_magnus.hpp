// Gyro pendulum (and physical pendulum, H = 0) whose pivot moves arbitrarily over the spherical Earth —
// Magnus §12.3.3, the small-angle equations (12.52)-(12.58) (docs/models/gyro-pendulum.md):
//   (12.52) the reference frame keeps axis 3 on the geocentric vertical, Ω = (−v2/R, v1/R, 0): the
//           azimuth-free trihedron F of sim/motion/earth_vehicle.hpp (F3 up, no absolute vertical rate)
//   (12.55) A(α'' − v2'/R) + H β' + (H/R) v1 = −m s v2' − k α
//           A(β'' + v1'/R) − H α' + (H/R) v2 = +m s v1' − k β
//   (12.57) k = m g s − (3g/R)(C − A)
//   (12.58) A z'' − i H z' + k z = i (m s − A/R) w' − (H/R) w,   z = α + iβ,  w = v1 + i v2
// v = (v1, v2): the pivot's ABSOLUTE velocity (own + Earth transport) in F axes; w' = (a1 + i a2), the
// horizontal absolute acceleration in F axes (exact: Ω is horizontal, so Ω × v is vertical).
// α, β: small rotations of the case about F1, F2; the rotor axis is ≈ (β, −α, 1) in F.
// Neglected (book): the pivot's centripetal acceleration in m g s (g, not g − |v|²/R) and the frame-rate
// terms of order A|Ω|² — relative errors ~|v_abs|²/(gR) and ~A|Ω|²/k (3.5e-3 and 2e-3 with the Earth's
// rotation at mid latitudes; 4e-5 at 50 m/s on a non-rotating sphere), plus O(tilt²) of the small angles.
// Measured against the 3-D and Chelnokov forms in tests/oracle/gyro_pendulum_cross_test.cpp.
//
// State x = [α (rad), β (rad), α' (rad/s), β' (rad/s)].
// Parameters (SI): A transverse, C axial moment of rotor + case about the pivot [kg m²]; H spin momentum
// [N m s]; m [kg]; s centre-of-mass distance BELOW the pivot [m] (the book's pendulous sign); R [m], g [m/s²].
// Fast part for dynamics::GyroscopicExponential: α'' ∋ −(H/A) β', β'' ∋ +(H/A) α' — the nutation ω^N ≈ H/A
// (12.61) carried exactly, so the 84-min precession can be stepped at h ω^N up to 0.8·2π
// (ω^N/|ω^P| ≈ 2e5 for the tuned reference instrument). Without spin (H = 0) use dynamics::Rk4.
// Closed forms: sim/oracles/schuler_tuning.hpp ((12.60), (12.61), (12.66)-(12.68), −Hw/(kR)).
// Oracles: tests/oracle/gyro_pendulum_magnus_test.cpp.
// Docs: docs/models/gyro-pendulum.md#magnuss-small-angle-form
#pragma once

#include <cmath>

#include "sim/dynamics/damped_gyroscopic_flow.hpp"
#include "sim/motion/suspension_reference.hpp"

namespace gyrostab::models {

struct GyroPendulumMagnusParams {
  double A{0.02};     // [kg m²]
  double C{0.025};    // [kg m²]
  double H{5.0};      // [N m s]
  double m{5.0};      // [kg]
  double s{1.264922e-4};  // [m], > 0 below the pivot
  double R{6.371e6};  // [m]
  double g{9.81};     // [m/s²]
  bool gravity_gradient{true};  // the −(3g/R)(C − A) of (12.57)

  double k() const { return m * g * s - (gravity_gradient ? 3.0 * g / R * (C - A) : 0.0); }  // (12.57)

  const char* invalid_reason() const {
    if (!(std::isfinite(A) && A > 0.0)) return "A must be finite and > 0";
    if (!(std::isfinite(C) && C >= 0.0)) return "C must be finite and >= 0";
    if (!std::isfinite(H)) return "H must be finite";
    if (!(std::isfinite(m) && m > 0.0)) return "m must be finite and > 0";
    if (!std::isfinite(s)) return "s must be finite";
    if (!(std::isfinite(R) && R > 0.0 && std::isfinite(g) && g > 0.0)) return "R and g must be finite and > 0";
    return nullptr;
  }
};

template <class Reference>
class GyroPendulumMagnus {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  static constexpr const char* kName = "gyro-pendulum-magnus";
  // The state's components, by name.
  static constexpr int kAlpha = 0, kBeta = 1, kAlphaRate = 2, kBetaRate = 3;

  GyroPendulumMagnus(const GyroPendulumMagnusParams& p, const Reference& ref) : p_(p), ref_(ref), k_(p.k()) {}

  double M1{0.0}, M2{0.0};  // extra torques about F1, F2 [N m] (held)

  const GyroPendulumMagnusParams& params() const { return p_; }
  Reference& reference() { return ref_; }
  const Reference& reference() const { return ref_; }

  static State make_state(double alpha, double beta, double alpha_rate = 0.0, double beta_rate = 0.0) {
    State x;
    x << alpha, beta, alpha_rate, beta_rate;
    return x;
  }

  void derivative(double t, const State& x, State& dx) const {
    const motion::SuspensionSample r = ref_(t);
    const double A = p_.A, H = p_.H, R = p_.R;
    const double v1 = r.v_Z.x(), v2 = r.v_Z.y(), dv1 = r.a_Z.x(), dv2 = r.a_Z.y();
    const double k = k_;
    dx[0] = x[2];
    dx[1] = x[3];
    dx[2] = (M1 - H * x[3] - (H / R) * v1 - p_.m * p_.s * dv2 - k * x[0]) / A + dv2 / R;
    dx[3] = (M2 + H * x[2] - (H / R) * v2 + p_.m * p_.s * dv1 - k * x[1]) / A - dv1 / R;
  }
  void project(State& /*x*/) const {}

  dynamics::GyroscopicPair gyroscopic_pair(const State& /*x*/) const {
    return {p_.H / p_.A, p_.H / p_.A, 0.0, 0.0};
  }

 private:
  GyroPendulumMagnusParams p_;
  Reference ref_;
  double k_;
};

}  // namespace gyrostab::models
