// Gyroscopic ship roll damper (Schlick type): ship roll φ coupled to the precession β of a pendulous gyro
// case, with large-angle terms, hard end stops of the precession angle, a viscous precession brake and a
// torque input on the precession axis (the active precession control of the firmware).
//
// Book: Magnus §14.2, equations (14.8)-(14.18) (docs/models/ship-roll-damper.md). Small angles, (14.8):
//   A φ'' + d1 φ' + c φ + H β' = E(t),        B β'' + d2 β' + q β − H φ' = 0
// Geometry (Fig. 14.3): the case G pivots on the hull about axis 2, parallel to the ship's transverse axis;
// the rotor axis 3 is vertical at β = 0 and the case's centre of mass lies below axis 2 (q > 0, statically
// stable, which (14.8) needs); the ship rolls by φ about its longitudinal axis 1. This is the two-gimbal
// gyro of (10.4) with the hull as the outer gimbal, so the large-angle equations implemented are
//   I(β) φ'' − Q sin2β φ'β' + H cosβ (β' + Ω3 sinφ) = E − d1 φ' − c sinφ (1 + w tan²φ) + q sinφ (1 − cosβ)
//   B β'' + Q sinβ cosβ φ'² − H cosβ φ' + H Ω3 cosφ sinβ = M2 − d2 β' − q cosφ sinβ + M_stop(β, β')
// with I(β) = A − Q sin²β. Large-angle terms, each reducing to (14.8) at first order:
//   - gyroscopic coupling H cosβ in both equations (the rotor axis leaves the vertical by β; the component
//     of H along the roll axis is H sinβ), as in (10.4) and the servo gyro (14.41);
//   - inertia terms of the case and rotor, Q = A^R + A^J − C^J as in (10.4) (zero for a case whose inertia
//     about the rotor axis equals that of case + rotor about the roll direction);
//   - righting moment c·GZ(φ)/GM with the wall-sided righting arm GZ = sinφ (GM + ½ BM tan²φ), w = BM/(2GM)
//     (w = 0: constant metacentric height, GZ = GM sinφ; the wall-sided form holds until the deck edge
//     immerses or the bilge emerges, typically |φ| ≲ 20-25°);
//   - pendulous moment of the case −q cosφ sinβ (its centre of mass at depth s below axis 2, q = G s), and
//     its share of the roll moment q sinφ (1 − cosβ) (c is the whole ship's stiffness at β = 0, so only the
//     change with β appears).
// The potential is V = (c − q)(1 − cosφ) + c w (secφ + cosφ − 2) + q (1 − cosφ cosβ) + H Ω3 (1 − cosφ cosβ).
// End stops at |β| = beta_stop: a stiff one-sided spring-damper (Kelvin-Voigt, force clipped at zero so it
// never pulls), M_stop = −sgn β · max(0, k_s δ + d_s sgn β · β'), δ = |β| − beta_stop > 0, with
// k_s = B ω_s², d_s = 2 ζ_s B ω_s (ω_s = stop_frequency, ζ_s = stop_damping_ratio). Chosen over an inelastic
// impact because the integrators are fixed-step without event location: a velocity reset in project() would
// act only at step ends (stages 2-4 of RK4 would not see the stop, the penetration and the lost energy would
// depend on h), whereas the spring-damper is part of the vector field, converges at the integrator's order
// between contact events and gives the stop load as a signal. ζ_s = 1 gives a coefficient of restitution
// of exactly e^-2 ≈ 0.135 (contact ends when the clipped force reaches zero at ω_s t = 2), nearly
// inelastic. The damper term makes the stop torque jump by d_s |β'| at first contact; a step straddling the
// onset misweights it in RK4's stages and errs by ≤ (2/3) ζ_s ω_s h |β'| in the rebound speed (0.067 |β'| at
// h ω_s = 0.1; measured ≤ 0.01 |β'|), first order in h but bounded and dissipative. The stop adds, while in
// contact, a mode λ = −ω_s (ζ_s ± sqrt(ζ_s² − 1)) (the gyroscopic H²/(AB) shifts ω_s² by < 1e-3 for the
// defaults): RK4 needs h·ω_s (ζ_s + sqrt(ζ_s² − 1)) < 2.78 to be stable
// and ≲ 0.3 to be accurate; the defaults (100 rad/s, ζ_s = 1) give h ω_s = 0.1 at the 1 ms controller tick,
// penetration H φ'/k_s ≈ 2e-3 rad at φ' = 0.3 rad/s. A linearisation at β = 0 (step_validation.hpp) does not
// see this mode: `stop_mode_rate()` returns its largest |λ| for the caller's step check.
// Turning (Ω3 = turn_rate ≠ 0, about the upward vertical, the rotor spinning with H > 0 about the case's
// axis 3, up at β = 0): the frame of the ship's course turns, the case's angular velocity in hull axes is
// (φ', β' + Ω3 sinφ, Ω3 cosφ), and the rotor's reaction −ω × H r, r = (sinβ, 0, cosβ), adds
//   −H cosβ Ω3 sinφ to the roll moment and −H Ω3 cosφ sinβ to the precession moment,
// the gradient of the potential H Ω3 (1 − cosφ cosβ): the stiffnesses of (14.8) become c + HΩ3 and q + HΩ3
// (the book's "tendency to like-directed parallelism", (10.22); the monorail's (14.6)-(14.7) with the
// signs of a statically stable case). A turn against the rotor's sense below Ω3 = −q/H makes the case's
// stiffness negative while the ship's stays positive: an odd number of negative stiffnesses, unstable for
// any H and any damping (Magnus §11.2 rules), a real root ≈ −(q + HΩ3)/d2 with the brake. The terms of
// order AΩ3², BΩ3 against H (the hull's own centrifugal roll moment, the heel from the turn's centripetal
// force) are left out, as in (10.22).
// Twin units (`units` = 2): two counter-rotating units (spins ±H) whose cases are linked to precess in
// mirror (β₂ = −β₁, the usual installation). With the per-unit B, Q, q, d2, H given, the pair's equations
// are those above with 2B, 2Q, 2q, 2d2, the coupling 2H, and the turn's terms cancelled (their spins sum
// to zero): the pair is immune to the turn, and the yaw moments H β' sinβ of the units cancel.
// Mount loads (mount_loads()): the rotor's reaction on the hull in hull axes, per unit k (spin s_k H,
// β_k = s_k β): roll −s_k H cosβ_k (β_k' + Ω3 sinφ), yaw s_k H sinβ_k (β_k' + Ω3 sinφ) — at Ω3 = 0 the
// book's H β' cosβ (the stabilizing moment) and H β' sinβ; and the torque the precession axis carries
// between case and hull (drive, brake, bearing friction, stops), which the foundation takes as pitch.
// Locked (`locked` = true): the case is fixed to the hull at its initial β, β' is ignored and the ship rolls
// alone, I(β0) φ'' + d1 φ' + restoring(φ, β0) = E: the unstabilized ship of (14.15) for comparison.
//
// State x = [φ (rad), β (rad), φ' (rad/s), β' (rad/s)].
// Parameters (book symbols, SI): A roll inertia of ship + installation at β = 0 [kg m²]; c = m g GM roll
// stiffness of the whole ship at β = 0 [N m/rad]; d1 roll damping [N m s/rad]; w = BM/(2 GM) [-];
// B case + rotor inertia about the case axis 2 [kg m²]; Q (see above) [kg m²]; q = G s pendulous stiffness of
// the case [N m/rad]; d2 viscous precession brake [N m s/rad]; H rotor spin momentum [N m s];
// beta_stop [rad]; stop_frequency ω_s [rad/s]; stop_damping_ratio ζ_s [-]; turn_rate Ω3 [rad/s]; units 1 or 2
// (B, Q, q, d2, H per unit).
// Inputs (zero-order hold, set by the caller each tick): E wave moment on the roll axis [N m] ((14.9):
// E0 cos ωt, or an irregular sea); M2 torque on the precession axis from the active control [N m], positive
// about axis 2.
// Assumptions: rigid hull rolling about a longitudinal axis that turns at the fixed rate Ω3 (no pitch, heave
// or sway; the yaw moment H sinβ β' and the pitch reactions of the gyro go into the hull, reported by
// mount_loads(), and do not move it); roll
// damping linear; case axis on the roll axis (the pivot's translational acceleration is neglected); rotor
// spin constant (H fixed: no spin motor torque); the sea acts only through E(t).
// Defaults: a constructed ship of 2000 t, GM 0.6 m (docs/models/ship-roll-damper.md), no precession brake
// (the minimax brake of (14.18) for it is d2 = 4.53e4 N m s/rad).
// Oracles: tests/oracle/ship_roll_damper_test.cpp — steady amplitudes vs (14.11), the invariant points
// (14.18), the minimax d2, the locked ship (14.15), energy conservation with the large-angle terms and the
// stops, and the stop's restitution e^-2; tests/oracle/ship_course_response_test.cpp — the regular sea at a
// heading and speed vs (14.11) at the encounter frequency, the turning bound, the twin units.
// Docs: docs/models/ship-roll-damper.md
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <numbers>

