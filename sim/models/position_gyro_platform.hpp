// Single-axis platform stabilized by a position (two-degree-of-freedom) gyro: the gyro's outer gimbal axis is
// the platform's axis 1; a pick-off measures the platform against the outer gimbal, δ − α, and an amplifier
// drives the platform's torquer M1^KP = −k(δ − α) (the firmware's law); the gyro's torquer on its inner axis 2,
// M2^K, slews the gyro frame and with it the platform.
//
// Book: Magnus §16.2.2, Fig. 16.2, (16.6)-(16.10) (docs/models/position-gyro-platform.md):
//   (16.6)  Θ δ'' + d1 (δ' − α') = M1^SP + M1^KP                 (platform; M1^KP = −k(δ − α))
//           A α'' + H β' + d1 (α' − δ') = 0                       (outer gimbal with the gyro, axis 1)
//           B β'' − H α' + d2 β' = M2^K                            (inner gimbal, axis 2)
//   (16.7)  steady, constant inputs: (δ − α)0 = M1^SP/k, α0' = δ0' = −M2^K/H, β0' = 0
//   (16.8)  λ² {ABΘ λ⁴ + (ABd1 + ΘAd2 + ΘBd1) λ³ + (ABk + Θd1d2 + Ad1d2 + H²Θ) λ²
//               + (Ad2k + H²d1) λ + H²k} = 0
//   (16.9)  Hurwitz D^II, D^III; unstable bands of k (firmware/control/position_gyro_platform_stability.hpp)
//   (16.10) H → ∞: λ²{Θλ² + d1λ + k} = 0 (the platform on a spring k about a fixed gyro frame)
// δ, α are absolute (inertial) angles about axis 1, β the inner gimbal's angle about axis 2.
//
// State x = [δ (rad), δ' (rad/s), α (rad), α' (rad/s), β (rad), β' (rad/s)] (named below).
// Parameters (SI): Θ platform inertia about axis 1 [kg m²]; A outer gimbal with inner gimbal and rotor about
// axis 1 [kg m²]; B inner gimbal with rotor about axis 2 [kg m²]; H spin momentum [N m s]; d1 viscous damping
// of the platform against the outer gimbal [N m s/rad]; d2 of the inner gimbal axis [N m s/rad]; bearing
// friction of the platform on its base d_b [N m s/rad].
// Inputs (held over the step): platform torquer M1^KP [N m], gyro torquer M2^K [N m], disturbance M1^SP [N m];
// the base's rate about axis 1, φ'(t) = a cos(ω_b t) [rad/s] (a function of time, not held).
// Base motion: the base turns about axis 1 at φ'(t); the bearing's viscous friction carries d_b φ' onto the
// platform. The platform's own rate in the friction, −d_b δ', is dropped: the stabilized platform's rate is
// small against the base's, and so the base's motion is the book's disturbance torque M1^SP(t) and (16.8)
// keeps its form. The torquer reacts on the base, not on the gyro.
// Assumptions: small β (the gyro's H stays along the same axis, cos β = 1); the rotor's spin held (H const);
// rigid gimbals; viscous damping only.
// The closed loop with an analog amplifier (the book's, for the linearisation, the oracles and the step
// check): PositionGyroPlatformAnalog below.
// Oracle: tests/oracle/position_gyro_platform_test.cpp — (16.7), (16.8) against the eigenvalues of the
// linearisation and the simulated decay, the band edges of (16.9) by the response's growth, (16.10), undamped,
// the base's roll through the bearing friction.
// Docs: docs/models/position-gyro-platform.md
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace gyrostab::models {

struct PositionGyroPlatformParams {
  double Theta{0.2};     // platform about axis 1 [kg m²]
  double A{0.02};        // outer gimbal + inner gimbal + rotor about axis 1 [kg m²]
  double B{0.016};       // inner gimbal + rotor about axis 2 [kg m²]
  double H{0.5};         // spin momentum [N m s]
  double d1{0.2};        // platform against the outer gimbal [N m s/rad]
  double d2{0.1};        // inner gimbal axis [N m s/rad]
  double d_base{0.0};    // bearing friction platform/base [N m s/rad]

  const char* invalid_reason() const {
    const auto fin = [](double v) { return std::isfinite(v); };
    if (!(fin(Theta) && Theta > 0.0 && fin(A) && A > 0.0 && fin(B) && B > 0.0)) return "Theta, A, B must be > 0";
    if (!(fin(H) && H > 0.0)) return "H must be > 0";
    if (!(fin(d1) && d1 >= 0.0 && fin(d2) && d2 >= 0.0 && fin(d_base) && d_base >= 0.0))
      return "d1, d2, d_base must be >= 0";
    return nullptr;
  }
};

class PositionGyroPlatform {
 public:
  static constexpr int kStateSize = 6;
  using State = Eigen::Matrix<double, 6, 1>;
  static constexpr int kDelta = 0, kDeltaRate = 1, kAlpha = 2, kAlphaRate = 3, kBeta = 4, kBetaRate = 5;

  struct Inputs {
    double platform_torque{0.0};  // M1^KP [N m]
    double gyro_torque{0.0};      // M2^K [N m]
    double disturbance{0.0};      // M1^SP [N m]
    double base_rate_amplitude{0.0};  // the base's rate φ'(t) = a cos(ω_b t): a [rad/s]
    double base_omega{0.0};           // ω_b [rad/s]
  };

  explicit PositionGyroPlatform(const PositionGyroPlatformParams& p = {}) : p_(p) {}

  Inputs inputs{};

  const PositionGyroPlatformParams& params() const { return p_; }

  double base_rate(double t) const { return inputs.base_rate_amplitude * std::cos(inputs.base_omega * t); }
  // The torque on the platform besides its torquer and the gyro's damper at t: M1^SP with the base's friction.
  double platform_disturbance(double t) const { return inputs.disturbance + p_.d_base * base_rate(t); }

  void derivative(double t, const State& x, State& dx) const { rates(t, x, inputs.platform_torque, dx); }
  void project(State&) const {}

  // (16.6) with platform torquer M1 [N m].
  void rates(double t, const State& x, double M1, State& dx) const {
    const double rel = x[kDeltaRate] - x[kAlphaRate];  // δ' − α'
    dx[kDelta] = x[kDeltaRate];
    dx[kDeltaRate] = (platform_disturbance(t) + M1 - p_.d1 * rel) / p_.Theta;
    dx[kAlpha] = x[kAlphaRate];
    dx[kAlphaRate] = (-p_.H * x[kBetaRate] + p_.d1 * rel) / p_.A;
    dx[kBeta] = x[kBetaRate];
    dx[kBetaRate] = (p_.H * x[kAlphaRate] - p_.d2 * x[kBetaRate] + inputs.gyro_torque) / p_.B;
  }

  static double pickoff(const State& x) { return x[kDelta] - x[kAlpha]; }

 private:
  PositionGyroPlatformParams p_;
};

// The loop closed by the book's analog amplifier, M1^KP = −k(δ − α) continuously.
class PositionGyroPlatformAnalog {
 public:
  static constexpr int kStateSize = 6;
  using State = PositionGyroPlatform::State;

  PositionGyroPlatformAnalog(const PositionGyroPlatformParams& p, double k) : plant(p), k_(k) {}

  PositionGyroPlatform plant;

  void derivative(double t, const State& x, State& dx) const {
    plant.rates(t, x, -k_ * PositionGyroPlatform::pickoff(x), dx);
  }
  void project(State&) const {}
  double gain() const { return k_; }

 private:
  double k_;
};

}  // namespace gyrostab::models
