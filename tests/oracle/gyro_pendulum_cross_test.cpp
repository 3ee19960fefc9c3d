// The same pendulum / gyro pendulum on the same manoeuvring pivot, computed three ways, must move the same:
// Magnus's small-angle (12.55)-(12.58) (sim/models/gyro_pendulum_magnus.hpp), Chelnokov's quaternion form
// (1.3)-(1.5) (sim/models/gyro_pendulum_quaternion.hpp), and the full 3-D Newton–Euler body
// (sim/models/schuler_pendulum.hpp). Tolerances come from what each form neglects (Magnus: O(tilt²), the
// pivot's centripetal term and the A|Ω|² frame terms — see gyro_pendulum_magnus.hpp) and from the steps.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/rotor_splitting.hpp"
#include "sim/models/gyro_pendulum_magnus.hpp"
#include "sim/models/gyro_pendulum_quaternion.hpp"
#include "sim/models/schuler_pendulum.hpp"
#include "sim/motion/earth_vehicle.hpp"
#include "sim/oracles/schuler_tuning.hpp"

namespace gyrostab {
namespace gyro_pendulum_cross_test {

using dynamics::Quat;
using dynamics::Vec3;
using Vehicle = motion::EarthVehicle<8>;
using Ref = motion::EarthReference<Vehicle>;
constexpr std::int64_t kS = 1'000'000'000;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

struct Gap {
  double tilt_max{0.0};
  double magnus_chelnokov{0.0};
  double magnus_body{0.0};
};

// H = 0, 10 % mistuned physical pendulum (A = 1.1 l m R, C = 0.5 l m R, gradient on) through speed changes and
// turns at ≤ 50 m/s, 3 h, RK4 at h = 1 s for all three forms.
Gap physical_pendulum(double omega_e) {
  motion::EarthParams e;
  e.rotation_rate = omega_e;
  const motion::ManoeuvreSegment seg[] = {{600 * kS, 0.0, 0.0},  {20 * kS, 0.0, 1.5},   {300 * kS, 0.02, 0.0},
                                          {1200 * kS, 0.0, 0.0}, {157 * kS, -0.02, 0.0}, {20 * kS, 0.0, -1.5}};
  const Vehicle veh(e, motion::VehicleStart{0.7, 0.0, 0.3, 20.0}, seg, 6);
  const Ref ref{&veh, motion::ReferenceTrihedron::kAzimuthFree};
  const double R = e.radius, ml = 0.5, A = 1.1 * ml * R, C = 0.5 * ml * R;
  models::GyroPendulumMagnusParams mp;
  mp.A = A;
  mp.C = C;
  mp.H = 0.0;
  mp.m = 1.0;
  mp.s = ml;
  mp.R = R;
  mp.g = e.gravity;
  using Magnus = models::GyroPendulumMagnus<Ref>;
  Magnus magnus(mp, ref);
  dynamics::Rk4<Magnus> rm(magnus);
  Magnus::State z = Magnus::make_state(0.0, 0.0);
  models::ChelnokovParams c;
  c.k = A;
  c.I3 = C;
  c.lm = ml;
  c.gravity_gradient = true;
  c.I1g = A;
  c.I3g = C;
  using Kappa = models::ChelnokovKappa<Ref>;
  Kappa kappa(c, ref);
  dynamics::Rk4<Kappa> rk(kappa);
  Kappa::State x = Kappa::aligned_state();
  models::SchulerPendulumParams bp;
  bp.inertia = Vec3(A, A, C);
  bp.ml = ml;
  using Body = models::SchulerPendulum<Ref>;
  Body body(bp, ref);
  dynamics::Rk4<Body> rb(body);
  Body::State xb = Body::aligned_state(ref(0.0));
  Gap gap;
  for (int i = 0; i < 10800; ++i) {
    const double t = i;
    magnus.reference().begin_step(t);
    kappa.reference().begin_step(t);
    body.reference().begin_step(t);
    rm.step(t, 1.0, z);
    rk.step(t, 1.0, x);
    rb.step(t, 1.0, xb);
    const Vec3 y3 = models::chelnokov::vertical(x.head<4>());
    const double a = std::atan2(-y3.y(), y3.z()), b = std::atan2(y3.x(), y3.z());
    double ab, bb;
    Body::magnus_angles(ref(t + 1.0), xb, ab, bb);
    gap.tilt_max = std::max(gap.tilt_max, std::hypot(a, b));
    gap.magnus_chelnokov = std::max(gap.magnus_chelnokov, std::hypot(a - z[0], b - z[1]));
    gap.magnus_body = std::max(gap.magnus_body, std::hypot(ab - a, bb - b));  // here: body vs Chelnokov
  }
  return gap;
}

TEST(GyroPendulumCross, PhysicalPendulumMagnusChelnokovAndBodyAgree) {
  // Non-rotating sphere: Magnus neglects |v|²/(gR) ≤ 4e-5 and O(θ²) ~ 5e-7 (θ ≤ 7e-4): tolerance 1e-4 of the
  // largest tilt (measured 2.6e-5). Chelnokov κ-form vs 3-D body: the same exact equations, RK4 at 1 s on
  // 40-min dynamics: 1e-9 of the tilt. Rotating Earth: the frame rates Ω ~ Ω_E cosφ add A|Ω|²/k ~ 2e-3 to
  // Magnus's neglect: tolerance 3e-3 of the tilt (measured 6.6e-4).
  const Gap still = physical_pendulum(0.0);
  RecordProperty("nonrotating_magnus_vs_chelnokov_rel", num(still.magnus_chelnokov / still.tilt_max));
  EXPECT_GT(still.tilt_max, 1e-4);  // the mistuned pendulum does swing
  EXPECT_LT(still.magnus_chelnokov, 1e-4 * still.tilt_max);
  EXPECT_LT(still.magnus_body, 1e-9 * still.tilt_max + 1e-15);
  const Gap turning = physical_pendulum(7.292115e-5);
  RecordProperty("rotating_magnus_vs_chelnokov_rel", num(turning.magnus_chelnokov / turning.tilt_max));
  EXPECT_LT(turning.magnus_chelnokov, 3e-3 * turning.tilt_max);
  EXPECT_LT(turning.magnus_body, 1e-9 * turning.tilt_max + 1e-15);
}

// Tuned reference gyro pendulum (m 5 kg, A 0.02, C 0.025, H 5, s of (12.66)) started on its velocity-error
// equilibrium z = −Hw/(kR); 1 h of manoeuvres; Magnus by the gyroscopic exponential, the 3-D body spinning at
// H/C by Strang splitting, both at h = 0.01 s (h ω^N = 2.5 rad).
struct GyroGap {
  double z_max{0.0};
  double gap{0.0};
};
GyroGap gyro_pendulum(double omega_e) {
  motion::EarthParams e;
  e.rotation_rate = omega_e;
  const motion::ManoeuvreSegment seg[] = {
      {600 * kS, 0.0, 0.0}, {50 * kS, 0.0, 0.2}, {600 * kS, 0.002, 0.0}, {600 * kS, 0.0, 0.0}};
  const Vehicle veh(e, motion::VehicleStart{0.7, 0.0, 0.3, 10.0}, seg, 4);
  const Ref ref{&veh, motion::ReferenceTrihedron::kAzimuthFree};
  models::GyroPendulumMagnusParams mp;
  mp.A = 0.02;
  mp.C = 0.025;
  mp.H = 5.0;
  mp.m = 5.0;
  mp.R = e.radius;
  mp.g = e.gravity;
  mp.s = oracles::tuned_gyro_pendulum_offset(mp.m, mp.A, mp.C, mp.H, mp.g, mp.R);
  using Magnus = models::GyroPendulumMagnus<Ref>;
  Magnus magnus(mp, ref);
  dynamics::GyroscopicExponential<Magnus> gx(magnus);
  const motion::SuspensionSample s0 = ref(0.0);
  const std::complex<double> ze =
      oracles::velocity_error(mp.H, mp.k(), mp.R, {s0.v_Z.x(), s0.v_Z.y()});
  const std::complex<double> dze = oracles::velocity_error(mp.H, mp.k(), mp.R, {s0.a_Z.x(), s0.a_Z.y()});
  Magnus::State z = Magnus::make_state(ze.real(), ze.imag(), dze.real(), dze.imag());
  models::SchulerPendulumParams bp;
  bp.inertia = Vec3(mp.A, mp.A, mp.C);
  bp.ml = mp.m * mp.s;
  using Body = models::SchulerPendulum<Ref>;
  Body body(bp, ref);
  dynamics::RotorStrang<Body> strang(body);
  // The case turned by α about F1, then β: axis 3 at (sinβ, −sinα cosβ, cosα cosβ) ≈ (β, −α, 1).
  const Quat tilt = Quat(Eigen::AngleAxisd(z[0], Vec3::UnitX())) * Quat(Eigen::AngleAxisd(z[1], Vec3::UnitY()));
  Body::State x = models::make_rigid_body_state(
      tilt.conjugate() * (s0.w_Z + Vec3(z[2], z[3], 0.0)) + Vec3(0.0, 0.0, mp.H / mp.C), s0.q_IZ * tilt);
  GyroGap out;
  const double h = 0.01;
  for (long i = 0; i < 360000; ++i) {
    const double t = static_cast<double>(i) * h;
    magnus.reference().begin_step(t);
    body.reference().begin_step(t);
    gx.step(t, h, z);
    strang.step(t, h, x);
    if ((i + 1) % 100 == 0) {
      double a, b;
      Body::magnus_angles(ref(t + h), x, a, b);
      out.gap = std::max(out.gap, std::hypot(a - z[0], b - z[1]));
      out.z_max = std::max(out.z_max, std::hypot(z[0], z[1]));
    }
  }
  return out;
}

TEST(GyroPendulumCross, TunedGyroPendulumMagnusAndSpinningBodyAgree) {
  // Non-rotating sphere (|z| ≤ 2.5e-3): measured 1.7e-7 rad at h = 0.01 s, 1.1e-8 at h = 0.002 s (∝ h²: the
  // splitting's and the exponential midpoint's step errors); small-angle terms θ³ ~ 2e-8. Tolerance 4e-7 rad.
  // Rotating Earth: the Earth's transport velocity puts the instrument at |z| ≈ 0.047 rad (the velocity error
  // −Hw/(kR), 2.7°): Magnus's O(θ²) ~ 1e-3 and |v|²/(gR) ~ 2e-3 relative: tolerance 1 % of |z| (measured 0.28 %).
  const GyroGap still = gyro_pendulum(0.0);
  RecordProperty("nonrotating_gap_rad", num(still.gap));
  EXPECT_LT(still.gap, 4e-7);
  const GyroGap turning = gyro_pendulum(7.292115e-5);
  RecordProperty("rotating_gap_rel", num(turning.gap / turning.z_max));
  EXPECT_GT(turning.z_max, 0.04);
  EXPECT_LT(turning.gap, 1e-2 * turning.z_max);
}

}  // namespace gyro_pendulum_cross_test
}  // namespace gyrostab