namespace gyrostab::models {

struct ShipRollDamperParams {
  double A{3.2e7};                 // roll inertia, ship + installation, β = 0 [kg m²]
  double c{1.1772e7};              // roll stiffness m g GM, whole ship at β = 0 [N m/rad]
  double d1{0.0};                  // roll damping [N m s/rad]
  double w{0.0};                   // wall-sided coefficient BM/(2 GM) [-]
  double B{1.5e4};                 // case + rotor about the case axis 2 [kg m²]
  double Q{0.0};                   // A^R + A^J − C^J of (10.4): I(β) = A − Q sin²β [kg m²]
  double q{1350.0};                // pendulous stiffness of the case G s [N m/rad]
  double d2{0.0};                  // viscous friction of the precession bearing (+ a passive brake) [N m s/rad]
  double H{1.018e6};               // rotor spin momentum [N m s]
  double beta_stop{std::numbers::pi / 180.0 * 70.0};  // precession end stops ±70° [rad]
  double stop_frequency{100.0};    // ω_s: k_s = B ω_s² [rad/s]
  double stop_damping_ratio{1.0};  // ζ_s: d_s = 2 ζ_s B ω_s [-]
  bool locked{false};              // case locked to the hull at its initial β (unstabilized ship)
  double turn_rate{0.0};           // Ω3 about the upward vertical, > 0 in the rotor's sense [rad/s]
  int units{1};                    // 1, or 2: counter-rotating pair with linked cases (B, Q, q, d2, H per unit)

