// Suspension point on a Kepler ellipse (free flight in a central Newtonian field) — Chelnokov §4, the
// "Kepler motion of the suspension point" case (docs/models/gyro-pendulum.md, Kepler oracle): with gravity
// evaluated at O the apparent acceleration (specific force) a = w − g_grav is exactly zero, so a gyro
// pendulum hung at O obeys z'' + ¼Ω²z = 0 with constant Ω = |L|/k (4.1).
//
// Frames: I inertial (as in earth_vehicle.hpp: origin at the attracting centre); perifocal P (P1 to
// perigee, P3 along the orbit normal h = r × v); orbital trihedron O: O1 = transverse (along-track, in the
// orbit plane, ⟂ radius), O2 = orbit normal, O3 = radial up. O is a Darboux trihedron with Z3 up and no
// rotation about the vertical: ω_IO_O = (0, ν', 0), ν' = h/r² (the orbit's angular rate Ω_orbit(t)).
//   q_IP = Rz(Ω_node) Rx(i) Rz(ω_peri)
// Kepler: M = n t + M0, n = sqrt(GM/a³); M = E − e sinE (Newton, fixed ≤ 30 iterations, |ΔE| < 1e-15);
//   r = a (1 − e cosE),  p_P = (a(cosE − e), b sinE, 0),  v_P = sqrt(GM a)/r · (−sinE, sqrt(1−e²) cosE, 0)
//   a_I = −GM p/r³,  h = sqrt(GM a (1 − e²)),  ν' = h/r²,  ν'' = −2 h r'/r³,  r' = (p·v)/r.
// Parameters: GM [m³/s²] > 0, a [m] > 0, 0 ≤ e < 1 (parabolic and hyperbolic flight are not provided),
// angles [rad]. Stateless, allocation-free, deterministic. Test: tests/unit/kepler_orbit_test.cpp
// (differences of position and attitude; energy and angular momentum; period).
// Docs: docs/models/suspension-motion.md#kepler-orbit
#pragma once

#include <cmath>
#include <numbers>

#include "sim/dynamics/quaternion.hpp"
#include "sim/motion/earth_vehicle.hpp"

namespace gyrostab::motion {

struct KeplerOrbitParams {
  double gm{3.986004418e14};        // GM [m³/s²]
  double semi_major_axis{7.0e6};    // a [m]
  double eccentricity{0.0};         // e [-], 0 ≤ e < 1
  double inclination{0.0};          // i [rad]
  double node{0.0};                 // Ω_node, right ascension of the ascending node [rad]
  double perigee{0.0};              // ω_peri, argument of perigee [rad]
  double mean_anomaly0{0.0};        // M0 at t = 0 [rad]

  double mean_motion() const { return std::sqrt(gm / (semi_major_axis * semi_major_axis * semi_major_axis)); }
  double period() const { return 2.0 * std::numbers::pi / mean_motion(); }  // [s]

  static const char* check(const KeplerOrbitParams& p) {
    if (!(std::isfinite(p.gm) && p.gm > 0.0)) return "orbit GM must be finite and > 0";
    if (!(std::isfinite(p.semi_major_axis) && p.semi_major_axis > 0.0))
      return "orbit semi-major axis must be finite and > 0";
    if (!(std::isfinite(p.eccentricity) && p.eccentricity >= 0.0 && p.eccentricity < 1.0))
      return "orbit eccentricity must be in [0, 1) (elliptic orbits only)";
    if (!std::isfinite(p.inclination) || !std::isfinite(p.node) || !std::isfinite(p.perigee) ||
        !std::isfinite(p.mean_anomaly0))
      return "orbit angles must be finite";
    return nullptr;
  }
};

struct KeplerSample {
  double t{0.0};                                 // [s]
  double eccentric_anomaly{0.0};                 // E [rad]
  double radius{0.0};                            // r [m]
  double orbit_rate{0.0};                        // ν' = Ω_orbit [rad/s]
  double orbit_rate_dot{0.0};                    // ν'' [rad/s²]
  dynamics::Vec3 p_I{dynamics::Vec3::Zero()};    // [m]
  dynamics::Vec3 v_I{dynamics::Vec3::Zero()};    // [m/s]
  dynamics::Vec3 a_I{dynamics::Vec3::Zero()};    // absolute acceleration = Newtonian gravity at O [m/s²]
  dynamics::Vec3 g_I{dynamics::Vec3::Zero()};    // gravity at O (= a_I) [m/s²]
  dynamics::Vec3 f_I{dynamics::Vec3::Zero()};    // specific force a − g ≡ 0 [m/s²]
  Trihedron orbital;                             // O (see header)
};

class KeplerOrbit {
 public:
  using Vec3 = dynamics::Vec3;
  using Quat = dynamics::Quat;

