// Suspension-point motion over a rotating spherical Earth: a vehicle at altitude 0 driven by a manoeuvre
// sequence (great-circle legs, coordinated turns, along-track acceleration), sampled at any time with the
// absolute kinematics a gyro instrument needs (Magnus 12.3.3 (12.52)-(12.58), 13.3, 16.4.4 (16.51);
// Chelnokov §1-§2 (1.6)-(1.7), (2.4)-(2.7); docs/models/suspension-motion.md).
//
// Frames (all right-handed; "x_A" = components of x in frame A; q_AB rotates B components into A: x_A = q_AB x_B)
//   I  inertial, origin at the Earth's centre, I3 = Earth's spin axis (north), I1 through Greenwich at t = 0.
//   E  Earth-fixed: E = I turned by Ω_E t about I3.  Latitude φ, longitude λ are geocentric, in E.
//   G  geographic trihedron ENU: G1 east, G2 north, G3 up (geocentric vertical) — Magnus 16.4.4 (east-north-
//      zenith), and any "3 up, 1-2 horizontal" frame of Magnus 12.3.3 / Chelnokov's Z (Z3 up).
//      ω_IG_G = (−v_N/R, v_E/R + Ω_E cosφ, (v_E/R) tanφ + Ω_E sinφ)  = Magnus (16.51).  Undefined AT a pole.
//   T  track trihedron: T1 = ground-track direction (velocity relative to Earth), T2 = left, T3 = up.
//      ω_ET_T = (0, v/R, −r).  Regular everywhere (the generator propagates T, not φ/λ/ψ).
//   F  azimuth-free trihedron (Chelnokov (2.5), Magnus (12.52) with Ω3 = 0): F3 = up, no absolute rotation
//      about the vertical: ω_IF_F = (p0, q0, 0) = (up × v_abs / R)_F.  F = G at t = 0; afterwards F turns
//      relative to T by ζ, ζ' = r − Ω_E sinφ (integrated in closed form per segment).  In F, Magnus's
//      w = v1 + i v2 (12.56) is (v_abs_F1 + i v_abs_F2) and its derivative is (a_abs_F1 + i a_abs_F2).
//   D  natural Darboux trihedron (Chelnokov (2.7)): D1 along the ABSOLUTE velocity v_abs (horizontal), D3 up:
//      ω_ID_D = (0, |v_abs|/R, r0), r0 = (a_abs·D2)/|v_abs| = |v_abs|/ρ.  Undefined when v_abs = 0 (a vehicle
//      at rest at a pole, or flying west at Ω_E R cosφ): then `darboux_valid` is false and D is set to T.
//
// Vehicle kinematics relative to the Earth (state = q_ET, speed v; altitude 0, radius R):
//   p' = (v/R) u,  u' = −(v/R) p + r (u × p),  v' = a        (p = up, u = T1, both unit vectors in E)
// so T rotates with constant body rate (0, v/R, −r) when a = 0 (a small circle: exact rotation), and about
// T2 by θ = (v0 τ + a τ²/2)/R when r = 0 (a great circle: exact).  A segment that turns AND accelerates is
// refused (check()): it has no closed form and is not needed by the book's cases.  r > 0 turns right
// (heading ψ, clockwise from north, increases); r is relative to the great circle, so r = 0 is a geodesic
// (heading drifts by (v/R) sinψ tanφ as meridians converge); loxodromes are not provided.
// After the last segment the vehicle cruises on a great circle at its final speed.
//
// Outputs (EarthVehicleSample): position, Earth-relative velocity (v_N, v_E), absolute velocity and
// acceleration a_abs = a_rel + 2Ω_E×v_rel + Ω_E×(Ω_E×r), Newtonian gravity g_grav = −g up (g = GM/R², the
// attraction only; the plumb-line g also contains −Ω_E×(Ω_E×r)), specific force f = a_abs − g_grav
// (Chelnokov's apparent acceleration a = w − g (1.9)), and for each trihedron Z ∈ {G, T, F, D}: q_IZ, ω_IZ_Z,
// d/dt(ω_IZ_Z) (derivative of the Z components, Chelnokov's ω°_Z'), and v_abs, a_abs, f in Z axes.
//
// Units: m, s, rad, m/s, m/s², rad/s, rad/s².  Time: segments in integer ns; sample(t) in s (RK stage times)
// and sample_ns(tick) agree to rounding at whole ns (segment boundaries are compared in integer ns).  Allocation-free, deterministic; a sample costs
// ~40 trig calls (+ 8 per 0.5 rad of arc for an accelerating great-circle leg, Gauss-Legendre for ∫ sinφ).
// Test: tests/unit/earth_vehicle_test.cpp (finite differences of positions and quaternions against the
// analytic velocities, accelerations and angular velocities; (16.51); Darboux relations of Chelnokov §2.4).
// Docs: docs/models/suspension-motion.md#vehicle-over-the-rotating-earth
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::motion {

struct EarthParams {
  double radius{6.371e6};            // R [m]
  double gravity{9.81};              // g = GM/R², Newtonian attraction at the surface [m/s²]
  double rotation_rate{7.292115e-5}; // Ω_E [rad/s] (0 = non-rotating sphere, Chelnokov §2)

  double gm() const { return gravity * radius * radius; }  // [m³/s²]
  double schuler_rate() const { return std::sqrt(gravity / radius); }  // ω_S [rad/s]

  static const char* check(const EarthParams& p) {
    if (!(std::isfinite(p.radius) && p.radius > 0.0)) return "earth radius must be finite and > 0";
    if (!(std::isfinite(p.gravity) && p.gravity > 0.0)) return "earth gravity must be finite and > 0";
    if (!std::isfinite(p.rotation_rate) || std::abs(p.rotation_rate) > 1e-2)
      return "earth rotation rate must be finite with |rate| <= 1e-2 rad/s";
    return nullptr;
  }
};

struct VehicleStart {
  double latitude{0.0};   // φ0 [rad], |φ0| <= π/2
  double longitude{0.0};  // λ0 [rad] (Earth-fixed)
  double heading{0.0};    // ψ0 [rad], clockwise from north (π/2 = east)
  double speed{0.0};      // v0 [m/s] ground speed, >= 0
};

struct ManoeuvreSegment {
  std::int64_t duration_ns{0};  // > 0 [ns]
  double turn_rate{0.0};        // r [rad/s], > 0 right, relative to the great circle
  double acceleration{0.0};     // a [m/s²] along track
};

// One reference trihedron Z at one instant.
struct Trihedron {
  dynamics::Quat q_IZ{dynamics::Quat::Identity()};   // x_I = q_IZ x_Z
  dynamics::Vec3 w_IZ_Z{dynamics::Vec3::Zero()};      // absolute angular velocity, Z axes [rad/s]
  dynamics::Vec3 dw_IZ_Z{dynamics::Vec3::Zero()};     // d/dt of the Z components of ω_IZ [rad/s²]
  dynamics::Vec3 v_Z{dynamics::Vec3::Zero()};         // absolute velocity of O [m/s]
  dynamics::Vec3 a_Z{dynamics::Vec3::Zero()};         // absolute acceleration of O (Chelnokov w_Z) [m/s²]
  dynamics::Vec3 f_Z{dynamics::Vec3::Zero()};         // specific force a_abs − g_grav (Chelnokov a_Z) [m/s²]
};

struct EarthVehicleSample {
  double t{0.0};                   // [s]
  double latitude{0.0};            // φ [rad]
  double longitude{0.0};           // λ [rad], Earth-fixed, in (−π, π]
  double heading{0.0};             // ψ [rad], clockwise from north, in (−π, π]
  double speed{0.0};               // v [m/s], relative to the Earth
  double v_north{0.0}, v_east{0.0};  // [m/s], relative to the Earth
  double turn_rate{0.0};           // r [rad/s] of the active segment
  double acceleration{0.0};        // a [m/s²] of the active segment
  dynamics::Vec3 p_I{dynamics::Vec3::Zero()};  // position of O [m]
  dynamics::Vec3 v_I{dynamics::Vec3::Zero()};  // absolute velocity [m/s]
  dynamics::Vec3 a_I{dynamics::Vec3::Zero()};  // absolute acceleration [m/s²]
  dynamics::Vec3 g_I{dynamics::Vec3::Zero()};  // Newtonian gravity −g up [m/s²]
  dynamics::Vec3 f_I{dynamics::Vec3::Zero()};  // specific force a_abs − g_grav [m/s²]
  Trihedron geographic;    // G (ENU); rates undefined at a pole
  Trihedron track;         // T
  Trihedron azimuth_free;  // F
  Trihedron darboux;       // D (natural, built on v_abs)
  bool darboux_valid{false};
};

template <int kMaxSegments = 32>
class EarthVehicle {
 public:
  using Vec3 = dynamics::Vec3;
  using Quat = dynamics::Quat;
  static constexpr int kCapacity = kMaxSegments;

  // Refuses what the generator cannot follow exactly; nullptr = fine.
  static const char* check(const EarthParams& earth, const VehicleStart& start, const ManoeuvreSegment* segments,
                           int count) {
    if (const char* e = EarthParams::check(earth)) return e;
    if (!(std::isfinite(start.latitude) && std::abs(start.latitude) <= 0.5 * std::numbers::pi))
      return "vehicle latitude must be finite and within [-pi/2, pi/2]";
    if (!std::isfinite(start.longitude) || !std::isfinite(start.heading))
      return "vehicle longitude and heading must be finite";
    if (!(std::isfinite(start.speed) && start.speed >= 0.0)) return "vehicle speed must be finite and >= 0";
    if (count < 0 || count > kMaxSegments) return "too many manoeuvre segments (capacity kMaxSegments)";
    if (count > 0 && segments == nullptr) return "manoeuvre segments missing";
    double v = start.speed, v_max = start.speed;
    for (int k = 0; k < count; ++k) {
      const ManoeuvreSegment& s = segments[k];
      if (s.duration_ns <= 0) return "manoeuvre segment duration must be > 0";
      if (!std::isfinite(s.turn_rate) || !std::isfinite(s.acceleration))
        return "manoeuvre turn rate and acceleration must be finite";
      if (s.turn_rate != 0.0 && s.acceleration != 0.0)
        return "a manoeuvre segment may turn or accelerate, not both (split it in two)";
      v += s.acceleration * (static_cast<double>(s.duration_ns) / 1e9);
      v_max = std::max(v_max, v);
      // Rounding of a deceleration to exactly 0 (e.g. 230 − 2·115) is not a reversal.
      if (v < -1e-9 * std::max(1.0, v_max)) return "manoeuvre sequence drives the ground speed below zero";
    }
    return nullptr;
  }

  EarthVehicle() : EarthVehicle(EarthParams{}, VehicleStart{}, nullptr, 0) {}

  // Unchecked input is clamped into something memory-safe; call check() first to get a message.
  EarthVehicle(const EarthParams& earth, const VehicleStart& start, const ManoeuvreSegment* segments, int count)
      : earth_(earth) {
    count_ = (segments == nullptr || count < 0) ? 0 : (count > kMaxSegments ? kMaxSegments : count);
    const double cphi = std::cos(start.latitude), sphi = std::sin(start.latitude);
    const double clam = std::cos(start.longitude), slam = std::sin(start.longitude);
    Eigen::Matrix3d C_EG;
    C_EG.col(0) = Vec3(-slam, clam, 0.0);
    C_EG.col(1) = Vec3(-sphi * clam, -sphi * slam, cphi);
    C_EG.col(2) = Vec3(cphi * clam, cphi * slam, sphi);
    const Quat q_EG(C_EG);
    const double half = 0.5 * std::numbers::pi;
    Leg leg;
    leg.t0_ns = 0;
    leg.q_ET0 = (q_EG * Quat(Eigen::AngleAxisd(half - start.heading, Vec3::UnitZ()))).normalized();
    leg.v0 = start.speed;
    leg.zeta0 = start.heading - half;  // F = G at t = 0
    for (int k = 0; k < count_; ++k) {
      leg.r = segments[k].turn_rate;
      leg.a = segments[k].acceleration;
      legs_[k] = leg;
      const std::int64_t d = segments[k].duration_ns;
      const double tau = static_cast<double>(d) / 1e9;
      Quat q_ET;
      double v, zeta;
      propagate(legs_[k], tau, q_ET, v, zeta);
      leg.t0_ns = legs_[k].t0_ns + d;
      leg.q_ET0 = q_ET.normalized();
      leg.v0 = v < 0.0 ? 0.0 : v;
      leg.zeta0 = std::remainder(zeta, 2.0 * std::numbers::pi);
    }
    leg.r = 0.0;
    leg.a = 0.0;
    legs_[count_] = leg;  // cruise
  }

  const EarthParams& earth() const { return earth_; }
  int segment_count() const { return count_; }
  std::int64_t end_ns() const { return legs_[count_].t0_ns; }  // start of the final cruise

  EarthVehicleSample sample_ns(std::int64_t t_ns) const {
    int k = 0;
    while (k < count_ && t_ns >= legs_[k + 1].t0_ns) ++k;
    return evaluate(k, static_cast<double>(t_ns - legs_[k].t0_ns) / 1e9, static_cast<double>(t_ns) / 1e9);
  }

  // t [s]; before 0 the first segment is extrapolated backwards (defined, but not a manoeuvre).
  EarthVehicleSample sample(double t) const { return sample_in_segment(segment_at(t), t); }

  // Index of the segment that contains t (count = the final cruise); a corner belongs to the later one.
  // t is rounded to whole ns first: a step time computed as 1e-9 × tick_ns may sit an ulp below a corner,
  // and must not put the whole next step into the ending segment.
  int segment_at(double t) const {
    const double t_ns_d = std::clamp(t * 1e9, -9.0e18, 9.0e18);
    const auto t_ns = static_cast<std::int64_t>(std::llround(t_ns_d));
    int k = 0;
    while (k < count_ && t_ns >= legs_[k + 1].t0_ns) ++k;
    return k;
  }
  // Segment k's closed form at t, also outside its span: the left limit at a corner is
  // sample_in_segment(k, t_corner) with k the segment that ends there. An integrator step [t, t + h] whose
  // end is a corner must see the left limit at t + h (the accelerations jump there): sample within
  // segment_at(t) for all its stages (EarthReference::begin_step) — else RK4 makes an O(h·Δa) error.
  EarthVehicleSample sample_in_segment(int k, double t) const {
    k = k < 0 ? 0 : (k > count_ ? count_ : k);
    return evaluate(k, t - static_cast<double>(legs_[k].t0_ns) / 1e9, t);
  }
  // Left limit at t_ns (= sample_ns away from corners).
  EarthVehicleSample sample_left_ns(std::int64_t t_ns) const {
    int k = 0;
    while (k < count_ && t_ns > legs_[k + 1].t0_ns) ++k;
    return evaluate(k, static_cast<double>(t_ns - legs_[k].t0_ns) / 1e9, static_cast<double>(t_ns) / 1e9);
  }

 private:
  struct Leg {
    std::int64_t t0_ns{0};
    Quat q_ET0{Quat::Identity()};
    double v0{0.0};
    double zeta0{0.0};
    double r{0.0};
    double a{0.0};
  };

  // Series-safe sin(x)/x, (1 − cos x)/x, (x − sin x)/x².
  static double sinc(double x) { return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }
  static double cosc(double x) {
    return std::abs(x) < 1e-4 ? 0.5 * x * (1.0 - x * x / 12.0) : (1.0 - std::cos(x)) / x;
  }
  static double sinc3(double x) {
    const double x2 = x * x;
    return std::abs(x) < 1e-2 ? x * (1.0 / 6.0 - x2 / 120.0 + x2 * x2 / 5040.0) : (x - std::sin(x)) / x2;
  }

  // q_ET, v and the azimuth-free angle ζ at time τ into leg L. ζ' = r − Ω_E sinφ, sinφ = (q_ET e3)·ẑ_E.
  void propagate(const Leg& L, double tau, Quat& q_ET, double& v, double& zeta) const {
    const double R = earth_.radius;
    const Vec3 z_T0 = L.q_ET0.conjugate() * Vec3::UnitZ();  // Earth axis in T(τ=0) axes
    v = L.v0 + L.a * tau;
    Vec3 integral_p_T0;  // ∫0^τ up dτ', in T(0) axes
    if (L.a == 0.0) {
      const Vec3 w_b(0.0, L.v0 / R, -L.r);
      const double w = w_b.norm();
      const double x = w * tau;
      if (w > 0.0) {
        const Vec3 k = w_b / w;
        q_ET = L.q_ET0 * Quat(Eigen::AngleAxisd(x, k));
        integral_p_T0 = tau * (Vec3::UnitZ() * sinc(x) + k.cross(Vec3::UnitZ()) * cosc(x) + k * (k.z() * x * sinc3(x)));
      } else {
        q_ET = L.q_ET0;
        integral_p_T0 = tau * Vec3::UnitZ();
      }
    } else {
      const double theta = (L.v0 * tau + 0.5 * L.a * tau * tau) / R;
      q_ET = L.q_ET0 * Quat(Eigen::AngleAxisd(theta, Vec3::UnitY()));
      // ∫ (sinθ, 0, cosθ) dτ' by composite 8-point Gauss-Legendre, ≤ 0.5 rad of arc per panel:
      // error ≲ (0.25)^16/16! — far below rounding.
      const int panels = 1 + static_cast<int>(std::abs(theta) / 0.5);
      const double h = tau / panels;
      double s_sum = 0.0, c_sum = 0.0;
      for (int j = 0; j < panels; ++j) {
        const double mid = (j + 0.5) * h;
        for (int i = 0; i < 8; ++i) {
          const double tt = mid + 0.5 * h * kGaussNodes[i];
          const double th = (L.v0 * tt + 0.5 * L.a * tt * tt) / R;
          s_sum += kGaussWeights[i] * std::sin(th);
          c_sum += kGaussWeights[i] * std::cos(th);
        }
      }
      integral_p_T0 = Vec3(0.5 * h * s_sum, 0.0, 0.5 * h * c_sum);
    }
    zeta = L.zeta0 + L.r * tau - earth_.rotation_rate * z_T0.dot(integral_p_T0);
  }

  EarthVehicleSample evaluate(int k, double tau, double t) const {
    const Leg& L = legs_[k];
    const double R = earth_.radius, W = earth_.rotation_rate, g = earth_.gravity;
    Quat q_ET;
    double v, zeta;
    propagate(L, tau, q_ET, v, zeta);
    const double a = L.a, r = L.r;

    EarthVehicleSample s;
    s.t = t;
    s.speed = v;
    s.turn_rate = r;
    s.acceleration = a;

    // --- Track trihedron T: everything below is in T axes first.
    const Vec3 z_T = q_ET.conjugate() * Vec3::UnitZ();  // Earth axis ẑ_E in T axes; z_T.z() = sinφ
    const Vec3 w_ET(0.0, v / R, -r);
    const Vec3 dz_T = -w_ET.cross(z_T);
    const Vec3 Om = W * z_T, dOm = W * dz_T;
    const Vec3 r_T(0.0, 0.0, R);
    const Vec3 vrel(v, 0.0, 0.0);
    const Vec3 w_IT = w_ET + Om;
    const Vec3 dw_IT = Vec3(0.0, a / R, 0.0) + dOm;
    const Vec3 v_T = vrel + Om.cross(r_T);
    const Vec3 arel(a, -r * v, -v * v / R);
    const Vec3 a_T = arel + 2.0 * Om.cross(vrel) + Om.cross(Om.cross(r_T));
    const Vec3 g_T(0.0, 0.0, -g);
    const Vec3 f_T = a_T - g_T;
    // d/dt of the T components of a_abs (for the Darboux r0'), piecewise-constant a and r.
    const Vec3 darel(0.0, -r * a, -2.0 * v * a / R);
    const Vec3 da_T = darel + 2.0 * (dOm.cross(vrel) + Om.cross(Vec3(a, 0.0, 0.0))) +
                      dOm.cross(Om.cross(r_T)) + Om.cross(dOm.cross(r_T));

    const Quat q_IE(Eigen::AngleAxisd(W * t, Vec3::UnitZ()));
    const Quat q_IT = q_IE * q_ET;
    fill(s.track, q_IT, w_IT, dw_IT, v_T, a_T, f_T);
    s.p_I = q_IT * r_T;
    s.v_I = q_IT * v_T;
    s.a_I = q_IT * a_T;
    s.g_I = q_IT * g_T;
    s.f_I = q_IT * f_T;

    // --- Geographic G (ENU) from the position and the track direction.
    const Vec3 p_E = q_ET * Vec3::UnitZ(), u_E = q_ET * Vec3::UnitX();
    const double sphi = std::clamp(p_E.z(), -1.0, 1.0);
    const double cphi = std::hypot(p_E.x(), p_E.y());
    s.latitude = std::atan2(p_E.z(), cphi);
    s.longitude = std::atan2(p_E.y(), p_E.x());
    const double clam = std::cos(s.longitude), slam = std::sin(s.longitude);
    const Vec3 e_E(-slam, clam, 0.0), n_E(-sphi * clam, -sphi * slam, cphi);
    const double ce = u_E.dot(e_E), cn = u_E.dot(n_E);
    s.heading = std::atan2(ce, cn);
    s.v_north = v * cn;
    s.v_east = v * ce;
    {
      // G = T turned about up by (ψ − π/2):  x_G = Rz(π/2 − ψ) x_T.
      const double psi = s.heading;
      const double tanphi = sphi / cphi;  // ±inf at a pole: rates there are undefined (documented)
      const double dpsi = r + (v / R) * std::sin(psi) * tanphi;
      const double vN = s.v_north, vE = s.v_east, dphi = vN / R;
      const double dvN = a * std::cos(psi) - vE * dpsi, dvE = a * std::sin(psi) + vN * dpsi;
      const Vec3 w_IG(-vN / R, vE / R + W * cphi, vE * tanphi / R + W * sphi);
      const Vec3 dw_IG(-dvN / R, dvE / R - W * sphi * dphi,
                       (dvE * tanphi + vE * dphi / (cphi * cphi)) / R + W * cphi * dphi);
      const Quat q_TG(Eigen::AngleAxisd(psi - 0.5 * std::numbers::pi, Vec3::UnitZ()));
      const Quat q_GT = q_TG.conjugate();
      fill(s.geographic, q_IT * q_TG, w_IG, dw_IG, q_GT * v_T, q_GT * a_T, q_GT * f_T);
    }

    // --- Azimuth-free F = T turned about up by ζ;  ζ' = −(ω_IT)_3.
    {
      const double dzeta = -w_IT.z(), ddzeta = -dw_IT.z();
      const Quat q_TF(Eigen::AngleAxisd(zeta, Vec3::UnitZ()));
      const Quat q_FT = q_TF.conjugate();
      const Vec3 w_IF = q_FT * (w_IT + dzeta * Vec3::UnitZ());
      const Vec3 dw_IF = q_FT * (dw_IT + ddzeta * Vec3::UnitZ()) - Vec3(0.0, 0.0, dzeta).cross(w_IF);
      fill(s.azimuth_free, q_IT * q_TF, Vec3(w_IF.x(), w_IF.y(), 0.0), Vec3(dw_IF.x(), dw_IF.y(), 0.0),
           q_FT * v_T, q_FT * a_T, q_FT * f_T);
    }

    // --- Natural Darboux D = T turned about up by χ = atan2(v_T2, v_T1).
    {
      const double vh2 = v_T.x() * v_T.x() + v_T.y() * v_T.y();
      const double vscale = std::max(1.0, v) + std::abs(W) * R;
      s.darboux_valid = vh2 > 1e-18 * vscale * vscale;
      if (s.darboux_valid) {
        const Vec3 dv_T = a_T - w_IT.cross(v_T);
        const Vec3 ddv_T = da_T - dw_IT.cross(v_T) - w_IT.cross(dv_T);
        const double chi = std::atan2(v_T.y(), v_T.x());
        const double dchi = (v_T.x() * dv_T.y() - v_T.y() * dv_T.x()) / vh2;
        const double ddchi = (v_T.x() * ddv_T.y() - v_T.y() * ddv_T.x()) / vh2 -
                             2.0 * dchi * (v_T.x() * dv_T.x() + v_T.y() * dv_T.y()) / vh2;
        const Quat q_TD(Eigen::AngleAxisd(chi, Vec3::UnitZ()));
        const Quat q_DT = q_TD.conjugate();
        const Vec3 w_ID = q_DT * (w_IT + dchi * Vec3::UnitZ());
        const Vec3 dw_ID = q_DT * (dw_IT + ddchi * Vec3::UnitZ()) - Vec3(0.0, 0.0, dchi).cross(w_ID);
        fill(s.darboux, q_IT * q_TD, w_ID, dw_ID, q_DT * v_T, q_DT * a_T, q_DT * f_T);
      } else {
        s.darboux = s.track;
      }
    }
    return s;
  }

  static void fill(Trihedron& z, const Quat& q_IZ, const Vec3& w, const Vec3& dw, const Vec3& v_Z, const Vec3& a_Z,
                   const Vec3& f_Z) {
    z.q_IZ = q_IZ;
    z.w_IZ_Z = w;
    z.dw_IZ_Z = dw;
    z.v_Z = v_Z;
    z.a_Z = a_Z;
    z.f_Z = f_Z;
  }

  static constexpr std::array<double, 8> kGaussNodes{-0.9602898564975363, -0.7966664774136267,
                                                      -0.5255324099163290, -0.1834346424956498,
                                                      0.1834346424956498,  0.5255324099163290,
                                                      0.7966664774136267,  0.9602898564975363};
  static constexpr std::array<double, 8> kGaussWeights{0.1012285362903763, 0.2223810344533745,
                                                        0.3137066458778873, 0.3626837833783620,
                                                        0.3626837833783620, 0.3137066458778873,
                                                        0.2223810344533745, 0.1012285362903763};

  EarthParams earth_{};
  std::array<Leg, kMaxSegments + 1> legs_{};
  int count_{0};
};

}  // namespace gyrostab::motion