  // The pair's totals (units × the per-unit value) and the sum of the spins (H for one unit, 0 for a pair).
  double total_B() const { return units * B; }
  double total_Q() const { return units * Q; }
  double total_q() const { return units * q; }
  double total_d2() const { return units * d2; }
  double total_H() const { return units * H; }
  double spin_sum() const { return units == 1 ? H : 0.0; }
  // The turn rate below which the case's stiffness q + k_c + HΩ3 is negative, for a centring stiffness k_c
  // of the precession control [rad/s]; −inf when the spins cancel.
  double turn_rate_bound(double centring_stiffness = 0.0) const {
    return spin_sum() > 0.0 ? -(total_q() + centring_stiffness) / spin_sum() : -std::numeric_limits<double>::infinity();
  }

  // nullptr if the parameters are physically possible, else the reason (for scene validation).
  const char* invalid_reason() const {
    if (!(A > 0.0)) return "A (roll inertia) must be > 0";
    if (!(B > 0.0)) return "B (case inertia) must be > 0";
    if (!(units == 1 || units == 2)) return "units must be 1 or 2 (a counter-rotating pair)";
    if (!(A - units * Q > 0.0)) return "A - units Q must be > 0 (roll inertia I(beta) = A - Q sin^2 beta)";
    if (!(c > 0.0)) return "c (roll stiffness m g GM) must be > 0";
    if (!(q >= 0.0)) return "q must be >= 0 (case pendulous: centre of mass below axis 2, (14.8))";
    if (!(d1 >= 0.0) || !(d2 >= 0.0)) return "d1, d2 must be >= 0";
    if (!(w >= 0.0)) return "w = BM/(2 GM) must be >= 0";
    if (!(H >= 0.0)) return "H must be >= 0";
    if (!(beta_stop > 0.0 && beta_stop < 0.5 * std::numbers::pi)) return "beta_stop must be in (0, pi/2)";
    if (!(stop_frequency > 0.0)) return "stop_frequency must be > 0";
    if (!(stop_damping_ratio >= 0.0)) return "stop_damping_ratio must be >= 0";
    if (!std::isfinite(turn_rate)) return "turn_rate must be finite";
    return nullptr;
  }
};

// The gyro's loads on the hull [N m], hull axes (see the header).
struct ShipMountLoads {
  double roll{0.0};      // net roll moment of the rotors' reaction (the stabilizing moment)
  double yaw{0.0};       // net yaw moment on the hull
  double yaw_unit{0.0};  // yaw moment of one unit (the first)
  double pitch{0.0};     // torque through one unit's precession axis, taken by the foundation as pitch
};

struct ShipRollDamperInputs {
  double E{0.0};   // wave moment on the roll axis [N m]
  double M2{0.0};  // torque on the precession axis 2 (active control) [N m]
};

class ShipRollDamper {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  static constexpr const char* kName = "ship-roll-damper";
  // The state's components, by name.
  static constexpr int kRoll = 0, kPrecession = 1, kRollRate = 2, kPrecessionRate = 3;

