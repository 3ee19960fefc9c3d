// Foucault's direction-finding gyros: a rotor of spin momentum H in a frame with ONE degree of freedom on an
// Earth-fixed base. Constrained to one axis, the rotor axis is pulled by the Earth's rotation toward
// "like-directed parallelism" with it: the declinometer finds the meridian, the inclinometer the Earth's axis.
//
// Book: Magnus, Kreisel §13.1, (13.1)-(13.4); its small-angle equation (13.5)-(13.6) in §13.2
// (docs/models/foucault-gyro.md). Earth-fixed axes: 1 up, 2 east, 3 north; Earth rate
// Ω = ω^E (sinφ, 0, cosφ) at latitude φ. The rotor, held on the frame, has the gyroscopic torque
//   (13.1)  M^KR = −Ω × H
// on the frame.
//   declinometer (Fig. 13.1): frame free about the vertical 1, rotor axis horizontal at azimuth α, positive
//     about the up axis (north toward WEST): a = (0, −sinα, cosα);
//     (13.2)  M^KR = (−H ω^E cosφ sinα,  H ω^E sinφ cosα,  H ω^E sinφ sinα): the directive torque M1 turns
//     the rotor axis into the meridian, α = 0 (M2, M3 are taken by the bearings).
//   inclinometer (Fig. 13.2): frame free about the east axis 2, rotor in the meridian plane at elevation ϑ
//     of its north end, positive about the east axis: a = (sinϑ, 0, cosϑ) (13.3); about the east axis
//     M2 = −H ω^E sin(ϑ − φ). The book prints (13.4) M2^KR = +H ω^E sin(ϑ − φ): the same torque with axis 2
//     taken the other way (west). Equilibrium ϑ = φ: the rotor axis parallel to the Earth's axis with H
//     like-directed to Ω (H > 0 points along the north end), stable; ϑ = φ ± π (unlike) is unstable.
// Exact one-degree-of-freedom equation (both kinds; derived in the docs page from Euler's law for frame +
// rotor, L = J'ω + H a, ω = Ω + x' n, n the free axis): the x' terms cancel along n and
//   J x'' = −n·[Ω × (J'Ω + H a)] − d x'
// which in the offset x = α (declinometer) or x = ϑ − φ (inclinometer) and the directive rate
// w = ω^E cosφ (declinometer) or w = ω^E (inclinometer) is
//   J x'' + d x' + H w sin x + (J_a − J_c) w² sin x cos x = 0.
// The last term is the centrifugal torque of the frame's own inertia in the rotating Earth (a body tends to
// turn its axis of largest inertia toward the rotation axis); it is (J_a − J_c) w/H ≈ 1e-6 of the directive
// torque for an instrument, and 0 when J_a = J_c. Small x: (13.5) A α'' + H ω^E cosφ α = 0, period (13.6).
//
// State x = [angle (rad), angle rate (rad/s)]: α, α' (declinometer) or ϑ, ϑ' (inclinometer), relative to
// the Earth.
// Parameters (SI): H spin momentum [N m s] (> 0); J frame + rotor about the free axis [kg m²]; J_a about the
// rotor axis, the frame only (the rotor's axial momentum is H) [kg m²]; J_c about the third axis (free axis
// × rotor axis) [kg m²]; d viscous damping on the free axis (oil, float) [N m s/rad]; earth_rate ω^E
// [rad/s]; latitude φ [rad].
// Assumptions: the spin motor holds the rotor's axial momentum H (absolute) constant (the book's H = const;
// holding the spin relative to the frame instead changes H by C ω^E cos(…) ≈ 1e-7 of it); the base is
// fixed to the Earth (no vehicle motion); frame and rotor rigid, balanced on the free axis (no pendulous
// torque: a single constraint, not the gyrocompass of §13.2), with the free axis, the rotor axis and the
// third axis principal axes of frame + rotor; rotor symmetric; the frame's bearings frictionless but for d.
// Oracle: tests/oracle/foucault_gyro_test.cpp — held-frame torques against (13.2), (13.4); the equation
// against Euler's law evaluated numerically; equilibria; small-oscillation period (13.6) and the damped
// roots; the large-amplitude pendulum period; no directive torque at the pole.
// Docs: docs/models/foucault-gyro.md
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace gyrostab::models {

enum class FoucaultKind { kDeclinometer, kInclinometer };

struct FoucaultGyroParams {
  FoucaultKind kind{FoucaultKind::kDeclinometer};
  double H{0.25};                  // spin momentum [N m s]
  double J{0.05};                  // frame + rotor about the free axis [kg m²]
  double J_a{0.05};                // about the rotor axis, frame only [kg m²]
  double J_c{0.05};                // about the third axis [kg m²]
  double d{0.0};                   // viscous damping on the free axis [N m s/rad]
  double earth_rate{7.292115e-5};  // ω^E [rad/s]
  double latitude{0.8726646259971648};  // φ [rad] (50°)

  // nullptr if physically possible, else the reason (for scene validation).
  const char* invalid_reason() const {
    const auto fin = [](double v) { return std::isfinite(v); };
    if (!(fin(H) && H > 0.0)) return "H must be finite and > 0 (its sense defines the rotor's north end)";
    if (!(fin(J) && J > 0.0) || !(fin(J_a) && J_a >= 0.0) || !(fin(J_c) && J_c >= 0.0))
      return "J must be > 0, J_rotor_axis and J_cross >= 0";
    const double slack = 1e-12 * (J + J_a + J_c);
    if (!(J + J_a + slack >= J_c) || !(J_a + J_c + slack >= J) || !(J_c + J + slack >= J_a))
      return "the inertias J, J_rotor_axis, J_cross must satisfy the triangle inequalities (J + J_rotor_axis >= "
             "J_cross, ...)";
    if (!(fin(d) && d >= 0.0)) return "d must be finite and >= 0";
    if (!(fin(earth_rate) && fin(latitude))) return "earth rate and latitude must be finite";
    if (!(stiffness() > 0.0))
      return "no restoring torque at the equilibrium: H w + (J_rotor_axis − J_cross) w² must be > 0 (w = ω^E cosφ "
             "or ω^E)";
    return nullptr;
  }

  // The directive rate w: the component of Ω the rotor axis can align with [rad/s].
  double directive_rate() const {
    return kind == FoucaultKind::kDeclinometer ? earth_rate * std::cos(latitude) : earth_rate;
  }
  // The stable equilibrium of the angle: α = 0, ϑ = φ [rad].
  double equilibrium() const { return kind == FoucaultKind::kDeclinometer ? 0.0 : latitude; }
  // Linearised restoring stiffness at the equilibrium, H w + (J_a − J_c) w² [N m/rad].
  double stiffness() const {
    const double w = directive_rate();
    return H * w + (J_a - J_c) * w * w;
  }
};

class FoucaultGyro {
 public:
  static constexpr int kStateSize = 2;
  using State = Eigen::Matrix<double, 2, 1>;
  using Vec3 = Eigen::Vector3d;
  static constexpr const char* kName = "foucault-gyro";
  // The state's components, by name.
  static constexpr int kAngle = 0, kRate = 1;

  explicit FoucaultGyro(const FoucaultGyroParams& p = {}) : p_(p) {}

  const FoucaultGyroParams& params() const { return p_; }

  static State make_state(double angle, double rate) {
    State x;
    x << angle, rate;
    return x;
  }

  // Ω in the Earth-fixed axes (up, east, north) [rad/s].
  Vec3 earth_rate_vector() const {
    return p_.earth_rate * Vec3(std::sin(p_.latitude), 0.0, std::cos(p_.latitude));
  }
  // The free axis n: up (declinometer) or east (inclinometer).
  Vec3 free_axis() const { return declinometer() ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0); }
  // The rotor axis a (the sense of H) at the angle: (0, −sinα, cosα) or (sinϑ, 0, cosϑ) (13.1), (13.3).
  Vec3 rotor_axis(double angle) const {
    const double s = std::sin(angle), c = std::cos(angle);
    return declinometer() ? Vec3(0.0, -s, c) : Vec3(s, 0.0, c);
  }
  // The third principal axis, free axis × rotor axis.
  Vec3 cross_axis(double angle) const { return free_axis().cross(rotor_axis(angle)); }

  // (13.1): the torque of the rotor on the frame held at the angle, −Ω × H, in (up, east, north) [N m].
  Vec3 rotor_torque_on_held_frame(double angle) const {
    return -earth_rate_vector().cross(p_.H * rotor_axis(angle));
  }
  // The directive torque: (13.1) along the free axis [N m].
  double directive_torque(double angle) const { return free_axis().dot(rotor_torque_on_held_frame(angle)); }
  // The frame's own centrifugal torque along the free axis, −n·(Ω × J'Ω) [N m].
  double centrifugal_torque(double angle) const {
    const Vec3 W = earth_rate_vector(), a = rotor_axis(angle), c = cross_axis(angle), n = free_axis();
    const Vec3 JW = p_.J * n.dot(W) * n + p_.J_a * a.dot(W) * a + p_.J_c * c.dot(W) * c;
    return -n.dot(W.cross(JW));
  }

  void derivative(double /*t*/, const State& x, State& dx) const {
    const double angle = x[kAngle], rate = x[kRate];
    dx[kAngle] = rate;
    dx[kRate] = (directive_torque(angle) + centrifugal_torque(angle) - p_.d * rate) / p_.J;
  }
  void project(State&) const {}

  // The angle's offset from the stable equilibrium, α or ϑ − φ [rad].
  double offset(double angle) const { return angle - p_.equilibrium(); }

 private:
  bool declinometer() const { return p_.kind == FoucaultKind::kDeclinometer; }
  FoucaultGyroParams p_;
};

