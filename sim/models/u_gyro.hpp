// Rate gyro with an asymmetric rotor (U-gyro): a single-gimbal rate gyro whose rotor has unequal transverse
// inertias A^R ≠ B^R. As the rotor spins, its inertia about the output axis changes with twice the spin
// angle, and the gyroscopic torque on the frame gets a component at twice the spin frequency.
//
// Book: Magnus, Kreisel §15.4, (15.27)-(15.29) (docs/models/u-gyro.md). With the frame held (β = 0) and the
// case turning at Ω about the input axis 1, the rotor's rates in its principal axes are
//   (15.27)  ω = (Ω cosγ, −Ω sinγ, γ'),   H = (A^R Ω cosγ, −B^R Ω sinγ, C^R γ'),
// Euler's equations give the torque (15.28), and about the output axis 2 the rotor acts on the frame with
//   (15.29)  M2 = H Ω [1 − ((A^R − B^R)/C^R) cos 2γ],   H = C^R γ'.
// Implemented: the frame free about axis 2 (angle β against the case), restrained by a spring c2 and a
// damper d2, from Lagrange's equation with the exact kinetic energy of rotor and frame (not linearized in
// β). Frame angular velocity in frame axes (Ω cosβ, β', Ω sinβ); rotor rates in its principal axes
//   ω_x = Ω cosβ cosγ + β' sinγ,   ω_y = −Ω cosβ sinγ + β' cosγ,   ω_z = Ω sinβ + γ';
// the output-axis inertia I2(γ) = A^R sin²γ + B^R cos²γ + B^J varies with the spin angle, and
//   d/dt[I2 β' + (A^R − B^R) Ω cosβ sinγ cosγ] − ∂T/∂β = −c2 β − d2 β'
//   ∂T/∂β = −A^R ω_x Ω sinβ cosγ + B^R ω_y Ω sinβ sinγ + C^R ω_z Ω cosβ + (C^J − A^J) Ω² sinβ cosβ.
// At β = β' = 0 the torque of the rotor on the frame is (15.29) exactly (gyro_torque_on_frame()).
//
// State x = [β (rad), β' (rad/s), γ (rad)]: output angle, its rate, spin angle.
// Parameters (SI): AR, BR, CR rotor principal inertias (CR about the spin axis) [kg m²]; AJ, BJ, CJ frame
// inertias about frame axes 1, 2, 3 [kg m²]; c2 spring [N m/rad]; d2 damper [N m s/rad]; spin γ' [rad/s].
// Inputs (zero-order hold): Omega, case rate about the input axis 1 [rad/s]; Omega_dot its rate [rad/s²].
// Assumptions: the spin motor holds γ' constant whatever the torque it takes (the book's H = C^R γ' =
// const); the case turns about axis 1 only (Ω2 = Ω3 = 0, as in (15.27)); rotor and frame rigid, rotor
// balanced (no static or dynamic unbalance beyond A^R ≠ B^R).
// Oracle: tests/oracle/u_gyro_test.cpp — the torque on the held frame against (15.29), and the amplitude of
// the output's twice-spin component against (15.29) passed through the frame's response.
// Docs: docs/models/u-gyro.md
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace gyrostab::models {

struct UGyroParams {
  double AR{1.04e-4};  // rotor inertia about its principal axis x [kg m²]
  double BR{0.56e-4};  // rotor inertia about its principal axis y [kg m²]
  double CR{1.6e-4};   // rotor inertia about the spin axis [kg m²]
  double AJ{2.0e-4};   // frame about axis 1 [kg m²]
  double BJ{3.0e-4};   // frame about the output axis 2 [kg m²]
  double CJ{2.0e-4};   // frame about axis 3 [kg m²]
  double c2{600.0};    // output-axis spring [N m/rad]
  double d2{0.05};     // output-axis damper [N m s/rad]
  double spin{628.3185307179587};  // γ', held [rad/s]

  // nullptr if physically possible, else the reason (for scene validation).
  const char* invalid_reason() const {
    if (!(AR > 0.0) || !(BR > 0.0) || !(CR > 0.0)) return "AR, BR, CR must be > 0";
    // A flat rotor sits on the bound AR + BR = CR: allow the rounding of its decimal inertias.
    const double slack = 1e-12 * (AR + BR + CR);
    if (!(AR + BR + slack >= CR) || !(BR + CR + slack >= AR) || !(CR + AR + slack >= BR)) {
      return "the rotor's inertias must satisfy the triangle inequalities (AR + BR >= CR, ...)";
    }
    if (!(AJ >= 0.0) || !(BJ >= 0.0) || !(CJ >= 0.0)) return "AJ, BJ, CJ must be >= 0";
    if (!(c2 > 0.0) || !(d2 >= 0.0)) return "c2 must be > 0, d2 >= 0";
    return nullptr;
  }
  double H() const { return CR * spin; }
  double asymmetry() const { return (AR - BR) / CR; }
  // The output-axis inertia averaged over a revolution [kg m²].
  double mean_output_inertia() const { return 0.5 * (AR + BR) + BJ; }
};

struct UGyroInputs {
  double Omega{0.0};      // case rate about the input axis 1 [rad/s]
  double Omega_dot{0.0};  // its rate of change [rad/s²]
};

class UGyro {
 public:
  static constexpr int kStateSize = 3;
  using State = Eigen::Matrix<double, 3, 1>;
  static constexpr const char* kName = "u-gyro";
  // The state's components, by name.
  static constexpr int kBeta = 0, kBetaRate = 1, kGamma = 2;

  explicit UGyro(const UGyroParams& p = {}) : p_(p) {}

  UGyroInputs inputs{};  // held between steps

  const UGyroParams& params() const { return p_; }

  static State make_state(double beta, double beta_rate, double gamma) {
    State x;
    x << beta, beta_rate, gamma;
    return x;
  }

  void derivative(double /*t*/, const State& x, State& dx) const {
    const double beta = x[kBeta], u = x[kBetaRate];
    const double sg = std::sin(x[kGamma]), cg = std::cos(x[kGamma]);
    const double I2 = p_.AR * sg * sg + p_.BR * cg * cg + p_.BJ;
    dx[kBeta] = u;
    dx[kBetaRate] = (gyro_torque_on_frame(x) - p_.c2 * beta - p_.d2 * u) / I2;
    dx[kGamma] = p_.spin;
  }
  void project(State&) const {}

  // Everything of Lagrange's equation but I2 β'', the spring and the damper: the torque rotor and frame
  // inertia put on the output axis [N m]; at β = β' = 0, Ω' = 0 it is (15.29).
  double gyro_torque_on_frame(const State& x) const {
    const double Om = inputs.Omega, dOm = inputs.Omega_dot, nu = p_.spin, u = x[kBetaRate];
    const double sb = std::sin(x[kBeta]), cb = std::cos(x[kBeta]);
    const double sg = std::sin(x[kGamma]), cg = std::cos(x[kGamma]);
    const double dAB = p_.AR - p_.BR;
    const double wx = Om * cb * cg + u * sg, wy = -Om * cb * sg + u * cg, wz = Om * sb + nu;
    const double dT_dbeta = -p_.AR * wx * Om * sb * cg + p_.BR * wy * Om * sb * sg + p_.CR * wz * Om * cb +
                            (p_.CJ - p_.AJ) * Om * Om * sb * cb;
    const double dI2_dt = nu * dAB * 2.0 * sg * cg;
    const double d_coupling_dt =
        dAB * (dOm * cb * sg * cg - Om * sb * u * sg * cg + Om * cb * nu * (cg * cg - sg * sg));
    return dT_dbeta - dI2_dt * u - d_coupling_dt;
  }

 private:
  UGyroParams p_;
};

}  // namespace gyrostab::models