  explicit ShipRollDamper(const ShipRollDamperParams& p = {})
      : p_(p),
        B_(p.total_B()),
        Q_(p.total_Q()),
        q_(p.total_q()),
        d2_(p.total_d2()),
        H_(p.total_H()),
        turn_(p.spin_sum() * p.turn_rate),
        k_stop_(B_ * p.stop_frequency * p.stop_frequency),
        d_stop_(2.0 * p.stop_damping_ratio * B_ * p.stop_frequency) {}

  ShipRollDamperInputs inputs{};  // held between steps

  const ShipRollDamperParams& params() const { return p_; }

  static State make_state(double phi, double beta, double phi_rate, double beta_rate) {
    State x;
    x << phi, beta, phi_rate, beta_rate;
    return x;
  }

  void derivative(double /*t*/, const State& x, State& dx) const {
    const double sp = std::sin(x[0]), cp = std::cos(x[0]);
    double sb = 0.0, cb = 1.0;
    if (!p_.locked) {
      sb = std::sin(x[1]);
      cb = std::cos(x[1]);
    } else {  // locked: β stays at β0, so its sin and cos are computed once
      if (!(x[1] == locked_beta_)) {
        locked_beta_ = x[1];
        locked_sb_ = std::sin(x[1]);
        locked_cb_ = std::cos(x[1]);
      }
      sb = locked_sb_;
      cb = locked_cb_;
    }
    const double u = x[2], v = x[3];
    const double inertia = p_.A - Q_ * sb * sb;
    double roll = inputs.E - p_.d1 * u - righting_moment(sp, cp) + q_ * sp * (1.0 - cb);
    dx[0] = u;
    if (p_.locked) {
      dx[1] = 0.0;
      dx[2] = roll / inertia;
      dx[3] = 0.0;
      return;
    }
    roll += 2.0 * Q_ * sb * cb * u * v - H_ * cb * v;
    double precession = inputs.M2 - d2_ * v - q_ * cp * sb + H_ * cb * u - Q_ * sb * cb * u * u + stop_torque(x[1], v);
    if (turn_ != 0.0) {  // a branch, so a straight course computes exactly what it did before the turn existed
      roll -= turn_ * cb * sp;
      precession -= turn_ * cp * sb;
    }
    dx[1] = v;
    dx[2] = roll / inertia;
    dx[3] = precession / B_;
  }
  void project(State& /*x*/) const {}

