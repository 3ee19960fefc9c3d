// The spatial (two-rotor) compass of Bauersfeld: a float sphere that shows the vertical AND north on any
// vehicle moving over the Earth — Magnus §13.4, (13.40)-(13.64).
//
// The instrument: a sphere with body axes a1, a2, a3 (a1 points down in the tuned state (13.58)), its centre
// of mass M at s along a1 from the support point A (mass m); two rotors of angular momentum H each, in cases
// that swing about axes parallel to a1 by −δ (rotor I) and +δ (rotor II), linked so that δ1 = δ2 = δ:
//   e^I = a3 sinδ − a2 cosδ,  e^II = a3 sinδ + a2 cosδ          (13.50)
// held by springs with the torque M^F = f sin 2δ (13.56); case inertia and damping neglected, the sphere's
// own inertia about its centre of mass neglected against the gyroscopic terms (the book's assumptions). A
// support force F^A makes A follow the vehicle (R^A from sim/motion/earth_vehicle.hpp, altitude 0).
// From the momentum balance (13.45)-(13.48) and the cases' equations (13.47)-(13.55), the sphere's motion
// reduces to its axis a1 (13.57)
//   a1 × [ (H²/f) a1'' + m s (R^M'' + g R^M/|R^M|) ] = 0,       R^M = R^A + s a1   (13.41)
// and the azimuth follows from the inertial rate of a1 (13.54): a1' = a2 M^F/(H cosδ) = (2 f sinδ/H) a2, so
//   a2 = a1'/|a1'|,  sinδ = H |a1'| / (2 f),  a3 = a1 × a2        (δ ≥ 0 taken; (−δ, −a2) is the same
//                                                                   sphere turned by 180° about a1)
// R^M'' is the centre of mass's acceleration and is kept exactly: R^M'' = R^A'' + s a1'', so the coefficient
// of a1'' is K = H²/f + m s². The book's tuning (13.60) H² = f m s |R^M| with |R^M| = R − s (A on the
// sphere of radius R, M below it) makes K = m s R, and then a1 = −R^A/R solves (13.57) exactly for ANY motion
// of A on that sphere (motion independence); perturbed, each tilt component swings with
// T = 2π sqrt(|R^M|/g) (13.63) — here exactly, the linearized restoring term being g R/(R − s).
// Gravity: the book's F^G = −m g R^M/|R^M| (13.43), g constant (the Newtonian attraction at the surface):
// the vertical the compass finds is the geocentric one.
//
// Frame: inertial I of earth_vehicle.hpp (origin at the Earth's centre). The ODE is integrated in I axes:
//   a1'' = −(m s/K) P(a1) [R^A'' + g R^M/|R^M|] − |a1'|² a1,     P(a1) = 1 − a1 a1ᵀ
// (the last term keeps a1·a1'' = −|a1'|², i.e. |a1| = 1 along the flow); project() renormalizes a1 and
// removes the radial part of a1' after every step (a correction of the order of the step's own error).
// State x = [a1 (3) (-), a1' (3) (1/s)] in I axes.
// Parameters (SI): H [N m s] (each rotor), f [N m], m [kg], s [m], g [m/s²].
// Support: any functor t → SupportSample {R^A, R^A''} in I axes [m, m/s²] with begin_step(t);
// VehicleSupport samples the vehicle generator exactly at every stage, within the segment that holds the
// step's start (a step ending on a manoeuvre corner sees the left limit there).
// Step: RK4. Along the tuned motion the right-hand side is a function of time, −up''(t), and RK4 errs by
// h⁵|up⁽⁵⁾|/720 in a1 and h⁵|up⁽⁶⁾|/2880 in a1' a step (Simpson), |up⁽ᵏ⁾| ≈ (v/R) r^(k−1) in a turn at rate r
// (a ship at 10 m/s turning at 3°/s: 1.6e-14 rad a 1-s step), powers of v/R or ω^E elsewhere; a rate error e
// becomes a Schuler swing of amplitude e/ω_S. The Schuler mode itself (ω_S h ≈ 1.2e-3 at h = 1 s) costs a
// relative phase error (ω_S h)⁴/120 ≈ 2e-14 a step.
// Docs: docs/models/bauersfeld-compass.md
// Oracle: tests/oracle/bauersfeld_compass_test.cpp
#pragma once

#include <cmath>
#include <limits>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

