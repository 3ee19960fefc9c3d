// Pendulous gyrocompass on a fixed base or on a ship: a rotor with a horizontal axis, free about the vertical,
// coupled to the vertical by a pendulous torque (CoM below the pivot and/or a level sensor driving a torquer),
// so that Earth's rotation turns it into the meridian; damped by a torque about the vertical from the level
// sensor (the firmware, firmware/control/gyrocompass_law.hpp).
//
// Book: Magnus ch. 13 (docs/models/gyrocompass.md): fixed base (13.7)-(13.16), moving base — speed deviation
// (13.17)-(13.18), ballistic deviation and Schuler tuning (13.19)-(13.28), rolling error (13.29)-(13.39);
// built on the master equation (10.22) (§10.2, sim/models/gyro_in_rotating_frame.hpp).
// Frame (book §13.1): axis 1 up, axis 2 east, axis 3 north (geographic; it does not turn with the ship):
//   Ω = ω_IG in these axes = [(ω^E + ω^EO) sinφ, −ω^EN, (ω^E + ω^EO) cosφ]   (13.20), = Magnus (16.51)
// taken from the vehicle generator's geographic ENU trihedron G as Ω = (Ω_G3, Ω_G1, Ω_G2), likewise f.
// α = azimuth of the rotor axis (rotation about the vertical, positive toward WEST: the rotor axis is
// ≈ (β, −α, 1)), β = elevation of its north end. The compass error (indicated − true heading) is +α; the
// speed deviation (13.23) α0 = v^N/(Rω^E cosφ + v^E) > 0 northbound is the classical westerly error.
// Level (apparent horizon) of the specific force f: β_L = atan2(−f_N, f_up) (≈ −b^N/g); the level sensor on
// the sphere reads β − β_L, the "β + b^N/g" of (13.21).
// Torques: M1 = torquer about the vertical (damping −fβ of (13.8), firmware) + the rolling-error torque
//          − d1 α';  M2 = −c (β − β_L) (pendulous moment c = G s, (13.8)/(13.21)) + torquer (electrical
//          pendulosity) − d2 β' (d1, d2: viscous damping of the floated sphere, 0 in the book).
// [derived] Nutation hidden by the precession theory (docs/models/gyrocompass.md): the damping torque −fβ is
// a circulatory (non-conservative positional) force; in the full form without d1, d2 the coefficient of λ³ of
// the characteristic quartic is 0, so the roots sum to 0 and the nutation pair grows at the rate δ/2 at which
// the compass mode decays. d1, d2 with (d1/A + d2/B)/2 > δ/2 (roughly) make it decay. Their effect on the
// compass mode follows (11.4) with c1 = HΩ3, c2 = c + HΩ3: extra decay (d1 c2 + d2 c1)/(2(H² + d1 d2)) —
// large for d1 (c2 >> c1), negligible for d2, so damp the nutation with d2. tests/oracle/gyrocompass_test.cpp
// checks the growth without and the decay with damping. With f = 0, the full form is (13.7) (with
// AΩ3, BΩ3 << H) and the precession form (13.10)/(13.22). Rolling error (13.29)-(13.36), optional
// (swing_inertia Θ_s > 0, needs c > 0): the sphere swings about its rotor axis under the athwartship
// acceleration b(t) of the ship's roll at height h above the roll axis,
//   (13.30)  b = h φ_s'' = −h Φ ω_s² sin ω_s t          (13.31)  Θ_s γ'' + c γ = (c/g) b cos(α + ψ)
//   (13.35)  M1 += −(c/g) b γ sin(α + ψ)                (ψ = ship heading; the book's sign conventions)
// whose mean (13.37) turns the compass by α^s (13.38).
//
// State x = [α, β (rad), α', β' (rad/s), γ (rad), γ' (rad/s)]. Precession form: x[2], x[3] unused (0).
// Parameters (SI): A, B [kg m²], H [N m s], c [N m/rad], d1, d2 [N m s/rad], g [m/s²], Θ_s [kg m²]
// (0: no swing), roll Φ [rad], period [s], h [m].
// Inputs: FrameInputs (compass axes), ship heading ψ [rad] (for the rolling error), torquer commands M1, M2
// [N m] (zero-order hold).
// Assumptions (book list after (13.28)): small α, β; large H; spherical Earth; gravity gradient neglected.
// Oracle: tests/oracle/gyrocompass_test.cpp — equilibrium (13.11), eigenvalues/period and decay (13.12),
// strong-coupling period (13.16), speed deviation (13.23), zero ballistic deviation when Schuler-tuned
// (13.26) and the predicted swing when not, rolling error (13.38).
// Docs: docs/models/gyrocompass.md
#pragma once

