// A gyro whose rotor axis is held near axis 3 of a reference frame that rotates in inertial space — the
// master equation of Magnus ch. 12, 13, 15 (§10.2; docs/models/gyro-vertical.md#the-master-equation-102),
// shared by the gyro vertical (sim/models/gyro_vertical.hpp), the gyrocompass (sim/models/gyrocompass.hpp)
// and the single-degree-of-freedom gyros (sim/sensors/rate_integrating_gyro.hpp). The devices differ only
// in the frame and in the torques.
//
//   (10.21)  H_i = [A(α' + Ω1) + Hβ,  B(β' + Ω2) − Hα,  H]
//   (10.22)  A α'' + H β' + H Ω3 α = M1 − A Ω1' − H Ω2
//            B β'' − H α' + H Ω3 β = M2 − B Ω2' + H Ω1
// α, β: small rotations of the rotor axis about frame axes 1 and 2 (the rotor axis is ≈ (β, −α, 1) in frame
// axes); Ω = (Ω1, Ω2, Ω3): absolute angular velocity of the frame in its own axes; M1, M2: torques about the
// gimbal axes 1, 2 (every torque of the device: pendulum, friction, torquers).
// Precession ("technical") form, A = B = 0 (the book's reduced theory, nutation dropped):
//   H β' = M1 − H Ω2 − H Ω3 α,      −H α' = M2 + H Ω1 − H Ω3 β
// When the torques contain viscous terms −d1 α', −d2 β', the rates solve
//   [d1  H; −H  d2] [α'; β'] = [R1; R2],   R1 = M1* − HΩ2 − HΩ3α,  R2 = M2* + HΩ1 − HΩ3β
// (M* = the rate-independent part of the torques): α' = (d2 R1 − H R2)/Δ, β' = (H R1 + d1 R2)/Δ, Δ = H² + d1 d2.
// Assumptions (book): symmetric rotor, constant spin (H fixed), small α, β, AΩ3 and BΩ3 << H (the terms
// (H − Bω^E cosφ) of (13.7) are taken as H).
// Units: A, B [kg m²], H [N m s], Ω [rad/s], Ω' [rad/s²], M [N m], angles [rad].
// Frame inputs vary within a tick: FrameInputs holds the frame's motion at the start and end of the current
// step and interpolates linearly, so an RK4 stage at t sees the frame at t to O(h²) from one motion sample
// per step (the motion generators cost more than the model).
// Oracles: through the devices (tests/oracle/gyro_vertical_test.cpp, gyrocompass_test.cpp,
// rate_integrating_gyro_test.cpp).
// Docs: docs/models/gyro-vertical.md#the-master-equation-102
#pragma once

#include <cmath>
#include <type_traits>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

// The reference frame's motion at one instant, in the frame's own axes.
struct FrameSample {
  dynamics::Vec3 Omega{dynamics::Vec3::Zero()};      // absolute angular velocity Ω [rad/s]
  dynamics::Vec3 Omega_dot{dynamics::Vec3::Zero()};  // d/dt of the components of Ω [rad/s²]
  dynamics::Vec3 f{dynamics::Vec3::Zero()};          // specific force at the pivot (a_abs − g_grav) [m/s²]
};

// The frame's motion over one step [t0, t0 + h]: linear between the samples at both ends.
struct FrameInputs {
  double t0{0.0};  // [s]
  double h{0.0};   // [s]; 0: hold s0
  FrameSample s0{}, s1{};

  void hold(const FrameSample& s) {
    s0 = s;
    s1 = s;
    h = 0.0;
  }
  FrameSample at(double t) const {
    if (!(h > 0.0)) return s0;
    const double w = (t - t0) / h;
    FrameSample s;
    s.Omega = s0.Omega + w * (s1.Omega - s0.Omega);
    s.Omega_dot = s0.Omega_dot + w * (s1.Omega_dot - s0.Omega_dot);
    s.f = s0.f + w * (s1.f - s0.f);
    return s;
  }
};

struct GyroFrameParams {
  double A{1e-3};  // inertia about gimbal axis 1 (rotor + gimbals) [kg m²]
  double B{1e-3};  // inertia about gimbal axis 2 [kg m²]
  double H{0.5};   // spin angular momentum along axis 3 [N m s]
};

// (10.22): the gimbal accelerations (α'', β'') for the torques M1, M2 [N m]. O(1).
inline void gyro_frame_accelerations(const GyroFrameParams& p, const FrameSample& w, double alpha, double beta,
                                     double alpha_rate, double beta_rate, double M1, double M2,
                                     double& alpha_acc, double& beta_acc) {
  const double H = p.H;
  alpha_acc = (M1 - p.A * w.Omega_dot.x() - H * w.Omega.y() - H * beta_rate - H * w.Omega.z() * alpha) / p.A;
  beta_acc = (M2 - p.B * w.Omega_dot.y() + H * w.Omega.x() + H * alpha_rate - H * w.Omega.z() * beta) / p.B;
}

