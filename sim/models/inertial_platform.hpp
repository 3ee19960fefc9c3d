// Gyro-stabilized inertial platforms with accelerometers: the single-axis platform of Magnus Fig. 16.1/16.9
// and a three-axis local-level platform held by three rate-integrating gyros (Fig. 16.4), each gyro's pick-off
// driving its axis's stabilization motor (the analog servo, part of this plant), commanded through the gyros'
// torquers by the Schuler loop of the firmware (firmware/control/schuler_loop.hpp). The three-axis platform on
// two two-degree-of-freedom gyros (Fig. 16.5) is sim/models/inertial_platform_position_gyros.hpp.
//
// Book: Magnus ch. 16 (docs/models/inertial-platform.md): single-axis platform with an I-gyro (16.1)-(16.5);
// three integrating gyros with their cross-coupling (16.11)-(16.18); Schuler tuning (16.27)-(16.50).
// One axis (absolute platform rate ω_P about it, gyro output angle β):
//   (16.40)  J ω_P' + H β' = −k β + M^S + M^G                      (platform + stabilization servo)
//            B β'' + d β' + c β = H ω_P + M^K − H ε               (gyro output axis; torquer M^K)
//   steady (16.2), c = 0: β0 = M^S/k and ω_P = ε − M^K/H, so a torquer command M^K = −H ω_cmd turns the
//   platform at ω_cmd (the book's α0' = −M2^K/H) plus the gyro drift ε [rad/s] (16.49).
//   Servo stability (characteristic J B λ³ + J d λ² + (J c + H²) λ + H k, Hurwitz):
//            k < d (J c + H²)/(B H)         (c = 0: (16.5) k < H d/B)
//   M^G = (3g/R)(B_p − C_p) e: gravity-gradient torque (16.30) on the single-axis platform (e = α − ϑ,
//   below), given as its coefficient; the servo loop treats it as a disturbance ((16.38): period unchanged).
// Three axes, coupled (16.11)-(16.13): gyro i has its input axis along platform axis i; gyros 1 (X) and 2 (Y)
// have their output axes along platform axis 3, gyro 3 (Z) along axis 1 (the X and Z rotors spin along axis 2,
// the Y rotor along axis 1). Every β_i is counted so that its steady output is +(H/d) × the rate about its
// input axis (the book's β^X = −β_1, β^Y = β_2, β^Z = β_3) and every servo is M_i = −k β_i (the book's
// M^K = (k β^X, −k β^Y, −k β^Z)). With T_i = M^K_i − d β_i' − c β_i − H ε_i, the torque between gyro i's float
// and its case:
//            J_1 ω_1' = −H_1 β_1' − k_1 β_1 + M^S_1 + H_1 ω_3 − T_3
//            J_2 ω_2' = −H_2 β_2' − k_2 β_2 + M^S_2 − H_2 ω_3
//            J_3 ω_3' = −H_3 β_3' − k_3 β_3 + M^S_3 − H_3 ω_1 + T_1 − T_2
//            B_1 β_1'' = H_1 ω_1 + T_1 + B_1 ω_3',   B_2 β_2'' = H_2 ω_2 + T_2 − B_2 ω_3',
//            B_3 β_3'' = H_3 ω_3 + T_3 − B_3 ω_1'
//   (H ω_3, H ω_1: a rotor turned about the axis that is neither its spin nor its output axis pushes on the
//   platform; T: the float's damper — and its torquer, beyond the book — reacts on the platform about the output
//   axis; B ω': the platform's angular acceleration about a gyro's output axis drags its float.) With
//   d = c = M^K = ε = 0 these are the book's (16.11)-(16.12) term by term. `coupling = decoupled` drops every
//   term after the first three of each line: three independent servos of the single-axis form, the book's
//   large-H/d limit. The cross terms are of relative size 2d/H in the quasi-static reduction (16.18): 4 % at
//   the default H/d = 50.
// Reference frame and the platform's error: e = platform attitude relative to a level frame that turns with
// the vehicle (small angles), e' = ω_P − Ω − Ω × e, Ω = the level frame's absolute rate.
//   Single axis: the book's great-circle case (16.4.1), Ω = ϑ' = v/R, e = α − ϑ; the vehicle generator's track
//   trihedron T (T2 = the platform axis, left) gives Ω = ω_IT_T2 and the specific force (f_T1 along track,
//   f_T3 up). Accelerometer along the track (exact in e):  b^M = f_T1 cos e − f_T3 sin e (+ bias)
//   ≈ v' − g(α − ϑ)  (16.27).
//   Three axes: the azimuth-free trihedron F of the vehicle generator (F3 up, ω_IF_F = (p0, q0, 0): no
//   absolute rotation about the vertical — the "semi-analytic platform with zero rate about the vertical"
//   of §16.1 and Chelnokov's r0 = 0). In F, the horizontal specific force is the derivative of the absolute
//   velocity's F components and Ω = (−v2/R, v1/R, 0): the Schuler loop needs no Coriolis terms. Per axis
//   the servo above; accelerometers along platform axes 1, 2 (small angles):
//            b = f − e × f:   b1 = f1 − g e2 + e3 f2,   b2 = f2 + g e1 − e3 f1    (f3 ≈ g)
// Apparent tilt (what the Schuler loop reads, theta1_rad, theta2_rad, the field's scale g0 = 9.80665):
//   single axis and three-axis axis 2:  θ = −b_along/g0;   three-axis axis 1: θ1 = b2/g0
// so that θ_i = e_i at rest and the loop is the same on every channel: ω_cmd,i' = −(g0/R) θ_i (16.36).
// Tuned, e obeys (16.37) e'' + (g/R) e = 0 for ANY vehicle motion: period 2π sqrt(R/g) = 84.4 min (16.38).
//
// State, single axis: x = [e (rad), ω_P (rad/s), β (rad), β' (rad/s)].
// State, three axes: x = [e1 e2 e3 (rad), ω_P1..3 (rad/s), β1..3 (rad), β'1..3 (rad/s)].
// Parameters (SI) per axis: J [kg m²], k [N m/rad], gyro H [N m s], B [kg m²], d [N m s/rad], c [N m/rad],
// disturbance M^S [N m], drift ε [rad/s], accelerometer bias [m/s²]; single axis also the gravity-gradient
// coefficient (3g/R)(B_p − C_p) [N m/rad]; three axes the coupling (full | decoupled).
// Inputs: FrameInputs (Ω, f over the step, in T resp. F axes), torquer commands M^K per axis [N m] (held).
// Assumptions: small e and β; the platform's rates in the gyro equations are its absolute rates in platform
// axes (no kinematic gimbal error, §16.1 gimbal order); the gyros' output-axis inertia B is the whole float's
// (the book's, about the output axis only).
// Oracles: tests/oracle/inertial_platform_test.cpp — servo offsets (16.2), stability bound (16.5), Schuler
// period (16.38)/(16.44), error curves for an initial tilt (16.46)-(16.47) and a gyro drift (16.49)-(16.50),
// level under vehicle acceleration when tuned (16.34), untuned growth (16.48);
// tests/oracle/inertial_platform_coupling_test.cpp — the coupled offsets (16.15)/(16.17), the full pencil
// (16.14) against the reduced form (16.18), the size of the coupling, the coupled stability check.
// Docs: docs/models/inertial-platform.md
#pragma once