#include <cmath>

#include "sim/models/gyro_in_rotating_frame.hpp"

namespace gyrostab::models {

// Ship rolling φ_s = Φ sin ω_s t (13.29) seen by a compass at height h above the roll axis.
struct ShipRoll {
  double amplitude{0.0};  // Φ [rad]
  double period{10.0};    // 2π/ω_s [s]
  double height{0.0};     // h [m]

  double omega() const { return 2.0 * 3.14159265358979323846 / period; }
  double b0() const { return height * amplitude * omega() * omega(); }  // (13.30) amplitude [m/s²]
  double acceleration(double t) const { return -b0() * std::sin(omega() * t); }  // (13.30) [m/s²]
};

struct GyrocompassParams {
  GyroFrameParams gyro{0.05, 0.05, 2.0};
  double c{0.0};               // pendulous moment G s [N m/rad]
  double d1{0.0}, d2{0.0};     // viscous damping of the sphere about axes 1, 2 (the float's liquid) [N m s/rad]
  double gravity{9.81};        // g in (13.31), (13.35) [m/s²]
  double swing_inertia{0.0};   // Θ_s about the rotor axis; 0: no swing (no rolling error) [kg m²]
  ShipRoll roll{};
  InstrumentFidelity fidelity{InstrumentFidelity::kFull};

  const char* invalid_reason() const {
    if (const char* why = gyro_frame_invalid_reason(gyro, fidelity, c, d1, d2)) return why;
    const auto fin = [](double v) { return std::isfinite(v); };
    if (!(fin(gravity) && gravity > 0.0)) return "gravity must be finite and > 0";
    if (!(fin(swing_inertia) && swing_inertia >= 0.0)) return "swing_inertia must be finite and >= 0";
    if (swing_inertia > 0.0 && !(c > 0.0))
      return "the swing (rolling error) needs a mechanically pendulous sphere, c > 0";
    if (!(fin(roll.amplitude) && fin(roll.height) && fin(roll.period) && roll.period > 0.0))
      return "roll amplitude, height must be finite and the roll period > 0";
    return nullptr;
  }
};

struct GyrocompassInputs {
  FrameInputs frame{};  // frame motion over the step (compass axes: up, east, north)
  double heading{0.0};  // ship heading ψ, clockwise from north [rad]
  double M1{0.0};       // torquer about the vertical [N m]
  double M2{0.0};       // torquer about the east axis [N m]
};

// Elevation of the apparent horizon's north end, β_L = atan2(−f_N, f_up) [rad] (compass axes up, east, north).
inline double apparent_horizon_tilt(const dynamics::Vec3& f_compass) {
  return std::atan2(-f_compass.z(), f_compass.x());
}

class Gyrocompass {
 public:
  static constexpr int kStateSize = 6;
  using State = Eigen::Matrix<double, 6, 1>;
  // The state's components, by name (γ: the swing about the rotor axis).
  static constexpr int kAlpha = 0, kBeta = 1, kAlphaRate = 2, kBetaRate = 3, kSwing = 4, kSwingRate = 5;