  // Torque of the end stops on the case [N m] (zero off the stops).
  double stop_torque(double beta, double beta_rate) const {
    const double s = beta >= 0.0 ? 1.0 : -1.0;
    const double penetration = s * beta - p_.beta_stop;
    if (penetration <= 0.0) return 0.0;
    const double force = k_stop_ * penetration + d_stop_ * s * beta_rate;
    return force > 0.0 ? -s * force : 0.0;
  }
  // Largest |λ| of the stop mode while in contact [1/s]: ω_s (ζ_s + sqrt(ζ_s² − 1)) if ζ_s ≥ 1, else ω_s.
  double stop_mode_rate() const {
    const double z = p_.stop_damping_ratio;
    return p_.stop_frequency * (z >= 1.0 ? z + std::sqrt(z * z - 1.0) : 1.0);
  }

  // Righting moment of the hull c GZ(φ)/GM [N m] (positive restores a positive φ).
  double righting_moment(double phi) const { return righting_moment(std::sin(phi), std::cos(phi)); }

  // The gyro's loads on the hull at state x, with `axis_torque` the torque the hull applies to the case about
  // axis 2 besides the stops (drive, brake, bearing friction) [N m].
  ShipMountLoads mount_loads(const State& x, double axis_torque) const {
    if (p_.locked) return {};
    const double sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double swing = p_.turn_rate != 0.0 ? p_.turn_rate * std::sin(x[0]) : 0.0;
    ShipMountLoads m;
    m.yaw_unit = p_.H * sb * (x[3] + swing);
    m.roll = -p_.H * cb * (x[3] + swing);
    m.yaw = m.yaw_unit;
    if (p_.units == 2) {  // the mirror unit: spin −H, angle −β
      m.roll += p_.H * cb * (-x[3] + swing);
      m.yaw += -p_.H * -sb * (-x[3] + swing);
    }
    m.pitch = (axis_torque + stop_torque(x[1], x[3])) / p_.units;
    return m;
  }

  // Mechanical energy [J]: ½ I(β) φ'² + ½ B β'² + V(φ, β) + ½ k_s δ². Without E, M2, damping (d1, d2, ζ_s)
  // it is conserved (the gyroscopic terms do no work). Locked: the case's kinetic energy is left out.
  double energy(const State& x) const {
    const double cp = std::cos(x[0]), sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double turn = p_.locked ? 0.0 : turn_;  // a locked case is the bare ship (see derivative())
    double V = (p_.c - q_) * (1.0 - cp) + (q_ + turn) * (1.0 - cp * cb);
    if (p_.w != 0.0) V += p_.c * p_.w * (1.0 / cp + cp - 2.0);
    const double penetration = std::abs(x[1]) - p_.beta_stop;
    if (penetration > 0.0) V += 0.5 * k_stop_ * penetration * penetration;
    const double T_case = p_.locked ? 0.0 : 0.5 * B_ * x[3] * x[3];
    return 0.5 * (p_.A - Q_ * sb * sb) * x[2] * x[2] + T_case + V;
  }

 private:
  double righting_moment(double sp, double cp) const {
    if (p_.w == 0.0) return p_.c * sp;
    const double t = sp / cp;
    return p_.c * sp * (1.0 + p_.w * t * t);
  }

  ShipRollDamperParams p_;
  double B_, Q_, q_, d2_, H_;  // the installation's totals (units × per unit)
  double turn_;                // spin sum × Ω3 [N m/rad]
  double k_stop_, d_stop_;
  // Locked: sin and cos of the last β seen (the same values as computing them each time; a cache, hence
  // mutable: one model per integrator, as for `inputs`).
  mutable double locked_beta_{std::numeric_limits<double>::quiet_NaN()}, locked_sb_{0.0}, locked_cb_{1.0};
};

}  // namespace gyrostab::models