#include <cmath>

#include "sim/models/gyro_in_rotating_frame.hpp"

namespace gyrostab::models {

inline constexpr double kStandardGravity = 9.80665;  // g0, the scale of the apparent-tilt signal [m/s²]

struct PlatformAxisParams {
  // Defaults: servo mode ≈ 8 Hz (book: platform frames 5-20 Hz), aperiodic root −k/H = −6 /s (16.44),
  // k = 0.3 k_max.
  double J{0.02};          // platform + gimbal inertia about the axis [kg m²]
  double k{0.3};           // stabilization servo gain, M = −k β [N m/rad]
  double H{0.05};          // gyro spin momentum [N m s]
  double B{5e-5};          // gyro output-axis inertia [kg m²]
  double d{1e-3};          // gyro output-axis damping [N m s/rad] (H/d = 50: book 20-80)
  double c{0.0};           // gyro output-axis spring [N m/rad]
  double disturbance{0.0};  // M^S on the platform [N m]
  double drift{0.0};       // gyro drift ε [rad/s]
  double accel_bias{0.0};  // bias of the accelerometer that senses tilt about this axis [m/s²]

  // Largest stable servo gain: k < d (J c + H²)/(B H) (Hurwitz of the cubic above; (16.5) for c = 0).
  double k_max() const { return d * (J * c + H * H) / (B * H); }

