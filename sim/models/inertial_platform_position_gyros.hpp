// Three-axis local-level platform held by two two-degree-of-freedom (position) gyros, Magnus §16.3, Fig. 16.5,
// (16.19)-(16.26): gyro X spins along platform axis 1 and measures the platform's rotations about axes 2 and 3,
// gyro Y spins along axis 2 and measures axes 1 and 3; their pick-offs drive the stabilization motors (analog
// servos, part of this plant); the firmware's Schuler loop (firmware/control/schuler_loop.hpp) commands the
// level channels through the gyros' torquers. The platform, its level frame, accelerometers and apparent tilts
// are those of the three-axis platform of sim/models/inertial_platform.hpp.
//
// Gimbal angles relative to the platform: gyro X outer α^X about axis 3, inner β^X about axis 2; gyro Y outer
// α^Y about axis 1, inner β^Y about axis 3. Gyro outer-axis inertia A, inner B, damping d (both axes), spring c.
// With ω the platform's absolute rate (the book's α', β', γ') and T the torque between a gimbal and the case
// (damper −d·rate, spring −c·angle, torquer, drift):
//   (16.19)  A(α^X'' + ω_3') − H(β^X' + ω_2) = T_αX,     B(β^X'' + ω_2') + H(α^X' + ω_3) = T_βX
//            A(α^Y'' + ω_1') − H(β^Y' + ω_3) = T_αY,     B(β^Y'' + ω_3') + H(α^Y' + ω_1) = T_βY
//   (16.20)  J_1 ω_1' = M^K_1 + M^S_1 − T_αY,  J_2 ω_2' = M^K_2 + M^S_2 − T_βX,  J_3 ω_3' = M^K_3 + M^S_3 − T_αX − T_βY
//   (16.21)  M^K_1 = k_1 α^Y,  M^K_2 = k_2 β^X,  M^K_3 = k_3 (α^X + β^Y)/2      (γ measured twice → averaged)
// (the reactions −T: the book's dampers, and here also the torquers and the spring). No gyroscopic term reaches the
// platform: the coupling is through the dampers and the loops, of relative size d/H (16.26).
// Torquers: the channel commands of the Schuler loop M_1, M_2 (M = −H ω_cmd, the same law as for the
// integrating gyros) are wired so that each rotor precesses at the commanded rate about the axis it holds:
//   T_βY ∋ −M_1 + H ε_1   (rotor Y turns about axis 1 at (T_βY)/H = ω_cmd,1 + ε_1)
//   T_αX ∋ M_2 − H ε_2    (rotor X turns about axis 2 at −T_αX/H = ω_cmd,2 + ε_2)
//   T_βX ∋ H ε_3, T_αY ∋ −H ε_3 (both rotors drift about the vertical at ε_3).
// Steady (16.22): α^Y = −M^S_1/k, β^X = −M^S_2/k, α^X + β^Y = −2 M^S_3/k; rates at constant platform rate
// (16.23), e.g. α^X' = (H d ω_2 − H² ω_3)/(H² + d²); platform offsets (16.25) ≈ M^S/k + O(d/H).
// Frames oscillate about the gyros at sqrt(k/J) (book: 5-20 Hz), damped by d only: ζ = d/(2 sqrt(kJ)) (16.26).
//
// State: x = [e1 e2 e3 (rad), ω_1..3 (rad/s), α^X β^X α^Y β^Y (rad), their rates (rad/s)].
// Parameters (SI): the three axes' PlatformAxisParams: J, k, disturbance M^S per platform axis; gyro Y (channel
// 1) takes H, B (= its A), d, c and the drift ε_1 of axis 1, gyro X (channel 2) those of axis 2; axis 3
// gives only its drift ε_3 (about the vertical, both rotors) — its H, B, d, c are unused; the accelerometer
// biases of axes 1, 2. Inputs: FrameInputs (F axes), torquer commands of channels 1, 2 [N m] (held).
// Assumptions: small angles; A = B per gyro; the platform's rates in the gyro equations are absolute rates in
// platform axes.
// Oracle: tests/oracle/inertial_platform_coupling_test.cpp — steady offsets (16.22), platform offsets (16.25),
// quasi-static gimbal rates (16.23), the 11th-order pencil, the stability check; the Schuler loop in the scene
// sim/scenes/inertial-platform-two-position-gyros.toml.
// Docs: docs/models/inertial-platform.md#two-position-gyros
#pragma once

#include "sim/models/inertial_platform.hpp"

namespace gyrostab::models {

struct TwoPositionGyroPlatformParams {
  PlatformAxisParams axis[3]{};  // platform axes 1, 2 (level), 3 (up); gyro Y from axis 1, gyro X from axis 2
};

class TwoPositionGyroPlatform {
 public:
  static constexpr int kStateSize = 14;
  using State = Eigen::Matrix<double, 14, 1>;
  // The state's components, by name: tilt and platform rate the first of three; the gimbal angles α^X, β^X,
  // α^Y, β^Y and their rates.
  static constexpr int kTilt = 0, kPlatformRate = 3, kAlphaX = 6, kBetaX = 7, kAlphaY = 8, kBetaY = 9,
                       kGimbalRate = 10;

