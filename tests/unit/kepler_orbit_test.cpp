// Kepler suspension-point orbit (sim/motion/kepler_orbit.hpp): velocity/acceleration against differences of
// position, the orbital trihedron's rate against differences of its attitude, energy and angular momentum
// constant, return after one period, zero specific force (Chelnokov §4 Kepler case).
#include "sim/motion/kepler_orbit.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gyrostab {
namespace kepler_orbit_test {

using dynamics::Quat;
using dynamics::Vec3;

motion::KeplerOrbitParams eccentric() {
  motion::KeplerOrbitParams p;
  p.semi_major_axis = 1.2e7;
  p.eccentricity = 0.4;
  p.inclination = 0.9;
  p.node = 0.3;
  p.perigee = -1.1;
  p.mean_anomaly0 = 0.2;
  return p;
}

TEST(KeplerOrbit, KinematicsMatchDifferences) {
  ASSERT_EQ(motion::KeplerOrbitParams::check(eccentric()), nullptr);
  const motion::KeplerOrbit orbit(eccentric());
  // h = 1 s; |p'''| ≲ GM v / r³ ~ 2.5e-2 at perigee (r = 7.2e6): truncation h²|p'''|/6 ≈ 4e-3 m/s,
  // acceleration h²|p''''|/12 ≲ 1e-4; rounding |p| ε/h² ~ 2e-9.  Tolerances 1e-2 m/s, 1e-3 m/s².
  // Attitude: |ω| ≤ 1.3e-3 rad/s, truncation h²|ω|³/6 ~ 1e-10; rate derivative h²|ν''''|/6 ~ 1e-12.
  const double h = 1.0;
  for (double t : {0.0, 1000.0, 4321.0, 9000.0, 12000.0}) {
    const auto m = orbit.sample(t - h), z = orbit.sample(t), p = orbit.sample(t + h);
    EXPECT_LT(((p.p_I - m.p_I) / (2 * h) - z.v_I).norm(), 1e-2) << t;
    EXPECT_LT(((p.p_I - 2 * z.p_I + m.p_I) / (h * h) - z.a_I).norm(), 1e-3) << t;
    const Eigen::Vector4d d = (p.orbital.q_IZ.coeffs() - m.orbital.q_IZ.coeffs()) / (2 * h);
    const Vec3 w = 2.0 * (z.orbital.q_IZ.conjugate() * Quat(d[3], d[0], d[1], d[2])).vec();
    EXPECT_LT((w - z.orbital.w_IZ_Z).norm(), 1e-9) << t;
    EXPECT_NEAR((p.orbit_rate - m.orbit_rate) / (2 * h), z.orbit_rate_dot, 1e-11) << t;
    // Energy, angular momentum: closed form evaluated at every t, so rounding only.
    const double energy = 0.5 * z.v_I.squaredNorm() - orbit.params().gm / z.p_I.norm();
    EXPECT_NEAR(energy, -orbit.params().gm / (2 * orbit.params().semi_major_axis), 1e-6 * std::abs(energy));
    EXPECT_NEAR(z.p_I.cross(z.v_I).norm(), orbit.angular_momentum(), 1e-9 * orbit.angular_momentum());
    EXPECT_EQ(z.f_I.norm(), 0.0);
    EXPECT_LT((z.orbital.q_IZ * Vec3::UnitZ() - z.p_I.normalized()).norm(), 1e-12);
    EXPECT_LT((z.orbital.q_IZ * z.orbital.v_Z - z.v_I).norm(), 1e-6);
  }
  const double T = orbit.params().period();
  EXPECT_LT((orbit.sample(T + 77.0).p_I - orbit.sample(77.0).p_I).norm(), 1e-6 * 1.2e7);
}

TEST(KeplerOrbit, RefusesNonElliptic) {
  auto p = eccentric();
  p.eccentricity = 1.0;
  EXPECT_NE(motion::KeplerOrbitParams::check(p), nullptr);
  p.eccentricity = 0.1;
  p.semi_major_axis = 0.0;
  EXPECT_NE(motion::KeplerOrbitParams::check(p), nullptr);
  const motion::KeplerOrbit clamped(p);
  EXPECT_TRUE(clamped.sample(3.0).p_I.allFinite());
}

}  // namespace kepler_orbit_test
}  // namespace gyrostab
