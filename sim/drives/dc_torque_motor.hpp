// DC torque motor, or a brushless (PMSM) motor under field-oriented control in its DQ-equivalent form: the
// electrics of a gimbal drive (docs/models/drives.md; the book's back-EMF motor, Magnus §14.3.2
// (14.26)-(14.27), here with the winding: u = L i' + R i + k_e ω, M = k_t i).
//
//   L di/dt = u − R i − k_e ω_m        torque on the rotor τ_m = k_t i
//   |u| ≤ U_max (bus), |i| ≤ I_max (the drive's own current clamp)
//
// State: winding current i [A]. Parameters (SI): R [Ω] > 0, L [H] ≥ 0 (0: resistive limit), k_t [N m/A],
// k_e [V s/rad] (= k_t for a lossless machine in consistent SI / power-invariant DQ units; a datasheet in
// amplitude-invariant DQ units gives k_t = 1.5 p λ, k_e = p λ — enter both), rotor inertia J_m [kg m²] (used
// by the gear train for the reflected inertia; the motor does not integrate its own speed), bus limit U_max
// [V] (H-bridge: V_bus; PMSM with SVPWM in amplitude-invariant DQ: V_bus/√3), current clamp I_max [A].
// For a PMSM: i is the q-axis current with i_d = 0, L = L_q, and the cross-coupling ω_e L_d i_d vanishes.
//
// PWM is a zero-order hold of the commanded voltage (the PWM average) over the step; the ripple at the PWM
// frequency, ≈ U_max T_pwm/(4L), is averaged out (valid while the current does not reach zero inside a PWM
// period, i.e. no discontinuous conduction).
//
// Integration over a step h, with the mechanical speed ω_m held at its start-of-step value (the drive is
// stepped before the axis: gimbal_drive.hpp): the ODE is then linear with constant input, and is solved
// EXACTLY (ZOH discretization), piecewise when the current clamp engages:
//   i(t_k + s) = i∞ + (i_k − i∞) e^{−s R/L},   i∞ = (u − k_e ω_m)/R
//   ∫ i ds     = i∞ s + (i_k − i∞) (L/R)(1 − e^{−s R/L})          (the mean current → mean torque)
// No step restriction comes from L/R: a step 1000× longer than L/R gives the exact i(t_k) (test).
// Current clamp: the asymptote beyond ±I_max makes the current hit the limit at
//   s* = (L/R) ln((i∞ − i_k)/(i∞ − I_lim)),
// after which the drive holds i = I_lim with the voltage R I_lim + k_e ω_m (a voltage override, within the
// bus); the mean current over the step is integrated exactly across that switch. If even the bus cannot
// hold the limit (back-EMF above the bus, i.e. the motor is overdriven as a generator), the current follows
// the bus-limited voltage beyond the limit: that is what a real bridge does before it trips.
//
// Error of the held speed [bound]. Let the true motor speed move by at most α (s − t_k) within a step
// (α = max |dω_m/dt|). The current error δi = i_held − i_true obeys L δi' = −R δi + k_e (ω_m(s) − ω_m(t_k)), a
// first-order low-pass (positive impulse response, L∞ gain 1/R) driven by a forcing of magnitude ≤ k_e α h.
// Hence, at every instant and whatever L/R is, and without accumulating over steps,
//   |i_held − i_true| ≤ k_e α h / R,        |τ_held − τ_true| ≤ k_t k_e α h / R = b_e α h,
// b_e = k_t k_e/R the electrical damping [N m s/rad]: one step's change of the back-EMF braking torque. The
// bound is attained for h ≫ L/R: on a speed ramp the error tends to k_e α (h − L/R)/R (test). Inside the
// clamp the current does not depend on ω and the error is zero.
// The mechanical consequence (the back-EMF damping acts explicitly on the axis) is in gimbal_drive.hpp.
//
// Hot path: advance* are O(1) (≤ 3 exponentials, ≤ 2 logarithms), no heap. Disabled (bridge open): i = 0 at
// once (the free-wheel transient, ≈ L|i|/U_max, is not modelled).
// Test: tests/oracle/gimbal_drive_test.cpp (current rise, stall, clamp, held-speed bound).
// Docs: docs/models/drives.md#dc-torque-motor
#pragma once

#include <algorithm>
#include <cmath>

namespace gyrostab::drives {

struct DcTorqueMotorParams {
  double R{1.0};               // winding resistance [Ω]
  double L{1e-3};              // winding inductance [H]
  double k_t{0.1};             // torque constant [N m/A]
  double k_e{0.1};             // back-EMF constant [V s/rad]
  double J_m{1e-5};            // rotor inertia [kg m²]
  double voltage_limit{24.0};  // U_max: largest |u| the bridge applies [V]
  double current_limit{10.0};  // I_max: the drive's current clamp [A]
};

class DcTorqueMotor {
 public:
  // What happened over one step.
  struct Interval {
    double current_mean{0.0};  // (1/h) ∫ i ds: gives the mean torque k_t i over the step [A]
    double current_end{0.0};   // i(t_k + h), what a current sensor samples at the end of the step [A]
    double voltage_mean{0.0};  // (1/h) ∫ u ds actually applied (after bus clip and clamp override) [V]
  };