// Precession form of (10.22) with viscous terms d1, d2 [N m s/rad] inside the torques; M1s, M2s = the
// rate-independent torques [N m]. Sets (α', β'). O(1).
inline void gyro_frame_precession_rates(const GyroFrameParams& p, const FrameSample& w, double alpha,
                                        double beta, double M1s, double M2s, double d1, double d2,
                                        double& alpha_rate, double& beta_rate) {
  const double H = p.H;
  const double R1 = M1s - H * w.Omega.y() - H * w.Omega.z() * alpha;
  const double R2 = M2s + H * w.Omega.x() - H * w.Omega.z() * beta;
  const double det = H * H + d1 * d2;
  alpha_rate = (d2 * R1 - H * R2) / det;
  beta_rate = (H * R1 + d1 * R2) / det;
}

// Nutation frequency H/sqrt(AB) of (10.17) [rad/s] (the fastest mode of the full form).
inline double nutation_frequency(const GyroFrameParams& p) {
  return p.H / std::sqrt(p.A * p.B);
}

enum class InstrumentFidelity {
  kFull,        // (10.22) with nutation
  kPrecession,  // A = B = 0
};

// The parameter checks every instrument on (10.22) shares (c: its pendulous moment, d1, d2: its viscous
// torques): nullptr if usable, else why not (scene validation).
inline const char* gyro_frame_invalid_reason(const GyroFrameParams& gyro, InstrumentFidelity fidelity, double c,
                                             double d1, double d2) {
  const auto fin = [](double v) { return std::isfinite(v); };
  if (!(fin(gyro.H) && gyro.H > 0.0)) return "H must be finite and > 0";
  if (fidelity == InstrumentFidelity::kFull && !(fin(gyro.A) && gyro.A > 0.0 && fin(gyro.B) && gyro.B > 0.0))
    return "A, B must be finite and > 0 for the full form";
  if (!(fin(c) && c >= 0.0)) return "c (pendulous moment) must be finite and >= 0";
  if (!(fin(d1) && d1 >= 0.0 && fin(d2) && d2 >= 0.0)) return "d1, d2 must be finite and >= 0";
  return nullptr;
}

// No rate-dependent torque besides the viscous rows.
struct NoGimbalFriction {};

// Entries 0-3 of dx for a state x = [α, β, α', β', ...] by (10.22), with the torques split as the devices'
// tables are: M1s, M2s rate-independent [N m]; viscous −d1 α', −d2 β'; and `friction(α', β', F1, F2)`, any
// other rate-dependent torque (subtracted, full form only: the precession form solves the viscous rows
// exactly and cannot resolve the rest). Precession form: (α', β') from gyro_frame_precession_rates and
// dx[2] = dx[3] = 0 (x[2], x[3] unused). O(1).
template <class State, class Friction = NoGimbalFriction>
inline void gyro_frame_derivative(const GyroFrameParams& p, InstrumentFidelity fidelity, const FrameSample& w,
                                  const State& x, double M1s, double M2s, double d1, double d2, State& dx,
                                  const Friction& friction = {}) {
  if (fidelity == InstrumentFidelity::kPrecession) {
    gyro_frame_precession_rates(p, w, x[0], x[1], M1s, M2s, d1, d2, dx[0], dx[1]);
    dx[2] = 0.0;
    dx[3] = 0.0;
    return;
  }
  double M1 = M1s - d1 * x[2];
  double M2 = M2s - d2 * x[3];
  if constexpr (!std::is_same_v<Friction, NoGimbalFriction>) {
    double F1, F2;
    friction(x[2], x[3], F1, F2);
    M1 -= F1;
    M2 -= F2;
  }
  dx[0] = x[2];
  dx[1] = x[3];
  gyro_frame_accelerations(p, w, x[0], x[1], x[2], x[3], M1, M2, dx[2], dx[3]);
}

// (α', β') at time t [rad/s]: the state's (full form) or the precession solution's (from the model's
// derivative). Model: State, derivative(t, x, dx) with the layout of gyro_frame_derivative.
template <class Model>
inline void gyro_frame_rates(const Model& m, InstrumentFidelity fidelity, double t, const typename Model::State& x,
                             double& alpha_rate, double& beta_rate) {
  if (fidelity == InstrumentFidelity::kFull) {
    alpha_rate = x[2];
    beta_rate = x[3];
    return;
  }
  typename Model::State dx;
  m.derivative(t, x, dx);
  alpha_rate = dx[0];
  beta_rate = dx[1];
}

}  // namespace gyrostab::models
