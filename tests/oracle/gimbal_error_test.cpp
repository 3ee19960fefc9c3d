// Oracle tests of the gimbal (kinematic) error of a position gyro (sim/models/position_gyro_gimbal_error.hpp)
// against Magnus §12.1 (docs/models/gimbal-error.md): the gimbal angles computed from the attitude against
// the book's closed forms (12.11), (12.16)-(12.20) for every mounting over random attitudes; the heading gyro
// "321" in a level turn against (12.13)-(12.15) and its extreme (bank 30°: 4.117°); the same through the
// integrated attitude of a simulated turn.
//
// Tolerances. The closed forms and the kinematics are the same functions of the Euler angles computed by
// different roundings (a DCM product against trigonometric products), each component to a few ε: sinβ agrees
// to ~1e-15; α = atan2 of two such components agrees to ~ε / cosβ, so 1e-12 holds away from gimbal lock
// (cosβ > 1e-3, where α stops being defined). In the turn the attitude is integrated by RK4 at hω = 5e-4
// (error ~(hω)⁵ per step, far below rounding) and the extreme of Δψ is sampled every 0.03° of heading: on its
// flat top (|Δψ''| < 0.3) the sampled maximum is low by < ½ · 0.3 · (2.6e-4 rad)² ≈ 1e-8 rad.
#include "sim/oracles/gimbal_error_closed_forms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "sim/dynamics/rk4.hpp"
#include "sim/models/position_gyro_gimbal_error.hpp"