// The linearised equation J x'' + d x' + k x = 0 at the equilibrium (k = H w + (J_a − J_c) w²): its roots
// λ = −σ ± i ω_d and the book's undamped small-oscillation period (13.6) without the centrifugal term.
struct FoucaultLinear {
  double J{1.0}, d{0.0}, k{1.0};

  static FoucaultLinear of(const FoucaultGyroParams& p) { return {p.J, p.d, p.stiffness()}; }
  double natural_rate() const { return std::sqrt(k / J); }      // ω0 [rad/s]
  double decay_rate() const { return d / (2.0 * J); }           // σ [1/s]
  double damping_ratio() const { return d / (2.0 * std::sqrt(k * J)); }
  // ω_d² = ω0² − σ² (≤ 0: aperiodic) [rad²/s²].
  double damped_rate_squared() const { return k / J - decay_rate() * decay_rate(); }
  double damped_period() const { return 2.0 * 3.14159265358979323846 / std::sqrt(damped_rate_squared()); }
};

// (13.6) T = 2π sqrt(J / (H w)): the book's period, w = ω^E cosφ (declinometer) or ω^E (inclinometer) [s].
inline double foucault_book_period(const FoucaultGyroParams& p) {
  return 2.0 * 3.14159265358979323846 * std::sqrt(p.J / (p.H * p.directive_rate()));
}

}  // namespace gyrostab::models