  KeplerOrbit() : KeplerOrbit(KeplerOrbitParams{}) {}
  // Unchecked parameters are clamped to something finite; call check() first for a message.
  explicit KeplerOrbit(const KeplerOrbitParams& p) : p_(p) {
    if (!(p_.eccentricity >= 0.0 && p_.eccentricity < 1.0)) p_.eccentricity = 0.0;
    if (!(p_.semi_major_axis > 0.0)) p_.semi_major_axis = 1.0;
    if (!(p_.gm > 0.0)) p_.gm = 1.0;
    q_IP_ = Quat(Eigen::AngleAxisd(p_.node, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(p_.inclination, Vec3::UnitX())) *
            Quat(Eigen::AngleAxisd(p_.perigee, Vec3::UnitZ()));
    n_ = p_.mean_motion();
    b_ = p_.semi_major_axis * std::sqrt(1.0 - p_.eccentricity * p_.eccentricity);
    h_ = std::sqrt(p_.gm * p_.semi_major_axis * (1.0 - p_.eccentricity * p_.eccentricity));
  }

  const KeplerOrbitParams& params() const { return p_; }
  double angular_momentum() const { return h_; }  // specific h [m²/s]

  KeplerSample sample(double t) const {
    const double e = p_.eccentricity, a = p_.semi_major_axis;
    const double M = std::remainder(n_ * t + p_.mean_anomaly0, 2.0 * std::numbers::pi);
    double E = e < 0.8 ? M + e * std::sin(M) : (M >= 0.0 ? std::numbers::pi : -std::numbers::pi);
    for (int i = 0; i < 30; ++i) {
      const double dE = (E - e * std::sin(E) - M) / (1.0 - e * std::cos(E));
      E -= dE;
      if (std::abs(dE) < 1e-15) break;
    }
    const double sE = std::sin(E), cE = std::cos(E);
    const double r = a * (1.0 - e * cE);
    const Vec3 p_P(a * (cE - e), b_ * sE, 0.0);
    const Vec3 v_P = (std::sqrt(p_.gm * a) / r) * Vec3(-sE, (b_ / a) * cE, 0.0);

    KeplerSample s;
    s.t = t;
    s.eccentric_anomaly = E;
    s.radius = r;
    s.p_I = q_IP_ * p_P;
    s.v_I = q_IP_ * v_P;
    s.a_I = -p_.gm / (r * r * r) * s.p_I;
    s.g_I = s.a_I;
    s.f_I = Vec3::Zero();
    const double rdot = p_P.dot(v_P) / r;
    s.orbit_rate = h_ / (r * r);
    s.orbit_rate_dot = -2.0 * h_ * rdot / (r * r * r);

    // Orbital trihedron: columns (transverse, normal, radial) in P.
    const Vec3 up_P = p_P / r;
    const Vec3 n_P = Vec3::UnitZ();
    const Vec3 tr_P = n_P.cross(up_P);
    Eigen::Matrix3d C_PO;
    C_PO.col(0) = tr_P;
    C_PO.col(1) = n_P;
    C_PO.col(2) = up_P;
    const Quat q_PO(C_PO);
    const Quat q_OI = (q_IP_ * q_PO).conjugate();
    Trihedron& O = s.orbital;
    O.q_IZ = q_IP_ * q_PO;
    O.w_IZ_Z = Vec3(0.0, s.orbit_rate, 0.0);
    O.dw_IZ_Z = Vec3(0.0, s.orbit_rate_dot, 0.0);
    O.v_Z = q_OI * s.v_I;
    O.a_Z = q_OI * s.a_I;
    O.f_Z = Vec3::Zero();
    return s;
  }

 private:
  KeplerOrbitParams p_{};
  Quat q_IP_{Quat::Identity()};
  double n_{0.0}, b_{0.0}, h_{0.0};
};

}  // namespace gyrostab::motion