namespace gyrostab {
namespace gimbal_error_test {

using models::GimbalMounting;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

Eigen::Matrix3d attitude(double psi, double theta, double phi) {
  return (Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }

TEST(GimbalErrorClosedForms, EveryMountingMatchesItsClosedFormOverRandomAttitudes) {
  std::mt19937_64 rng(20261210);  // seeded: the test is deterministic
  std::uniform_real_distribution<double> yaw(-kPi, kPi), pitch(-0.5 * kPi, 0.5 * kPi), roll(-kPi, kPi);
  for (int m = 0; m < 6; ++m) {
    const auto mounting = static_cast<GimbalMounting>(m);
    const Eigen::Matrix3d a_E = models::mounting_matrix(mounting);
    ASSERT_NEAR(a_E.determinant(), 1.0, 0.0) << "a proper rotation";
    double worst_alpha = 0.0, worst_sin_beta = 0.0;
    for (int k = 0; k < 100000; ++k) {
      const double psi = yaw(rng), theta = pitch(rng), phi = roll(rng);
      const models::GimbalAngles g = models::gimbal_angles(attitude(psi, theta, phi), a_E);
      const oracles::GimbalClosedForm cf = oracles::gimbal_closed_form(mounting, psi, theta, phi);
      worst_sin_beta = std::fmax(worst_sin_beta, std::fabs(std::sin(g.beta) - cf.sin_beta));
      if (std::cos(g.beta) > 1e-3) worst_alpha = std::fmax(worst_alpha, std::fabs(wrap(g.alpha - cf.alpha())));
    }
    std::printf("  mounting %s: max |Δα| %.2e rad, max |Δ sinβ| %.2e over 1e5 attitudes\n",
                models::kGimbalMountingNames[m].data(), worst_alpha, worst_sin_beta);
    EXPECT_LT(worst_alpha, 1e-12) << models::kGimbalMountingNames[m];
    EXPECT_LT(worst_sin_beta, 1e-14) << models::kGimbalMountingNames[m];
  }
}

TEST(GimbalErrorClosedForms, EachGimbalReadsItsVehicleAngleForThatRotationAlone) {
  // The book's labels: at a single small rotation the gimbal along that axis reads it exactly.
  const double a = 0.3;
  const struct {
    GimbalMounting m;
    double psi, theta, phi;
    double alpha, beta;
  } cases[] = {{GimbalMounting::k321, a, 0, 0, a, 0}, {GimbalMounting::k321, 0, a, 0, 0, a},
               {GimbalMounting::k123, 0, 0, a, a, 0}, {GimbalMounting::k213, 0, a, 0, a, 0},
               {GimbalMounting::k213, 0, 0, a, 0, a}, {GimbalMounting::k231, a, 0, 0, a, 0},
               {GimbalMounting::k231, 0, 0, a, 0, a}, {GimbalMounting::k312, 0, a, 0, a, 0},
               {GimbalMounting::k312, a, 0, 0, 0, a}, {GimbalMounting::k132, 0, 0, a, a, 0},
               {GimbalMounting::k132, a, 0, 0, 0, a}};
  for (const auto& c : cases) {
    const models::GimbalAngles g = models::gimbal_angles(attitude(c.psi, c.theta, c.phi), models::mounting_matrix(c.m));
    EXPECT_NEAR(g.alpha, c.alpha, 1e-15) << models::kGimbalMountingNames[static_cast<int>(c.m)];
    EXPECT_NEAR(g.beta, c.beta, 1e-15) << models::kGimbalMountingNames[static_cast<int>(c.m)];
  }
}

TEST(GimbalErrorHeadingGyro, LevelTurnMatches12_13To12_15) {
  double worst14 = 0.0, worst15 = 0.0;
  for (const double bank_deg : {5.0, 10.0, 30.0, 60.0, 80.0}) {
    const double phi = bank_deg * kDeg;
    for (int k = 0; k <= 3600; ++k) {
      const double psi = -kPi + 2.0 * kPi * k / 3600.0;
      const models::GimbalAngles g = models::gimbal_angles(attitude(psi, 0.0, phi),
                                                           models::mounting_matrix(GimbalMounting::k321));
      // (12.13) tanα = tanψ cosφ, with α on ψ's branch.
      EXPECT_NEAR(std::sin(g.alpha) * std::cos(psi), std::cos(g.alpha) * std::sin(psi) * std::cos(phi), 1e-15);
      const double d_psi = wrap(g.alpha - psi);
      worst14 = std::fmax(worst14, std::fabs(d_psi - oracles::heading_gyro_turn_error(psi, phi)));
      if (bank_deg <= 10.0) {
        // (12.15) drops the terms of order φ⁴: |Δψ − (12.15)| ≤ φ⁴/4 (bound of the series' next terms).
        const double e15 = std::fabs(d_psi - oracles::heading_gyro_turn_error_small_bank(psi, phi));
        worst15 = std::fmax(worst15, e15 / std::pow(phi, 4));
      }
    }
  }
  std::printf("  (12.14): max |Δψ − formula| %.2e rad; (12.15): max |Δψ − formula| / φ⁴ = %.3f\n", worst14, worst15);
  EXPECT_LT(worst14, 1e-14);
  EXPECT_LT(worst15, 0.25);
}

TEST(GimbalErrorHeadingGyro, ExtremeAtBank30DegIs4_117Deg) {
  const oracles::TurnErrorExtreme e = oracles::heading_gyro_turn_error_extreme(30.0 * kDeg);
  std::printf("  bank 30°: extreme Δψ %.6f° at ψ = %.4f°\n", e.error / kDeg, e.heading / kDeg);
  EXPECT_NEAR(e.error / kDeg, -4.117, 0.0005);   // the digits the book gives
  EXPECT_NEAR(e.heading / kDeg, 47.06, 0.005);
  // It is the extreme of (12.14): a scan of ψ finds no larger |Δψ|, and finds it there.
  double best = 0.0, at = 0.0;
  for (int k = 0; k <= 900000; ++k) {
    const double psi = 0.5 * kPi * k / 900000.0, d = std::fabs(oracles::heading_gyro_turn_error(psi, 30.0 * kDeg));
    if (d > best) best = d, at = psi;
  }
  EXPECT_NEAR(best, std::fabs(e.error), 1e-12);
  EXPECT_NEAR(at, e.heading, 2e-6);
  // Other banks: 10° → 0.439°, 60° → 19.47°, 80° → 44.76° (the book's Fig. 12.5 bank).
  EXPECT_NEAR(oracles::heading_gyro_turn_error_extreme(10.0 * kDeg).error / kDeg, -0.439, 0.0005);
  EXPECT_NEAR(oracles::heading_gyro_turn_error_extreme(60.0 * kDeg).error / kDeg, -19.47, 0.005);
  EXPECT_NEAR(oracles::heading_gyro_turn_error_extreme(80.0 * kDeg).error / kDeg, -44.76, 0.005);
}

TEST(GimbalErrorHeadingGyro, SimulatedTurnReachesTheBookExtreme) {
  models::PositionGyroGimbalErrorParams p;
  p.mounting = GimbalMounting::k321;
  p.vehicle.yaw.rate = 3.0 * kDeg;  // standard-rate turn
  p.vehicle.roll.offset = 30.0 * kDeg;
  const models::PositionGyroGimbalError model(p);
  dynamics::Rk4<models::PositionGyroGimbalError> rk4(model);
  auto x = model.initial_state(0.0);
  const double h = 0.01;
  double best = 0.0, worst_formula = 0.0;
  for (int k = 1; k <= 12000; ++k) {
    rk4.step((k - 1) * h, h, x);
    const double psi = p.vehicle.yaw(k * h).angle;
    const double d_psi = wrap(model.gimbal_angles_of(x).alpha - psi);
    best = std::fmax(best, std::fabs(d_psi));
    worst_formula = std::fmax(worst_formula, std::fabs(d_psi - oracles::heading_gyro_turn_error(psi, 30.0 * kDeg)));
  }
  const double book = std::fabs(oracles::heading_gyro_turn_error_extreme(30.0 * kDeg).error);
  std::printf("  simulated turn: max |Δψ| %.9f rad (book %.9f, diff %.1e), max |Δψ − (12.14)| %.1e rad\n", best,
              book, best - book, worst_formula);
  EXPECT_LT(worst_formula, 1e-12);  // rounding of 12000 RK4 steps of the attitude
  EXPECT_LE(best, book + 1e-12);
  EXPECT_GT(best, book - 1e-8);  // the sampled flat top
  EXPECT_NEAR(best / kDeg, 4.117, 0.0005);
}

}  // namespace gimbal_error_test
}  // namespace gyrostab
