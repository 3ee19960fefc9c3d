// GimbalGyro<Base>::derivative against an independent derivation of its equations of motion.
//
// The model (sim/models/gimbal_gyro.hpp) is derived with Kane's method. The oracle here,
// tools/derive/gimbal_gyro_lagrange.py, derives the same system from the Lagrangian of the three bodies on a
// base with arbitrary Ω(t), reduces the rotor angle γ by Routh with a time-varying spin momentum H (Ḣ = M3),
// checks itself symbolically against the book (Magnus (1.47), (1.51), (4.34), (4.45), (10.4)-(10.7), (10.22))
// and against the unreduced 3-DOF Lagrange equations, and writes α'', β'' for 20 random parameter sets,
// states, torques and base samples (w_B, dw_B, up_B independent of each other: the equations at one instant
// hold for any values) to data/gimbal_gyro_lagrange_vectors.inc.
// Two further cases are written out by hand from the book: (10.4)-(10.7) and (10.22).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/models/gimbal_gyro.hpp"

namespace gyrostab {
namespace gimbal_gyro_equations_test {

// One reference vector; field order is the generator's (see the header of the .inc file).
struct LagrangeVector {
  double AR, CR, AJ, BJ, CJ, AA, BA, CA;         // [kg m²]
  double Gs, d1, d2, r1, r2, coulomb_velocity;   // [N m], [N m s/rad], [N m], [rad/s]
  double alpha, beta, alpha_rate, beta_rate, H;  // [rad], [rad/s], [N m s]
  double M1, M2, M3;                             // [N m]
  double w_B[3], dw_B[3], up_B[3];               // [rad/s], [rad/s²], [-]
  double alpha_acc, beta_acc;                    // Lagrangian α'', β'' [rad/s²]
  double alpha_scale, beta_scale;                // Σ|terms of the numerator| / mass [rad/s²]
};

constexpr LagrangeVector kVectors[] =
#include "tests/oracle/data/gimbal_gyro_lagrange_vectors.inc"
    ;

// A base that returns one fixed sample whatever t is: the equations are checked at one instant.
struct SampledBase {
  models::BaseSample sample{};
  models::BaseSample operator()(double /*t*/) const { return sample; }
};

using Gyro = models::GimbalGyro<SampledBase>;

dynamics::Vec3 vec3(const double (&v)[3]) {
  return {v[0], v[1], v[2]};
}

Gyro make_model(const LagrangeVector& v) {
  models::GimbalGyroParams p;
  p.AR = v.AR;
  p.CR = v.CR;
  p.AJ = v.AJ;
  p.BJ = v.BJ;
  p.CJ = v.CJ;
  p.AA = v.AA;
  p.BA = v.BA;
  p.CA = v.CA;
  p.Gs = v.Gs;
  p.d1 = v.d1;
  p.d2 = v.d2;
  p.r1 = v.r1;
  p.r2 = v.r2;
  p.coulomb_velocity = v.coulomb_velocity;
  // The reference vectors carry the regularised Coulomb term r v/sqrt(v² + v_c²), a function of the state;
  // the stick-slip torque is a per-step decision (gimbal_stick_slip_test.cpp holds that one).
  p.friction_model = drives::CoulombModel::kSmooth;
  SampledBase base;
  base.sample.w_B = vec3(v.w_B);
  base.sample.dw_B = vec3(v.dw_B);
  base.sample.up_B = vec3(v.up_B);
  Gyro g(p, base);
  g.torques = {v.M1, v.M2, v.M3};
  return g;
}

// Tolerance: the model evaluates each acceleration in ~150 double operations (sin/cos within 1 ulp). Whatever
// the order of evaluation, the round-off of a sum of products is bounded by (operation count) · 2^-53 ·
// Σ|products|, and Σ|products| ≤ Σ|terms of the expanded numerator| = scale · mass, which the generator
// writes as `*_scale`: 150 · 1.1e-16 ≈ 2e-14 of the scale, so 1e-12 · scale leaves a 50× margin (observed:
// 2e-16). Sensitivity, measured when this test was written by compiling it against mutated copies of the
// model: dropping M3 from the gyrostat, swapping C^A − B^A, dropping any one transport term (α'·a3, α'·a2,
// β'·j3) or dΩ1, or flipping the Ω3 term of a2 each fails 10-20 of the vectors by ≥ 7·10⁴ × this tolerance.
constexpr double kRoundOff = 1e-12;

TEST(GimbalGyroEquations, AccelerationsMatchLagrangianDerivationOnArbitraryBaseMotion) {
  double max_rel_to_scale = 0.0, max_rel = 0.0;
  int index = 0;
  for (const LagrangeVector& v : kVectors) {
    SCOPED_TRACE(testing::Message() << "vector " << index++);
    const Gyro g = make_model(v);
    const Gyro::State x = Gyro::make_state(v.alpha, v.beta, v.alpha_rate, v.beta_rate, v.H);
    Gyro::State dx;
    g.derivative(0.0, x, dx);
    EXPECT_EQ(dx[0], v.alpha_rate);
    EXPECT_EQ(dx[1], v.beta_rate);
    EXPECT_EQ(dx[4], v.M3);  // Ḣ = M3: the rotor's own equation (the γ equation of the Lagrangian)
    EXPECT_NEAR(dx[2], v.alpha_acc, kRoundOff * v.alpha_scale);
    EXPECT_NEAR(dx[3], v.beta_acc, kRoundOff * v.beta_scale);
    max_rel_to_scale = std::max({max_rel_to_scale, std::abs(dx[2] - v.alpha_acc) / v.alpha_scale,
                                 std::abs(dx[3] - v.beta_acc) / v.beta_scale});
    max_rel = std::max({max_rel, std::abs(dx[2] - v.alpha_acc) / std::abs(v.alpha_acc),
                        std::abs(dx[3] - v.beta_acc) / std::abs(v.beta_acc)});
  }
  std::printf("max |model - Lagrange| / |Lagrange| = %.3g, / scale = %.3g over %zu vectors\n", max_rel,
              max_rel_to_scale, std::size(kVectors));
}

// Magnus (10.4)-(10.7), written out by hand: base at rest, outer axis tilted by δ from the vertical
// (up_B = (cos δ, 0, sin δ)), no friction, no rotor torque.
//   [A cos²β + P sin²β] α'' − Q sin2β α'β' + H cosβ β' = M1 + Gs sinδ cosβ sinα
//   B β'' + Q sinβ cosβ α'² − H cosβ α' = M2 − Gs (cosδ cosβ − sinδ sinβ cosα)
TEST(GimbalGyroEquations, FixedTiltedBaseMatchesBookEquations10_4To10_7) {
  models::GimbalGyroParams p;
  p.AR = 0.7;
  p.CR = 1.3;
  p.AJ = 0.25;
  p.BJ = 0.35;
  p.CJ = 0.15;
  p.AA = 0.4;
  p.BA = 0.9;  // B^A, C^A must not matter on a base at rest
  p.CA = 0.2;
  p.Gs = 1.7;
  const double delta = 0.6, alpha = 0.8, beta = -0.5, alpha_rate = 1.3, beta_rate = -2.1, H = 25.0;
  const double M1 = 0.45, M2 = -0.3;
  SampledBase base;
  base.sample.up_B = {std::cos(delta), 0.0, std::sin(delta)};
  Gyro g(p, base);
  g.torques = {M1, M2, 0.0};
  Gyro::State dx;
  g.derivative(0.0, Gyro::make_state(alpha, beta, alpha_rate, beta_rate, H), dx);

  const double A = p.AA + p.AJ + p.AR, B = p.BJ + p.AR, P = p.AA + p.CJ, Q = p.AR + p.AJ - p.CJ;
  const double sb = std::sin(beta), cb = std::cos(beta);
  const double M1g = M1 + p.Gs * std::sin(delta) * cb * std::sin(alpha);
  const double M2g = M2 - p.Gs * (std::cos(delta) * cb - std::sin(delta) * sb * std::cos(alpha));
  const double alpha_acc = (M1g + Q * std::sin(2.0 * beta) * alpha_rate * beta_rate - H * cb * beta_rate) /
                           (A * cb * cb + P * sb * sb);
  const double beta_acc = (M2g - Q * sb * cb * alpha_rate * alpha_rate + H * cb * alpha_rate) / B;
  // The largest terms are H cosβ·rate ≈ 50 N m over masses ≈ 1 kg m²; 1e-10 is ~10⁴ ulp of them, and far
  // below any wrong term (the smallest, Q sin2β α'β', is ≈ 1 N m).
  EXPECT_NEAR(dx[2], alpha_acc, 1e-10);
  EXPECT_NEAR(dx[3], beta_acc, 1e-10);
}

// Magnus (10.22): small angles, rates and base rate on a rotating base (Gs = 0, no friction):
//   A α'' + H β' + H Ω3 α = M1 − A Ω1' − H Ω2
//   B β'' − H α' + H Ω3 β = M2 − B Ω2' + H Ω1
// The book drops inertia·Ω·(state), inertia·Ω·Ω and all second-order state terms (the generator lists them);
// they are O(ε²) here with ε = 1e-6, i.e. ≲ 10·(inertias + H)·ε² ≈ 1e-9 N m, while every kept term is
// ≳ 1e-7 N m and the accelerations are ~1e-5 rad/s². A tolerance of 1e-8 rad/s² therefore separates the
// neglected second order from any wrong first-order term (sign, Ω index or missing H).
TEST(GimbalGyroEquations, SmallAnglesOnRotatingBaseMatchBookEquation10_22) {
  models::GimbalGyroParams p;
  p.AR = 0.6;
  p.CR = 1.1;
  p.AJ = 0.2;
  p.BJ = 0.3;
  p.CJ = 0.1;
  p.AA = 0.5;
  p.BA = 0.8;
  p.CA = 0.3;
  const double eps = 1e-6, H = 40.0;
  const double alpha = 0.7 * eps, beta = -1.1 * eps, alpha_rate = 2.0 * eps, beta_rate = 1.5 * eps;
  const double M1 = 30.0 * eps, M2 = -20.0 * eps;
  SampledBase base;
  base.sample.w_B = {0.9 * eps, -1.3 * eps, 1.7 * eps};
  base.sample.dw_B = {-2.3 * eps, 0.4 * eps, 1.9 * eps};
  base.sample.up_B = {0.0, 0.0, 1.0};
  Gyro g(p, base);
  g.torques = {M1, M2, 0.0};
  Gyro::State dx;
  g.derivative(0.0, Gyro::make_state(alpha, beta, alpha_rate, beta_rate, H), dx);

  const double A = p.AA + p.AJ + p.AR, B = p.BJ + p.AR;
  const dynamics::Vec3& W = base.sample.w_B;
  const dynamics::Vec3& dW = base.sample.dw_B;
  const double alpha_acc = (M1 - A * dW[0] - H * W[1] - H * beta_rate - H * W[2] * alpha) / A;
  const double beta_acc = (M2 - B * dW[1] + H * W[0] + H * alpha_rate - H * W[2] * beta) / B;
  EXPECT_NEAR(dx[2], alpha_acc, 1e-8);
  EXPECT_NEAR(dx[3], beta_acc, 1e-8);
  EXPECT_GT(std::abs(alpha_acc), 1e-5);  // the comparison is not vacuous
  EXPECT_GT(std::abs(beta_acc), 1e-5);
}

// The rotor motor's reaction reaches the gimbals only through Ḣ = M3 inside d/dt ∂R/∂α' (= M3 sinβ); the
// motor torque pair itself has zero generalised force on α and β. Net effect: α'' changes by −M3 sinβ / I(β),
// β'' not at all.
TEST(GimbalGyroEquations, RotorTorqueReactsOnOuterGimbalAsMinusM3SinBetaOverI) {
  models::GimbalGyroParams p;
  p.AR = 0.5;
  p.AJ = 0.2;
  p.BJ = 0.3;
  p.CJ = 0.1;
  p.AA = 0.4;
  SampledBase base;
  base.sample.w_B = {0.3, -0.2, 0.5};
  base.sample.dw_B = {0.1, 0.4, -0.3};
  const double beta = 0.9, M3 = 2.5;
  const Gyro::State x = Gyro::make_state(0.3, beta, 0.7, -0.4, 12.0);
  Gyro g(p, base);
  Gyro::State dx0, dx1;
  g.derivative(0.0, x, dx0);
  g.torques.M3 = M3;
  g.derivative(0.0, x, dx1);
  // Differences of O(10) accelerations: round-off ~1e-15, tolerance 1e-12.
  EXPECT_NEAR(dx1[2] - dx0[2], -M3 * std::sin(beta) / p.outer_axis_inertia(beta), 1e-12);
  EXPECT_NEAR(dx1[3] - dx0[3], 0.0, 1e-12);
  EXPECT_EQ(dx1[4], M3);
}

}  // namespace gimbal_gyro_equations_test
}  // namespace gyrostab