  // Usable numbers (the three-axis platforms check their stability as a whole: inertial_platform_stability.hpp).
  const char* invalid_parameters() const {
    const auto fin = [](double v) { return std::isfinite(v); };
    if (!(fin(J) && J > 0.0 && fin(B) && B > 0.0 && fin(H) && H > 0.0)) return "J, B, H must be finite and > 0";
    if (!(fin(k) && k > 0.0)) return "servo gain k must be finite and > 0";
    if (!(fin(d) && d > 0.0 && fin(c) && c >= 0.0)) return "gyro damping d must be > 0 and c >= 0";
    if (!(fin(disturbance) && fin(drift) && fin(accel_bias))) return "disturbance, drift, bias must be finite";
    return nullptr;
  }
  // Usable numbers and a stable single-axis servo.
  const char* invalid_reason() const {
    if (const char* why = invalid_parameters()) return why;
    if (!(k < k_max())) return "servo gain k beyond the stability bound k < d (J c + H^2)/(B H) (16.5)";
    return nullptr;
  }
};

namespace detail {
// (J ω_P', β'') of one axis.
inline void platform_axis(const PlatformAxisParams& p, double omega_P, double beta, double beta_rate,
                          double torquer, double extra_torque, double& domega_P, double& dbeta_rate) {
  domega_P = (-p.H * beta_rate - p.k * beta + p.disturbance + extra_torque) / p.J;
  dbeta_rate = (p.H * omega_P - p.d * beta_rate - p.c * beta + torquer - p.H * p.drift) / p.B;
}

// The level accelerometers of a three-axis platform at tilt e in the specific force f (F axes) [m/s²].
inline void level_accelerometers(const PlatformAxisParams (&axis)[3], const dynamics::Vec3& f,
                                 const dynamics::Vec3& e, double& b1, double& b2) {
  const dynamics::Vec3 b = f - e.cross(f);
  b1 = b.x() + axis[1].accel_bias;  // senses tilt about axis 2
  b2 = b.y() + axis[0].accel_bias;  // senses tilt about axis 1
}
}  // namespace detail

struct SingleAxisPlatformParams {
  PlatformAxisParams axis{};
  double gravity_gradient{0.0};  // (3g/R)(B_p − C_p) of (16.30) [N m/rad]
};

class SingleAxisPlatform {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  // The state's components, by name.
  static constexpr int kTilt = 0, kPlatformRate = 1, kGyroAngle = 2, kGyroRate = 3;

  struct Inputs {
    FrameInputs frame{};  // track trihedron T: Ω_T2 = ϑ', f_T1 along track, f_T3 up
    double torquer{0.0};  // M^K [N m]
  };

  explicit SingleAxisPlatform(const SingleAxisPlatformParams& p = {}) : p_(p) {}

  Inputs inputs{};

  const SingleAxisPlatformParams& params() const { return p_; }

  void derivative(double t, const State& x, State& dx) const {
    const FrameSample w = inputs.frame.at(t);
    dx[0] = x[1] - w.Omega.y();
    dx[2] = x[3];
    detail::platform_axis(p_.axis, x[1], x[2], x[3], inputs.torquer, p_.gravity_gradient * x[0], dx[1], dx[3]);
  }
  void project(State&) const {}

  // b^M [m/s²] and the apparent tilt θ = −b^M/g0 [rad] at time t.
  double specific_force_along(double t, const State& x) const {
    const dynamics::Vec3 f = inputs.frame.at(t).f;
    return f.x() * std::cos(x[0]) - f.z() * std::sin(x[0]) + p_.axis.accel_bias;
  }
  double apparent_tilt(double t, const State& x) const {
    return -specific_force_along(t, x) / kStandardGravity;
  }

 private:
  SingleAxisPlatformParams p_;
};

// full: (16.11)-(16.13) with every cross term; decoupled: three single-axis servos (the large-H/d limit).
enum class PlatformCoupling : int { kFull = 0, kDecoupled = 1 };

struct ThreeAxisPlatformParams {
  PlatformAxisParams axis[3]{};  // platform axes 1, 2 (level), 3 (up)
  PlatformCoupling coupling{PlatformCoupling::kFull};
};

class ThreeAxisPlatform {
 public:
  static constexpr int kStateSize = 12;
  using State = Eigen::Matrix<double, 12, 1>;
  // The state's components, by name: the first of three (axes 1, 2, 3).
  static constexpr int kTilt = 0, kPlatformRate = 3, kGyroAngle = 6, kGyroRate = 9;

