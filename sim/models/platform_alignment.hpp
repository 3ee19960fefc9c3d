// Alignment of a local-level inertial platform from an unaligned start: a three-axis platform whose
// stabilization servos follow its gyros, on a base at rest on the rotating Earth, levelled and
// gyrocompassed by its own accelerometers and gyro torquers (firmware/control/platform_alignment_loops.hpp).
//
// Book: Magnus §16.5, (16.52), with the local-level frame of §16.4.4, (16.51) (docs/models/platform-alignment.md).
// Frames: G = geographic trihedron (G1 east, G2 north, G3 up along the plumb line), P = platform
// (P1 "east", P2 "north", P3 "up" as far as the platform knows). q_GP rotates P components into G.
// On a base at rest G turns with the Earth: ω_IG_G = ω^E (0, cosφ, sinφ), constant in G axes ((16.51), v = 0).
// Servo assumption (the book's: servo time constants << alignment time): the platform turns at exactly its
// gyros' torquing command plus their drift,
//   ω_IP_P = ω_cmd + ε                                                   [rad/s, P axes]
//   dq_GP/dt = ½ q_GP ⊗ (0, ω_GP_P),   ω_GP_P = ω_IP_P − R_PG ω_IG_G      (exact, any attitude)
// so the base's own rotation (angular jitter, gusts) does not reach the platform; its translational
// acceleration does, through the accelerometers:
//   a_P = R_PG f_G + b       f_G = specific force at the platform [m/s²] (g up at rest), b = biases
// Misalignment (outputs), exact for any attitude with P2 not vertical, from up_P = R_PG e3 and P2_G = R_GP e2:
//   tilt about east   θ_E = asin(up_P,2)            (rotation of P about P1; a_N ≈ g θ_E)
//   tilt about north  θ_N = atan2(−up_P,1, up_P,3)  (rotation of P about P2; a_E ≈ −g θ_N)
//   heading error     ψ   = atan2(P2_G,1, P2_G,2)   (azimuth of the platform's north axis, clockwise from north)
// and the attitude they stand for is R_GP = Rz(−ψ) Rx(θ_E) Ry(θ_N) (the round trip is exact).
// (16.52): on a level platform with heading error ψ the east axis P1 = (cosψ, −sinψ, 0) sees the Earth rate
//   ω_IG · P1 = −ω^E cosφ sinψ                      (4.7e-8 rad/s for ψ = 1 mrad at 50°)
// Linearised (small θ_E, θ_N, ψ; Ω_N = ω^E cosφ, Ω_U = ω^E sinφ; derived from the kinematics above):
//   θ_E' = ω_cE + ε_E + Ω_N ψ + Ω_U θ_N
//   θ_N' = ω_cN + ε_N − Ω_N − Ω_U θ_E
//   ψ'   = −ω_cU − ε_U + Ω_U − Ω_N θ_E
// State: x = q_GP (x, y, z, w) [-]. Inputs (held over a tick): ω_cmd [rad/s, P axes].
// Parameters: ω^E [rad/s], latitude φ [rad] (astronomical: the plumb line's), gyro drifts ε [rad/s, P axes],
// accelerometer biases b [m/s², P axes].
// Assumptions: ideal gimbal isolation and servos (no servo lag, no gimbal error), gyro scale factors exact,
// base at rest (its motion enters only as specific force), the plumb line is "up" of G.
// Oracle: tests/oracle/platform_alignment_test.cpp — (16.52) exact; the levelling loops' second-order response;
// the azimuth loop's roots; the residual misalignment from biases and drifts; alignment time ∝ 1/cosφ.
// Docs: docs/models/platform-alignment.md
#pragma once

#include <cmath>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

struct PlatformAlignmentParams {
  double earth_rate{7.292115e-5};                        // ω^E [rad/s]
  double latitude{0.0};                                  // φ [rad]
  dynamics::Vec3 drift{dynamics::Vec3::Zero()};          // ε of the east, north, zenith gyros [rad/s]
  dynamics::Vec3 accel_bias{dynamics::Vec3::Zero()};     // b of the east, north, up accelerometers [m/s²]
};