  explicit Gyrocompass(const GyrocompassParams& p = {}) : p_(p) {}

  GyrocompassInputs inputs{};  // held between steps

  const GyrocompassParams& params() const { return p_; }

  static State make_state(double alpha, double beta) {
    State x = State::Zero();
    x[0] = alpha;
    x[1] = beta;
    return x;
  }

  void derivative(double t, const State& x, State& dx) const {
    const FrameSample w = inputs.frame.at(t);
    double M1 = inputs.M1;
    const double M2 = -p_.c * (x[1] - apparent_horizon_tilt(w.f)) + inputs.M2;
    dx[4] = x[5];
    dx[5] = 0.0;
    if (p_.swing_inertia > 0.0) {
      const double b = p_.roll.acceleration(t);
      const double phase = x[0] + inputs.heading;
      dx[5] = (-p_.c * x[4] + (p_.c / p_.gravity) * b * std::cos(phase)) / p_.swing_inertia;  // (13.31)
      M1 += -(p_.c / p_.gravity) * b * x[4] * std::sin(phase);                                 // (13.35)
    }
    gyro_frame_derivative(p_.gyro, p_.fidelity, w, x, M1, M2, p_.d1, p_.d2, dx);
  }
  void project(State&) const {}

  // (α', β') at time t [rad/s]: the state's (full) or the precession solution's.
  void rates(double t, const State& x, double& alpha_rate, double& beta_rate) const {
    gyro_frame_rates(*this, p_.fidelity, t, x, alpha_rate, beta_rate);
  }

  // The level sensor: elevation of the rotor axis above the apparent horizon, β − β_L [rad].
  double level_signal(double t, const State& x) const {
    return x[1] - apparent_horizon_tilt(inputs.frame.at(t).f);
  }

 private:
  GyrocompassParams p_;
};

// Closed forms of the precession theory for the checks and the run report (Magnus §13.2-13.3).
struct GyrocompassTheory {
  double H{1.0};            // [N m s]
  double c{0.0};            // total pendulous moment (mechanical + electrical) [N m/rad]
  double f{0.0};            // damping coefficient of M1 = −f β [N m/rad]
  double earth_rate{7.292115e-5};  // ω^E [rad/s]
  double latitude{0.0};     // φ [rad]

  double omega_c() const { return c / H; }                           // (13.9)
  double delta() const { return f / H; }                             // (13.9)
  double horizontal_rate() const { return earth_rate * std::cos(latitude); }  // ω^E cosφ
  // (13.11) equilibrium on a fixed base.
  double alpha0() const { return -delta() * std::tan(latitude) / (omega_c() + horizontal_rate()); }
  double beta0() const { return earth_rate * std::sin(latitude) / (omega_c() + horizontal_rate()); }
  // (13.12) λ = −δ/2 ± i ω^K; ω^K² = ω^E cosφ (ω^E cosφ + ω^c) − δ²/4 (≤ 0: aperiodic).
  double omega_K_squared() const {
    return horizontal_rate() * (horizontal_rate() + omega_c()) - 0.25 * delta() * delta();
  }
  double period() const { return 2.0 * 3.14159265358979323846 / std::sqrt(omega_K_squared()); }  // [s]
  double decay_rate() const { return 0.5 * delta(); }  // [1/s]
};

// (13.23) speed deviation: α0 = −Ω2/Ω3 = v^N / (R ω^E cosφ + v^E) (v^E = ship's east speed) [rad].
inline double speed_deviation(double v_north, double v_east, double latitude, double radius, double earth_rate) {
  return v_north / (radius * earth_rate * std::cos(latitude) + v_east);
}

// (13.26) Schuler tuning: ω^c = c/H = g / (R ω^E cosφ) [1/s].
inline double schuler_tuned_omega_c(double latitude, double gravity, double radius, double earth_rate) {
  return gravity / (radius * earth_rate * std::cos(latitude));
}

}  // namespace gyrostab::models