  // nullptr if the parameters are usable, else what is wrong.
  static const char* check(const DcTorqueMotorParams& p) {
    if (!(p.R > 0.0 && std::isfinite(p.R))) return "dc torque motor: R must be > 0 ohm";
    if (!(p.L >= 0.0 && std::isfinite(p.L))) return "dc torque motor: L must be >= 0 H";
    if (!(p.k_t > 0.0 && std::isfinite(p.k_t))) return "dc torque motor: k_t must be > 0 N m/A";
    if (!(p.k_e >= 0.0 && std::isfinite(p.k_e))) return "dc torque motor: k_e must be >= 0 V s/rad";
    if (!(p.J_m >= 0.0 && std::isfinite(p.J_m))) return "dc torque motor: J_m must be >= 0 kg m^2";
    if (!(p.voltage_limit > 0.0 && std::isfinite(p.voltage_limit)))
      return "dc torque motor: voltage_limit must be > 0 V";
    if (!(p.current_limit > 0.0 && std::isfinite(p.current_limit)))
      return "dc torque motor: current_limit must be > 0 A";
    return nullptr;
  }

  explicit DcTorqueMotor(const DcTorqueMotorParams& p = {}) : p_(p), tau_(p.L / p.R) {}

  const DcTorqueMotorParams& params() const { return p_; }
  double electrical_time_constant() const { return tau_; }  // L/R [s]
  double current() const { return i_; }                     // i at the end of the last step [A]
  void set_current(double i) { i_ = i; }                    // initial condition [A]
  double torque() const { return p_.k_t * i_; }             // instantaneous k_t i [N m]

  // Voltage mode: the bridge applies u_cmd (clipped to the bus; a non-finite command applies 0 V) for h,
  // with the motor speed held at omega_m [rad/s]. Exact, including the current clamp.
  Interval advance(double h, double u_cmd, double omega_m) {
    const double u = std::isfinite(u_cmd) ? std::clamp(u_cmd, -p_.voltage_limit, p_.voltage_limit) : 0.0;
    return evolve(h, u, p_.k_e * omega_m, -p_.current_limit, p_.current_limit);
  }

  // Current-regulated (torque) mode: an ideal current regulator inside the drive, the fastest the bus
  // allows: full bus voltage towards i_ref (clamped to ±I_max), then the holding voltage R i_ref + k_e ω_m.
  // The rise takes ≈ L Δi/(U_max ∓ k_e ω_m); when the back-EMF leaves no headroom the current falls short.
  Interval advance_to_current(double h, double i_ref, double omega_m) {
    const double lim = p_.current_limit;
    const double target = std::isfinite(i_ref) ? std::clamp(i_ref, -lim, lim) : 0.0;
    const double emf = p_.k_e * omega_m;
    if (i_ < target) return evolve(h, p_.voltage_limit, emf, -lim, target);
    if (i_ > target) return evolve(h, -p_.voltage_limit, emf, target, lim);
    return evolve(h, std::clamp(p_.R * target + emf, -p_.voltage_limit, p_.voltage_limit), emf, target, target);
  }

  // Bridge open: no current, no torque.
  Interval disable() {
    i_ = 0.0;
    return {};
  }

 private:
  // Exact evolution over h under voltage u with back-EMF `emf`, the current kept inside [lo, hi] by the
  // drive's override (once the current reaches a bound the asymptote lies beyond, the drive holds it there).
  Interval evolve(double h, double u, double emf, double lo, double hi) {
    if (!(h > 0.0)) return {i_, i_, u};
    double i = i_, left = h, q = 0.0, w = 0.0;  // q = ∫ i ds, w = ∫ u ds
    for (int phase = 0; phase < 3 && left > 0.0; ++phase) {
      const double i_inf = (u - emf) / p_.R;
      if (i >= hi && i_inf >= hi) {
        hold(hi, emf, left, i, q, w);
        break;
      }
      if (i <= lo && i_inf <= lo) {
        hold(lo, emf, left, i, q, w);
        break;
      }
      // Free phase under u; ends early where the current reaches the bound its asymptote lies beyond.
      double bound = 0.0, d = left;
      bool hits = false;
      if (i_inf > hi && i < hi) {
        bound = hi;
        hits = true;
      } else if (i_inf < lo && i > lo) {
        bound = lo;
        hits = true;
      }
      if (hits) {
        const double s_hit = tau_ * std::log1p((bound - i) / (i_inf - bound));
        if (s_hit < left) {
          d = s_hit;
        } else {
          hits = false;
        }
      }
      segment(d, i_inf, i, q);
      w += u * d;
      if (hits) i = bound;  // exactly on the bound: the next phase holds it
      left -= d;
    }
    i_ = i;
    return {q / h, i, w / h};
  }

  // The override holds the current at `level` with u = R·level + emf, clipped to the bus: exact hold when
  // the current is there and the voltage is available; otherwise an exponential towards what the clipped
  // voltage reaches (approach from beyond the limit, or a bus too low to hold it).
  void hold(double level, double emf, double d, double& i, double& q, double& w) const {
    const double u_hold = p_.R * level + emf;
    const double u = std::clamp(u_hold, -p_.voltage_limit, p_.voltage_limit);
    if (u == u_hold && i == level) {
      q += level * d;
    } else {
      segment(d, (u - emf) / p_.R, i, q);
    }
    w += u * d;
  }

  // i ← i∞ + (i − i∞) e^{−d/τ}, q += ∫ over d. τ = 0 gives i = i∞ at once (exp(−∞) = 0).
  void segment(double d, double i_inf, double& i, double& q) const {
    if (!(d > 0.0)) return;
    const double one_minus_e = -std::expm1(-d / tau_);  // 1 − e^{−d/τ}
    const double di = i - i_inf;
    q += i_inf * d + di * tau_ * one_minus_e;
    i = i_inf + di * (1.0 - one_minus_e);
  }

  DcTorqueMotorParams p_;
  double tau_;
  double i_{0.0};
};

}  // namespace gyrostab::drives