struct BauersfeldCompassParams {
  double H{5.0};         // angular momentum of each rotor [N m s]
  double f{6.0e-4};      // spring coefficient, M^F = f sin 2δ (13.56) [N m]
  double m{10.0};        // mass of the sphere [kg]
  double s{6.5e-4};      // centre of mass below the support point, along a1 [m]
  double gravity{9.81};  // g in F^G = −m g R^M/|R^M| (13.43) [m/s²]

  // Coefficient of a1'' in (13.57) with R^M'' = R^A'' + s a1'' [kg m²].
  double effective_inertia() const { return H * H / f + m * s * s; }

  const char* invalid_reason() const {
    const auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
    if (!pos(H)) return "H must be finite and > 0";
    if (!pos(f)) return "f must be finite and > 0";
    if (!pos(m)) return "m must be finite and > 0";
    if (!pos(s)) return "s must be finite and > 0 (the sphere must be pendulous)";
    if (!pos(gravity)) return "g must be finite and > 0";
    return nullptr;
  }
};

// (13.60): the spring that tunes the compass, f = H²/(m s |R^M|) [N m].
inline double bauersfeld_tuned_spring(double H, double m, double s, double radius_M) {
  return H * H / (m * s * radius_M);
}
// H²/(f m s |R^M|): 1 when tuned (13.60).
inline double bauersfeld_tuning_ratio(const BauersfeldCompassParams& p, double radius_M) {
  return p.H * p.H / (p.f * p.m * p.s * radius_M);
}

struct SupportSample {
  dynamics::Vec3 p_I{dynamics::Vec3::Zero()};  // R^A [m]
  dynamics::Vec3 a_I{dynamics::Vec3::Zero()};  // R^A'' [m/s²]
};

// The support point A on a vehicle of sim/motion/earth_vehicle.hpp, sampled exactly at each call. The
// segment is fixed per step (begin_step), the last sample cached (RK4 asks twice at the midpoint).
template <class Vehicle>
struct VehicleSupport {
  const Vehicle* vehicle{nullptr};
  int segment{-1};
  double cached_t{std::numeric_limits<double>::quiet_NaN()};
  SupportSample cached{};

  void begin_step(double t) {
    segment = vehicle->segment_at(t);
    cached_t = std::numeric_limits<double>::quiet_NaN();
  }
  SupportSample operator()(double t) {
    if (t == cached_t) return cached;
    const auto v = segment < 0 ? vehicle->sample(t) : vehicle->sample_in_segment(segment, t);
    cached = {v.p_I, v.a_I};
    cached_t = t;
    return cached;
  }
};

template <class Support>
class BauersfeldCompass {
 public:
  static constexpr int kStateSize = 6;
  using State = Eigen::Matrix<double, 6, 1>;
  using Vec3 = dynamics::Vec3;
  static constexpr const char* kName = "bauersfeld-compass";
  // The state's parts, by name: a1 and a1' (three components each, I axes).
  static constexpr int kAxis = 0, kAxisRate = 3;

  BauersfeldCompass(const BauersfeldCompassParams& p, const Support& support) : p_(p), support_(support) {}

  const BauersfeldCompassParams& params() const { return p_; }
  Support& support() { return support_; }
  const Support& support() const { return support_; }

  static State make_state(const Vec3& a1, const Vec3& a1_rate) {
    State x;
    x << a1, a1_rate;
    return x;
  }
  static Vec3 axis(const State& x) { return x.template segment<3>(kAxis); }
  static Vec3 axis_rate(const State& x) { return x.template segment<3>(kAxisRate); }

  // (13.64): a1 = −R^A/|R^A|, a1' = −(R^A/|R^A|)' for the support's position and velocity R^A, R^A' — the
  // start that does not swing — then a1 tilted by (θ_E, θ_N) toward east and north of the geographic
  // trihedron q_IG (a1 ∝ (tan θ_E, tan θ_N, −1) in G), its rate kept but for its part along the new a1.
  static State start_state(const Vec3& p_I, const Vec3& v_I, const dynamics::Quat& q_IG, double tilt_east,
                           double tilt_north) {
    const double r = p_I.norm();
    const Vec3 up = p_I / r;
    const Vec3 up_rate = (v_I - up.dot(v_I) * up) / r;
    const Vec3 a1 = q_IG * Vec3(std::tan(tilt_east), std::tan(tilt_north), -1.0).normalized();
    const Vec3 w = -up_rate;
    return make_state(a1, w - a1.dot(w) * a1);
  }