// The platform's misalignment against the geographic frame [rad].
struct PlatformMisalignment {
  double tilt_east{0.0};      // θ_E: about the east axis
  double tilt_north{0.0};     // θ_N: about the north axis
  double heading_error{0.0};  // ψ: azimuth of the platform's north axis, clockwise from north
};

// ω_IG_G of a base at rest: (0, ω^E cosφ, ω^E sinφ) [rad/s].
inline dynamics::Vec3 earth_rate_geographic(double earth_rate, double latitude) {
  return {0.0, earth_rate * std::cos(latitude), earth_rate * std::sin(latitude)};
}

// q_GP of R_GP = Rz(−ψ) Rx(θ_E) Ry(θ_N).
inline dynamics::Quat attitude_of(const PlatformMisalignment& m) {
  using Eigen::AngleAxisd;
  return dynamics::Quat(AngleAxisd(-m.heading_error, dynamics::Vec3::UnitZ()) *
                        AngleAxisd(m.tilt_east, dynamics::Vec3::UnitX()) *
                        AngleAxisd(m.tilt_north, dynamics::Vec3::UnitY()));
}

// The misalignment of q_GP (header).
inline PlatformMisalignment misalignment_of(const dynamics::Quat& q_GP) {
  const Eigen::Matrix3d R = q_GP.toRotationMatrix();
  const dynamics::Vec3 up_P = R.row(2).transpose();  // R_PG e3
  const dynamics::Vec3 north_G = R.col(1);           // R_GP e2
  const double s = std::fmax(-1.0, std::fmin(1.0, up_P.y()));
  return {std::asin(s), std::atan2(-up_P.x(), up_P.z()), std::atan2(north_G.x(), north_G.y())};
}

class PlatformAlignment {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  // The state's components, by name (q_GP in Eigen's order).
  static constexpr int kQx = 0, kQy = 1, kQz = 2, kQw = 3;

  struct Inputs {
    dynamics::Vec3 rate_command{dynamics::Vec3::Zero()};  // ω_cmd of the east, north, zenith gyros [rad/s]
  };

  explicit PlatformAlignment(const PlatformAlignmentParams& p = {})
      : p_(p), w_IG_G_(earth_rate_geographic(p.earth_rate, p.latitude)) {}

  Inputs inputs{};

  const PlatformAlignmentParams& params() const { return p_; }
  const dynamics::Vec3& earth_rate_G() const { return w_IG_G_; }

  static State state_of(const dynamics::Quat& q) {
    State x;
    x << q.x(), q.y(), q.z(), q.w();
    return x;
  }
  static dynamics::Quat attitude(const State& x) { return dynamics::Quat(x[kQw], x[kQx], x[kQy], x[kQz]); }

  void derivative(double, const State& x, State& dx) const {
    const Eigen::Map<const dynamics::Quat> q(x.data());
    const dynamics::Vec3 w_GP_P = inputs.rate_command + p_.drift - q.conjugate() * w_IG_G_;
    dynamics::quaternion_rate(x, w_GP_P, dx);
  }
  // RK4 does not keep |q| = 1; the drift per step is far below the cheap projection's validity.
  void project(State& x) const { dynamics::renormalize_cheap(x); }

  // The Earth's rate on the platform axes, R_PG ω_IG_G [rad/s]: what each gyro must be torqued at for the
  // platform to stay put relative to G; its east component is (16.52) on a level platform.
  dynamics::Vec3 earth_rate_on_platform(const State& x) const { return attitude(x).conjugate() * w_IG_G_; }

  // The accelerometer outputs a_P = R_PG f_G + b for the specific force f_G [m/s²].
  dynamics::Vec3 accelerometers(const State& x, const dynamics::Vec3& f_G) const {
    return attitude(x).conjugate() * f_G + p_.accel_bias;
  }

  static PlatformMisalignment misalignment(const State& x) { return misalignment_of(attitude(x)); }

 private:
  PlatformAlignmentParams p_;
  dynamics::Vec3 w_IG_G_;
};

}  // namespace gyrostab::models
