// Earth/vehicle motion generator (sim/motion/earth_vehicle.hpp): analytic velocities, accelerations and
// trihedron angular velocities against central differences of the sampled positions and attitudes; the
// geographic rates against Magnus (16.51); Chelnokov's Darboux relations w1 = R(q0' + p0 r0),
// w2 = −R(p0' − q0 r0), w3 = −R(p0² + q0²) (§2.4; the paper's printed w1, w2 lose their dots) for every
// trihedron with Z3 up;
// the azimuth-free trihedron's zero vertical rate; exact closure of a full coordinated turn.
#include "sim/motion/earth_vehicle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace gyrostab {
namespace earth_vehicle_test {

using dynamics::Quat;
using dynamics::Vec3;
using motion::EarthVehicleSample;
using motion::Trihedron;
constexpr double kPi = std::numbers::pi;
constexpr std::int64_t kSecond = 1'000'000'000;

// A sequence with every kind of segment at a high latitude (convergence of meridians matters there).
motion::EarthVehicle<8> manoeuvring(double omega_e = 7.292115e-5) {
  motion::EarthParams e;
  e.rotation_rate = omega_e;
  const motion::VehicleStart s{0.9, 0.3, 0.4, 120.0};
  static const motion::ManoeuvreSegment seg[] = {
      {600 * kSecond, 0.0, 0.0},      // great circle
      {300 * kSecond, 0.0, 0.4},      // accelerate to 240 m/s
      {400 * kSecond, 0.02, 0.0},     // right turn
      {200 * kSecond, -0.05, 0.0},    // left turn
      {500 * kSecond, 0.0, -0.3},     // decelerate to 90 m/s
  };
  EXPECT_EQ(motion::EarthVehicle<8>::check(e, s, seg, 5), nullptr);
  return motion::EarthVehicle<8>(e, s, seg, 5);
}

// Angular velocity in Z axes from q_IZ differences: ω_Z = 2 Im(q̄ q').
Vec3 fd_rate(const Quat& qm, const Quat& qp, const Quat& q0, double h) {
  Eigen::Vector4d d = (qp.coeffs() - qm.coeffs()) / (2.0 * h);
  if (qp.coeffs().dot(qm.coeffs()) < 0.0) ADD_FAILURE() << "quaternion sign flip inside the difference";
  const Quat dq(d[3], d[0], d[1], d[2]);
  const Quat w = q0.conjugate() * dq;
  return 2.0 * w.vec();
}

const Trihedron& pick(const EarthVehicleSample& s, int i) {
  switch (i) {
    case 0: return s.geographic;
    case 1: return s.track;
    case 2: return s.azimuth_free;
    default: return s.darboux;
  }
}

// Sample times in the interior of each segment (the differences must not straddle a corner).
constexpr double kTimes[] = {250.0, 750.0, 1100.0, 1610.0, 1800.0, 2600.0, 4000.0};

TEST(EarthVehicle, VelocityAndAccelerationMatchDifferencesOfPosition) {
  const auto veh = manoeuvring();
  // h = 0.1 s, worst case the 0.05 rad/s turn at 240 m/s: truncation h²|p'''|/6 = 0.01·v r²/6 = 1e-4 m/s,
  // h²|p''''|/12 = 0.01·v r³/12 = 2.5e-6 m/s²; rounding |p| ε / h² = 6.4e6·1.1e-16/0.01 = 7e-8 m/s².
  // Tolerances 1e-3 m/s and 1e-5 m/s².
  const double h = 0.1;
  for (double t : kTimes) {
    const auto m = veh.sample(t - h), z = veh.sample(t), p = veh.sample(t + h);
    EXPECT_LT(((p.p_I - m.p_I) / (2 * h) - z.v_I).norm(), 1e-3) << t;
    EXPECT_LT(((p.p_I - 2 * z.p_I + m.p_I) / (h * h) - z.a_I).norm(), 1e-5) << t;
    EXPECT_NEAR(z.p_I.norm(), veh.earth().radius, 1e-6);
    EXPECT_LT((z.f_I - (z.a_I + veh.earth().gravity * z.p_I.normalized())).norm(), 1e-12);
  }
}

TEST(EarthVehicle, TrihedronRatesMatchDifferencesOfAttitude) {
  const auto veh = manoeuvring();
  // Richardson-extrapolated central differences, h = 0.02 s and 0.01 s: error O(h⁴). The Darboux frame is
  // the fastest (|v_abs| = 89 m/s at t = 1100 s, r0 = 0.0185 rad/s varying on the Earth-rate beat): its plain
  // h = 0.02 difference is off by 2.6e-8 rad/s (measured, ∝ h²), so the extrapolated error is ~1e-11.
  // Rounding ε/h ~ 1e-14.  Tolerances 1e-9 rad/s and 1e-9 rad/s².
  const double h = 0.02;
  for (double t : kTimes) {
    const auto m = veh.sample(t - h), z = veh.sample(t), p = veh.sample(t + h);
    const auto m2 = veh.sample(t - h / 2), p2 = veh.sample(t + h / 2);
    ASSERT_TRUE(z.darboux_valid);
    for (int i = 0; i < 4; ++i) {
      const Trihedron &A = pick(m, i), &B = pick(z, i), &C = pick(p, i), &A2 = pick(m2, i), &C2 = pick(p2, i);
      const Vec3 w_fd = (4.0 * fd_rate(A2.q_IZ, C2.q_IZ, B.q_IZ, h / 2) - fd_rate(A.q_IZ, C.q_IZ, B.q_IZ, h)) / 3.0;
      const Vec3 dw_fd = (4.0 * (C2.w_IZ_Z - A2.w_IZ_Z) / h - (C.w_IZ_Z - A.w_IZ_Z) / (2 * h)) / 3.0;
      EXPECT_LT((w_fd - B.w_IZ_Z).norm(), 1e-9) << "trihedron " << i << " t " << t;
      EXPECT_LT((dw_fd - B.dw_IZ_Z).norm(), 1e-9) << "trihedron " << i << " t " << t;
      // Every trihedron has Z3 up and carries the same point: components are rotations of the inertial ones.
      EXPECT_LT((B.q_IZ * Vec3::UnitZ() - z.p_I.normalized()).norm(), 1e-12);
      EXPECT_LT((B.q_IZ * B.a_Z - z.a_I).norm(), 1e-9);
      EXPECT_LT((B.q_IZ * B.v_Z - z.v_I).norm(), 1e-9);
    }
  }
}

TEST(EarthVehicle, GeographicRatesAreMagnus1651) {
  const auto veh = manoeuvring();
  const double R = veh.earth().radius, W = veh.earth().rotation_rate;
  for (double t : kTimes) {
    const auto z = veh.sample(t);
    const double phi = z.latitude;
    const Vec3 expected(-z.v_north / R, z.v_east / R + W * std::cos(phi),
                        z.v_east / R * std::tan(phi) + W * std::sin(phi));
    EXPECT_LT((z.geographic.w_IZ_Z - expected).norm(), 1e-15) << t;
    EXPECT_NEAR(z.v_north, z.speed * std::cos(z.heading), 1e-9);
  }
}

TEST(EarthVehicle, DarbouxRelationsOfChelnokov24HoldForEveryTrihedron) {
  // w1 = R(q0' + p0 r0), w2 = −R(p0' − q0 r0), w3 = −R(p0² + q0²) for a point on a sphere, any Z with Z3 up.
  const auto veh = manoeuvring();
  const double R = veh.earth().radius;
  for (double t : kTimes) {
    const auto z = veh.sample(t);
    for (int i = 0; i < 4; ++i) {
      const Trihedron& Z = pick(z, i);
      const double p0 = Z.w_IZ_Z.x(), q0 = Z.w_IZ_Z.y(), r0 = Z.w_IZ_Z.z();
      const double dp0 = Z.dw_IZ_Z.x(), dq0 = Z.dw_IZ_Z.y();
      // |w| ~ 0.1 m/s², terms R·(rate)² are formed from rates good to 1e-16 relative: 1e-9 is generous.
      EXPECT_NEAR(Z.a_Z.x(), R * (dq0 + p0 * r0), 1e-9) << i;
      EXPECT_NEAR(Z.a_Z.y(), -R * (dp0 - q0 * r0), 1e-9) << i;
      EXPECT_NEAR(Z.a_Z.z(), -R * (p0 * p0 + q0 * q0), 1e-9) << i;
      EXPECT_NEAR(Z.v_Z.z(), 0.0, 1e-9);
    }
    // Azimuth-free: no vertical rate, ω = up × v_abs / R.  Natural Darboux: p0 = 0, q0 = |v_abs|/R.
    EXPECT_EQ(z.azimuth_free.w_IZ_Z.z(), 0.0);
    const Vec3 vF = z.azimuth_free.v_Z;
    EXPECT_LT((z.azimuth_free.w_IZ_Z - Vec3(-vF.y(), vF.x(), 0.0) / R).norm(), 1e-18);
    EXPECT_NEAR(z.darboux.w_IZ_Z.x(), 0.0, 1e-18);
    EXPECT_NEAR(z.darboux.w_IZ_Z.y(), z.v_I.norm() / R, 1e-18);
    EXPECT_NEAR(z.darboux.v_Z.x(), z.v_I.norm(), 1e-9);
  }
}

TEST(EarthVehicle, GreatCircleAlongTheEquatorIsUniform) {
  motion::EarthParams e;
  e.rotation_rate = 0.0;
  const motion::VehicleStart s{0.0, 0.0, 0.5 * kPi, 250.0};
  const motion::EarthVehicle<1> veh(e, s, nullptr, 0);
  const auto z = veh.sample_ns(3600 * kSecond);
  EXPECT_NEAR(z.longitude, 250.0 * 3600.0 / e.radius, 1e-15);
  EXPECT_NEAR(z.latitude, 0.0, 1e-15);
  EXPECT_NEAR(z.heading, 0.5 * kPi, 1e-12);
  EXPECT_NEAR(z.f_I.norm(), e.gravity - 250.0 * 250.0 / e.radius, 1e-12);
}

TEST(EarthVehicle, FullCoordinatedTurnClosesExactly) {
  // Constant body rate (0, v/R, −r) of the track frame: it returns to its start after 2π/sqrt(r² + v²/R²).
  motion::EarthParams e;
  const double v = 200.0, r = 0.03;
  const double period = 2 * kPi / std::hypot(r, v / e.radius);
  const auto dur = static_cast<std::int64_t>(std::llround(period * 1e9));
  const motion::ManoeuvreSegment seg[] = {{dur, r, 0.0}};
  const motion::VehicleStart s{0.7, -1.2, 2.0, v};
  const motion::EarthVehicle<1> veh(e, s, seg, 1);
  const auto a = veh.sample_ns(0), b = veh.sample_ns(dur);
  // Position is Earth-relative: compare latitude/longitude/heading. Rounding of the duration to 1 ns moves
  // the vehicle by ≤ v·0.5e-9 m.
  EXPECT_NEAR(b.latitude, a.latitude, 1e-12);
  EXPECT_NEAR(b.longitude, a.longitude, 1e-12);
  EXPECT_NEAR(b.heading, a.heading, 1e-9);
  EXPECT_NEAR(b.speed, v, 1e-12);
  // Half way the turn diameter 2v/r (flat-Earth approximation, curvature correction ~(v/(rR))² ~ 1e-6).
  const auto c = veh.sample(0.5 * period);
  const Vec3 d = c.p_I - veh.sample(0.5 * period).p_I;  // self-consistency of sample()
  EXPECT_EQ(d.norm(), 0.0);
  const Vec3 pa = Quat(Eigen::AngleAxisd(-e.rotation_rate * 0.0, Vec3::UnitZ())) * a.p_I;
  const Vec3 pc = Quat(Eigen::AngleAxisd(-e.rotation_rate * 0.5 * period, Vec3::UnitZ())) * c.p_I;
  EXPECT_NEAR((pc - pa).norm(), 2 * v / r, 2 * v / r * 1e-5);
}

TEST(EarthVehicle, SegmentCornersAreContinuousAndTickSamplingAgrees) {
  const auto veh = manoeuvring();
  std::int64_t corner = 0;
  const std::int64_t ends[] = {600, 900, 1300, 1500, 2000};
  for (std::int64_t end_s : ends) {
    corner = end_s * kSecond;
    const auto before = veh.sample_ns(corner - 1), at = veh.sample_ns(corner);
    EXPECT_LT((at.p_I - before.p_I).norm(), 1e-6);  // 1 ns at ≤ 500 m/s absolute speed
    EXPECT_LT(at.azimuth_free.q_IZ.angularDistance(before.azimuth_free.q_IZ), 1e-10);
    EXPECT_NEAR(at.speed, before.speed, 1e-8);
    const auto at_s = veh.sample(1e-9 * static_cast<double>(corner) + 1e-7);
    EXPECT_LT((at_s.p_I - at.p_I).norm(), 1e-4);
  }
  EXPECT_EQ(veh.end_ns(), 2000 * kSecond);
  EXPECT_NEAR(veh.sample(2000.0).speed, 90.0, 1e-9);
  EXPECT_NEAR(veh.sample(9000.0).speed, 90.0, 1e-9);  // cruise after the last segment
}

TEST(EarthVehicle, RefusesWhatItCannotFollow) {
  using V = motion::EarthVehicle<2>;
  motion::EarthParams e;
  const motion::VehicleStart s{0.1, 0.0, 0.0, 10.0};
  const motion::ManoeuvreSegment both[] = {{kSecond, 0.1, 0.1}};
  const motion::ManoeuvreSegment reverse[] = {{20 * kSecond, 0.0, -1.0}};
  const motion::ManoeuvreSegment zero[] = {{0, 0.0, 0.0}};
  const motion::ManoeuvreSegment three[] = {{kSecond, 0, 0}, {kSecond, 0, 0}, {kSecond, 0, 0}};
  EXPECT_NE(V::check(e, s, both, 1), nullptr);
  EXPECT_NE(V::check(e, s, reverse, 1), nullptr);
  EXPECT_NE(V::check(e, s, zero, 1), nullptr);
  EXPECT_NE(V::check(e, s, three, 3), nullptr);
  EXPECT_EQ(V::check(e, s, three, 2), nullptr);
  motion::EarthParams bad = e;
  bad.radius = -1.0;
  EXPECT_NE(V::check(bad, s, nullptr, 0), nullptr);
  bad = e;
  bad.gravity = std::nan("");
  EXPECT_NE(V::check(bad, s, nullptr, 0), nullptr);
  motion::VehicleStart pole = s;
  pole.latitude = 2.0;
  EXPECT_NE(V::check(e, pole, nullptr, 0), nullptr);
  // Constructed anyway with too many segments: clamped, memory-safe.
  const V clamped(e, s, three, 3);
  EXPECT_EQ(clamped.segment_count(), 2);
}

TEST(EarthVehicle, DarbouxUndefinedWhenAbsoluteVelocityVanishes) {
  motion::EarthParams e;
  // Flying due west at the Earth's surface speed: inertially at rest.
  const double phi = 0.5;
  const motion::VehicleStart s{phi, 0.0, -0.5 * kPi, e.rotation_rate * e.radius * std::cos(phi)};
  const motion::EarthVehicle<1> veh(e, s, nullptr, 0);
  const auto z = veh.sample(0.0);
  EXPECT_LT(z.v_I.norm(), 1e-9);
  EXPECT_FALSE(z.darboux_valid);
  EXPECT_TRUE(veh.sample(0.0).azimuth_free.w_IZ_Z.allFinite());
}

}  // namespace earth_vehicle_test
}  // namespace gyrostab