  struct Inputs {
    FrameInputs frame{};          // azimuth-free trihedron F: Ω = (p0, q0, 0), f
    double torquer[3]{0.0, 0.0, 0.0};  // M^K per gyro [N m]
  };

  explicit ThreeAxisPlatform(const ThreeAxisPlatformParams& p = {}) : p_(p) {}

  Inputs inputs{};

  const ThreeAxisPlatformParams& params() const { return p_; }

  void derivative(double t, const State& x, State& dx) const {
    const FrameSample w = inputs.frame.at(t);
    const dynamics::Vec3 e = x.segment<3>(0);
    const dynamics::Vec3 wP = x.segment<3>(3);
    dx.segment<3>(0) = wP - w.Omega - w.Omega.cross(e);
    if (p_.coupling == PlatformCoupling::kDecoupled) {
      for (int i = 0; i < 3; ++i) {
        dx[6 + i] = x[9 + i];
        detail::platform_axis(p_.axis[i], x[3 + i], x[6 + i], x[9 + i], inputs.torquer[i], 0.0, dx[3 + i],
                              dx[9 + i]);
      }
      return;
    }
    const PlatformAxisParams* a = p_.axis;
    double T[3], P[3];
    for (int i = 0; i < 3; ++i) {
      dx[6 + i] = x[9 + i];
      T[i] = inputs.torquer[i] - a[i].d * x[9 + i] - a[i].c * x[6 + i] - a[i].H * a[i].drift;
      P[i] = -a[i].H * x[9 + i] - a[i].k * x[6 + i] + a[i].disturbance;
    }
    // The platform's accelerations need only the floats' rates: explicit, then the floats.
    dx[3] = (P[0] + a[0].H * wP[2] - T[2]) / a[0].J;
    dx[4] = (P[1] - a[1].H * wP[2]) / a[1].J;
    dx[5] = (P[2] - a[2].H * wP[0] + T[0] - T[1]) / a[2].J;
    dx[9] = (a[0].H * wP[0] + T[0]) / a[0].B + dx[5];
    dx[10] = (a[1].H * wP[1] + T[1]) / a[1].B - dx[5];
    dx[11] = (a[2].H * wP[2] + T[2]) / a[2].B - dx[3];
  }
  void project(State&) const {}

  // The gyro angles at which the platform rests (ω' = 0, β' = 0) while it turns at the absolute rate ω with
  // the torquer commands M^K [rad].
  dynamics::Vec3 resting_gyro_angles(const dynamics::Vec3& omega, const double (&torquer)[3]) const {
    const PlatformAxisParams* a = p_.axis;
    dynamics::Vec3 b;
    for (int i = 0; i < 3; ++i) b[i] = a[i].disturbance / a[i].k;
    if (p_.coupling == PlatformCoupling::kDecoupled) return b;
    double T0[3];  // the float torques without the springs
    for (int i = 0; i < 3; ++i) T0[i] = torquer[i] - a[i].H * a[i].drift;
    b[1] = (a[1].disturbance - a[1].H * omega[2]) / a[1].k;
    // k1 β1 − c3 β3 = r1,  c1 β1 + k3 β3 = r3
    const double r1 = a[0].disturbance + a[0].H * omega[2] - T0[2];
    const double r3 = a[2].disturbance - a[2].H * omega[0] + T0[0] - T0[1] + a[1].c * b[1];
    const double det = a[0].k * a[2].k + a[0].c * a[2].c;
    b[0] = (r1 * a[2].k + a[2].c * r3) / det;
    b[2] = (a[0].k * r3 - a[0].c * r1) / det;
    return b;
  }

  // Accelerometer outputs b1, b2 along platform axes 1, 2 [m/s²].
  void accelerometers(double t, const State& x, double& b1, double& b2) const {
    detail::level_accelerometers(p_.axis, inputs.frame.at(t).f, x.segment<3>(0), b1, b2);
  }
  // Apparent tilts θ1 = b2/g0, θ2 = −b1/g0 [rad].
  void apparent_tilts(double t, const State& x, double& theta1, double& theta2) const {
    double b1, b2;
    accelerometers(t, x, b1, b2);
    theta1 = b2 / kStandardGravity;
    theta2 = -b1 / kStandardGravity;
  }

 private:
  ThreeAxisPlatformParams p_;
};

}  // namespace gyrostab::models