  // The step-start hook (sim/dynamics/step_start.hpp): the support's segment for the whole step.
  void begin_step(double t, double, State&) const { support_.begin_step(t); }

  void derivative(double t, const State& x, State& dx) const {
    const Vec3 a1 = axis(x), w = axis_rate(x);
    const SupportSample A = support_(t);
    dx.template segment<3>(kAxis) = w;
    dx.template segment<3>(kAxisRate) = acceleration(A, a1, w);
  }

  // a1'' of (13.57) for the support's state A.
  Vec3 acceleration(const SupportSample& A, const Vec3& a1, const Vec3& w) const {
    const double n2 = a1.squaredNorm();
    const Vec3 RM = A.p_I + p_.s * a1;
    const Vec3 F = A.a_I + (p_.gravity / RM.norm()) * RM;
    const Vec3 F_perp = F - (a1.dot(F) / n2) * a1;
    return -(p_.m * p_.s / p_.effective_inertia()) * F_perp - (w.squaredNorm() / n2) * a1;
  }

  void project(State& x) const {
    const Vec3 a1 = axis(x).normalized();
    const Vec3 w = axis_rate(x);
    x.template segment<3>(kAxis) = a1;
    x.template segment<3>(kAxisRate) = w - a1.dot(w) * a1;
  }

  // sin δ = H |a1'| / (2 f) (13.54), (13.56); > 1: the cases have no real swing for this rate.
  double sin_delta(const State& x) const { return p_.H * axis_rate(x).norm() / (2.0 * p_.f); }
  // δ [rad], π/2 where sin δ ≥ 1.
  double delta(const State& x) const { return std::asin(std::fmin(1.0, sin_delta(x))); }

  // The azimuth axis a2 = a1'/|a1'| (13.54); where a1' vanishes (a vehicle at rest on a non-rotating Earth)
  // the book's model leaves the azimuth free: the held a2, made orthogonal to a1.
  static Vec3 azimuth_axis(const State& x, const Vec3& a2_held) {
    const Vec3 a1 = axis(x), w = axis_rate(x);
    const double n = w.norm();
    if (n > kRestRate) return w / n;
    const Vec3 h = a2_held - a1.dot(a2_held) * a1;
    return h.norm() > 0.0 ? Vec3(h.normalized()) : a1.unitOrthogonal();
  }

  // Below this |a1'| the azimuth is held [rad/s] (1e-9 of the Earth's rate: a1' is never that small on a
  // rotating Earth except at a pole).
  static constexpr double kRestRate = 1e-13;

 private:
  BauersfeldCompassParams p_;
  mutable Support support_;
};

// The sphere read against the geographic trihedron G (ENU, earth_vehicle.hpp) [rad]:
//   tilt_east, tilt_north: a1 displaced from the geocentric down toward east / north,
//     atan2(a1·G1, −a1·G3), atan2(a1·G2, −a1·G3); tilt: the whole angle between a1 and down;
//   azimuth: a3 from north toward east, atan2(a3·G1, a3·G2) (the compass error);
//   roll, pitch, yaw: 3-2-1 angles of the sphere's axes (a3, −a2, a1) against north-east-down (yaw =
//   azimuth).
struct BauersfeldReading {
  double tilt_east{0.0}, tilt_north{0.0}, tilt{0.0}, azimuth{0.0};
  double roll{0.0}, pitch{0.0}, yaw{0.0};
};

inline BauersfeldReading bauersfeld_reading(const dynamics::Vec3& a1, const dynamics::Vec3& a2,
                                            const dynamics::Quat& q_IG) {
  const dynamics::Quat q_GI = q_IG.conjugate();
  const dynamics::Vec3 d = q_GI * a1, b = q_GI * a2, c = d.cross(b);  // a1, a2, a3 in G
  BauersfeldReading r;
  r.tilt_east = std::atan2(d.x(), -d.z());
  r.tilt_north = std::atan2(d.y(), -d.z());
  r.tilt = std::atan2(std::hypot(d.x(), d.y()), -d.z());
  r.azimuth = std::atan2(c.x(), c.y());
  // x_b = a3, y_b = −a2, z_b = a1 in NED (north, east, −up).
  r.yaw = r.azimuth;
  r.pitch = std::asin(std::fmax(-1.0, std::fmin(1.0, c.z())));
  r.roll = std::atan2(b.z(), -d.z());
  return r;
}

}  // namespace gyrostab::models