  struct Inputs {
    FrameInputs frame{};               // azimuth-free trihedron F: Ω = (p0, q0, 0), f
    double torquer[3]{0.0, 0.0, 0.0};  // channel commands M_1, M_2 [N m]; [2] unused
  };

  explicit TwoPositionGyroPlatform(const TwoPositionGyroPlatformParams& p = {}) : p_(p) {}

  Inputs inputs{};

  const TwoPositionGyroPlatformParams& params() const { return p_; }

  void derivative(double t, const State& x, State& dx) const {
    const FrameSample w = inputs.frame.at(t);
    const dynamics::Vec3 e = x.segment<3>(kTilt);
    const dynamics::Vec3 wP = x.segment<3>(kPlatformRate);
    dx.segment<3>(kTilt) = wP - w.Omega - w.Omega.cross(e);
    dx.segment<4>(kAlphaX) = x.segment<4>(kGimbalRate);
    double T[4];
    gimbal_torques(x, T);
    const PlatformAxisParams* a = p_.axis;
    const PlatformAxisParams &gX = a[1], &gY = a[0];
    dx[3] = (a[0].k * x[kAlphaY] + a[0].disturbance - T[2]) / a[0].J;
    dx[4] = (a[1].k * x[kBetaX] + a[1].disturbance - T[1]) / a[1].J;
    dx[5] = (0.5 * a[2].k * (x[kAlphaX] + x[kBetaY]) + a[2].disturbance - T[0] - T[3]) / a[2].J;
    const double* r = &x[kGimbalRate];  // α^X', β^X', α^Y', β^Y'
    dx[10] = (T[0] + gX.H * (r[1] + wP[1])) / gX.B - dx[5];
    dx[11] = (T[1] - gX.H * (r[0] + wP[2])) / gX.B - dx[4];
    dx[12] = (T[2] + gY.H * (r[3] + wP[2])) / gY.B - dx[3];
    dx[13] = (T[3] - gY.H * (r[2] + wP[0])) / gY.B - dx[5];
  }
  void project(State&) const {}

  // The gimbal angles α^X, β^X, α^Y, β^Y at which the platform rests (ω' = 0, gimbal rates 0) with the
  // channel torquer commands M_1, M_2 [rad]; the azimuth is read twice, the two readings are set equal.
  Eigen::Matrix<double, 4, 1> resting_gimbal_angles(const double (&torquer)[3]) const {
    const PlatformAxisParams* a = p_.axis;
    const PlatformAxisParams &gX = a[1], &gY = a[0];
    Eigen::Matrix<double, 4, 1> g;
    const double e3 = a[2].drift;
    g[1] = (gX.H * e3 - a[1].disturbance) / (a[1].k + gX.c);
    g[2] = -(a[0].disturbance + gY.H * e3) / (a[0].k + gY.c);
    const double T0_aX = torquer[1] - gX.H * a[1].drift, T0_bY = -torquer[0] + gY.H * a[0].drift;
    g[0] = g[3] = (T0_aX + T0_bY - a[2].disturbance) / (a[2].k + gX.c + gY.c);
    return g;
  }

  // Accelerometer outputs b1, b2 along platform axes 1, 2 [m/s²]; apparent tilts θ1 = b2/g0, θ2 = −b1/g0 [rad].
  void accelerometers(double t, const State& x, double& b1, double& b2) const {
    detail::level_accelerometers(p_.axis, inputs.frame.at(t).f, x.segment<3>(kTilt), b1, b2);
  }
  void apparent_tilts(double t, const State& x, double& theta1, double& theta2) const {
    double b1, b2;
    accelerometers(t, x, b1, b2);
    theta1 = b2 / kStandardGravity;
    theta2 = -b1 / kStandardGravity;
  }

 private:
  // T_αX, T_βX, T_αY, T_βY: the torques of the case on the gimbals [N m].
  void gimbal_torques(const State& x, double (&T)[4]) const {
    const PlatformAxisParams* a = p_.axis;
    const PlatformAxisParams &gX = a[1], &gY = a[0];
    const double e3 = a[2].drift;
    T[0] = inputs.torquer[1] - gX.H * a[1].drift - gX.d * x[10] - gX.c * x[kAlphaX];
    T[1] = gX.H * e3 - gX.d * x[11] - gX.c * x[kBetaX];
    T[2] = -gY.H * e3 - gY.d * x[12] - gY.c * x[kAlphaY];
    T[3] = -inputs.torquer[0] + gY.H * a[0].drift - gY.d * x[13] - gY.c * x[kBetaY];
  }

  TwoPositionGyroPlatformParams p_;
};

}  // namespace gyrostab::models
