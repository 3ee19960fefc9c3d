// Gimbal drive loops (docs/models/drives.md): the cascade of a gimbal torque-motor drive —
// velocity PI (outer, e.g. 1 kHz) → current reference → current PI (inner, fast task, e.g. 10 kHz) → voltage.
//
// One PI law for both, discrete, with output limits and anti-windup by CONDITIONAL INTEGRATION (clamping):
//   e_k = r_k − y_k
//   v_k = K_p e_k + I_k + ff_k                      (I: the integral term, in output units)
//   u_k = clamp(v_k, u_min, u_max)                  (the output; never outside the limits, NaN-safe)
//   I_{k+1} = clamp(I_k + K_i T e_k, u_min − ff_k, u_max − ff_k),   except that I is frozen
//             (I_{k+1} = I_k) while v_k is beyond a limit and e_k pushes further into it
// Stated time: I never exceeds u_max − ff, so in the first tick at which the error has the other sign
// (e ≤ 0 after the upper limit) v = K_p e + I + ff ≤ u_max (up to the feedforward's change over one tick):
// the output leaves the limit in the SAME tick as the error changes sign, and earlier when
// K_p e < u_max − I − ff (the frozen integral leaves room). Without anti-windup the integral keeps K_i ∫e of
// the whole saturated interval and the output stays on the limit until the opposite error has integrated
// it away (unit test: 500 ticks blocked ⇒ ~10^4 ticks late).
// Why not back-calculation (I tracking the limit, I += (T/T_t)(u − v)): its equilibrium I = u_max − K_p e +
// K_i T_t e goes far beyond the range when K_p e ≫ u_max (a big step, a blocked axis), and when the error
// then flips the output jumps to the OPPOSITE limit (with T_t = T it even stays there at e = 0); tuning T_t
// trades that against windup. The clamped, frozen integral has neither problem and no extra parameter.
// Known cost: after leaving the limit the integral starts from its frozen value, so a loop that needs a
// large steady integral (a big load) approaches its set-point at the linear loop's rate from there.
//
// Designs (SI gains; the task period T is part of the design):
// - Current loop on the winding L di/dt = u − R i − k_e ω (with the back-EMF fed forward, u_ff = k_e ω,
//   or treated as a slow disturbance): exact discrete pole placement on the ZOH plant
//   i_{k+1} = a i_k + (1 − a)/R u_k, a = e^{−T R/L}. The PI zero cancels the plant pole,
//   K_p (z − a)/(z − 1) with K_i T/K_p = 1 − a, and the closed loop is first order with its pole at
//   p = e^{−ω_c T}:   K_p = R (1 − p)/(1 − a) [V/A],  K_i = R (1 − p)/T [V/(A s)]
//   (→ L ω_c and R ω_c, the continuous design, as T → 0). The step response is i_k = i_ref (1 − e^{−ω_c k T})
//   exactly when u_k acts over [k, k + 1] (no computation delay). With one period of delay (u_k applied at
//   k + 1) the closed loop z² − z + (1 − p) keeps real poles only while ω_c T ≤ ln(4/3) ≈ 0.29.
// - Velocity loop on J ω' = k i (ideal inner loop, J and k at the measured shaft; geared: k = N η k_t):
//   K_p = J ω_v/k [A s/rad], K_i = K_p ω_v/ρ [A/rad]; closed loop s² + ω_v s + ω_v²/ρ, ρ = 4: a double pole
//   at −ω_v/2. Keep ω_v ≤ ω_c/5 and ω_v T ≤ 0.1.
// Scheduling: the scheduler tick is the current-loop period; add current_task with period 1 and
// velocity_task with period n (e.g. 10 for 10 kHz / 1 kHz), velocity first within a tick so the inner loop
// uses the fresh reference:
//   sched.add_member<&DriveCascade<>::velocity_task>("velocity", 10, 0, budget_ns, cascade);
//   sched.add_member<&DriveCascade<>::current_task>("current", 1, 0, budget_ns, cascade);
// The platform writes `in` (measurements) before the tick and reads `out.voltage` after it.
// Real: double by default (host runs bit-identical with the plant); PiParams<float> (narrow()) for a
// Cortex-M4F, whose FPU is single precision.
//
// Resources: fixed-size state (one Real per PI), no heap, no exceptions, no I/O; pi_step is O(1) with
// 3 multiplications and no division at run time (compile_pi precomputes).
// Test: tests/unit/drive_loops_test.cpp (bandwidth, anti-windup timing vs none, limits, scheduler cascade),
// tests/alloc/drive_alloc_test.cpp.
// Docs: docs/models/drives.md#firmware-drive-loops
#pragma once

#include <cmath>
#include <cstdint>
#include "firmware/math/deterministic_math.hpp"

namespace gyrostab::firmware {

enum class AntiWindup : std::uint8_t { kConditionalIntegration, kNone };

template <class Real = double>
struct PiParams {
  Real kp{0};                 // K_p [output unit / input unit]
  Real ki{0};                 // K_i [output unit / (input unit · s)]
  Real period{Real(1e-3)};    // T, the task period [s]
  Real out_min{Real(-1)};     // output limits [output unit]; out_min < out_max
  Real out_max{Real(1)};
  AntiWindup anti_windup{AntiWindup::kConditionalIntegration};
};

// The per-tick form of PiParams (what a task holds): no division left.
template <class Real = double>
struct PiCoefficients {
  Real kp{0};
  Real ki_T{0};  // K_i T [output unit / input unit]
  Real out_min{0};
  Real out_max{0};
  bool anti_windup{true};
};

template <class Real = double>
struct PiState {
  Real integral{0};  // I, the integral term [output unit]
};

template <class Real = double>
struct PiOutput {
  Real value{0};          // u, within [out_min, out_max] [output unit]
  bool saturated{false};  // u is on a limit (v was beyond it)
  bool valid{true};       // false: a non-finite input or state; u is the safe value 0 (clamped), I unchanged
};

// nullptr if usable, else what is wrong.
template <class Real>
constexpr const char* check_pi(const PiParams<Real>& p) {
  if (!(p.kp >= Real(0))) return "pi: kp must be >= 0";
  if (!(p.ki >= Real(0))) return "pi: ki must be >= 0";
  if (!(p.period > Real(0))) return "pi: period must be > 0 s";
  if (!(p.out_min < p.out_max)) return "pi: out_min must be < out_max";
  return nullptr;
}

template <class Real>
constexpr PiCoefficients<Real> compile_pi(const PiParams<Real>& p) {
  PiCoefficients<Real> c;
  c.kp = p.kp;
  c.ki_T = p.ki * p.period;
  c.out_min = p.out_min;
  c.out_max = p.out_max;
  c.anti_windup = p.anti_windup != AntiWindup::kNone;
  return c;
}

// One tick of the PI law above. O(1).
template <class Real>
constexpr PiOutput<Real> pi_step(const PiCoefficients<Real>& c, PiState<Real>& s, Real reference,
                                 Real measurement, Real feedforward = Real(0)) {
  const Real e = reference - measurement;
  const Real v = c.kp * e + s.integral + feedforward;
  if (!(v - v == Real(0))) {  // NaN or ±Inf in an input or the state
    const Real safe = Real(0) > c.out_max ? c.out_max : (Real(0) < c.out_min ? c.out_min : Real(0));
    return {safe, true, false};
  }
  const bool above = v > c.out_max, below = v < c.out_min;
  const Real u = above ? c.out_max : (below ? c.out_min : v);
  if (!c.anti_windup) {
    s.integral += c.ki_T * e;
  } else if (!(above && e > Real(0)) && !(below && e < Real(0))) {
    const Real I = s.integral + c.ki_T * e;
    const Real hi = c.out_max - feedforward, lo = c.out_min - feedforward;
    s.integral = I > hi ? hi : (I < lo ? lo : I);
  }
  return {u, above || below, true};
}

// Bumpless start or hand-over: the integral that makes the output `value` at zero error.
template <class Real>
constexpr void pi_preload(PiState<Real>& s, Real value) {
  s.integral = value;
}

// PiParams<double> → PiParams<To> (e.g. float on the target).
template <class To>
constexpr PiParams<To> narrow(const PiParams<double>& p) {
  return {static_cast<To>(p.kp),      static_cast<To>(p.ki),      static_cast<To>(p.period),
          static_cast<To>(p.out_min), static_cast<To>(p.out_max), p.anti_windup};
}

// ------------------------------------------------------------------------------------------------ designs

struct CurrentLoopSpec {
  double resistance{1.0};      // R [Ω]
  double inductance{1e-3};     // L [H]
  double bandwidth{2000.0};    // ω_c, closed-loop bandwidth [rad/s]
  double period{1e-4};         // T, current task period [s]
  double voltage_limit{24.0};  // output limit ±U_max [V]
};

// Exact discrete pole placement (see the top of the file). Gains in V/A and V/(A s).
inline PiParams<double> design_current_pi(const CurrentLoopSpec& s) {
  const double a = math::exp(-s.period * s.resistance / s.inductance);  // L = 0: a = 0
  const double one_minus_p = -math::expm1(-s.bandwidth * s.period);
  PiParams<double> p;
  p.kp = s.resistance * one_minus_p / (1.0 - a);
  p.ki = s.resistance * one_minus_p / s.period;
  p.period = s.period;
  p.out_min = -s.voltage_limit;
  p.out_max = s.voltage_limit;
  return p;
}

struct VelocityLoopSpec {
  double inertia{1e-3};         // J at the measured shaft, including reflected inertia [kg m²]
  double torque_constant{0.1};  // k: torque per ampere at that shaft (geared: N η k_t) [N m/A]
  double bandwidth{100.0};      // ω_v, crossover [rad/s]
  double zero_ratio{4.0};       // ρ = ω_v / PI zero [-]; 4: critically damped
  double period{1e-3};          // T, velocity task period [s]
  double current_limit{10.0};   // output limit ±I_max [A]
};

// Gains in A s/rad and A/rad.
inline PiParams<double> design_velocity_pi(const VelocityLoopSpec& s) {
  PiParams<double> p;
  p.kp = s.inertia * s.bandwidth / s.torque_constant;
  p.ki = p.kp * s.bandwidth / s.zero_ratio;
  p.period = s.period;
  p.out_min = -s.current_limit;
  p.out_max = s.current_limit;
  return p;
}

// ------------------------------------------------------------------------------------------------ cascade

template <class Real = double>
struct DriveCascadeParams {
  PiParams<Real> velocity{};        // speed [rad/s] → current reference [A]
  PiParams<Real> current{};         // current [A] → terminal voltage [V]
  Real back_emf_feedforward{0};     // k_e at the shaft whose speed is measured [V s/rad]: u_ff = k_e ω
};

template <class Real = double>
class DriveCascade {
 public:
  struct Inputs {
    Real speed_reference{0};  // [rad/s]
    Real speed{0};            // measured [rad/s]
    Real current{0};          // measured winding current [A]
  };
  struct Outputs {
    Real current_reference{0};  // velocity loop output [A]
    Real voltage{0};            // current loop output, the PWM average to apply [V]
    bool velocity_saturated{false};
    bool current_saturated{false};
    bool valid{true};  // false after a non-finite input: the output is 0 V until valid inputs return
  };

  constexpr explicit DriveCascade(const DriveCascadeParams<Real>& p)
      : velocity_(compile_pi(p.velocity)), current_(compile_pi(p.current)), k_ff_(p.back_emf_feedforward) {}

  // Outer loop: in.speed_reference, in.speed → out.current_reference.
  constexpr void velocity_step() {
    const PiOutput<Real> o = pi_step(velocity_, velocity_state_, in.speed_reference, in.speed);
    out.current_reference = o.value;
    out.velocity_saturated = o.saturated;
    velocity_valid_ = o.valid;
    out.valid = o.valid;
  }
  // Inner loop: out.current_reference, in.current (+ back-EMF feedforward) → out.voltage.
  constexpr void current_step() {
    const PiOutput<Real> o = pi_step(current_, current_state_, out.current_reference, in.current, k_ff_ * in.speed);
    out.voltage = o.value;
    out.current_saturated = o.saturated;
    out.valid = velocity_valid_ && o.valid;
  }
  // Scheduler adapters (TaskFn via Scheduler::add_member).
  constexpr void velocity_task(std::uint64_t /*tick*/) { velocity_step(); }
  constexpr void current_task(std::uint64_t /*tick*/) { current_step(); }

  constexpr void reset() {
    velocity_state_ = {};
    current_state_ = {};
    velocity_valid_ = true;
    out = {};
  }
  constexpr const PiState<Real>& velocity_state() const { return velocity_state_; }
  constexpr const PiState<Real>& current_state() const { return current_state_; }

  Inputs in{};
  Outputs out{};

 private:
  PiCoefficients<Real> velocity_;
  PiCoefficients<Real> current_;
  Real k_ff_;
  PiState<Real> velocity_state_{};
  PiState<Real> current_state_{};
  bool velocity_valid_{true};
};

// ------------------------------------------------------------------------------------------------ encoder

// Count difference of a 32-bit wrapping encoder counter (SensorFrame::encoder_count): exact across the wrap
// while the shaft moves less than 2^31 counts between samples. O(1).
constexpr std::int32_t encoder_count_delta(std::int32_t now, std::int32_t before) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(now) - static_cast<std::uint32_t>(before));
}

}  // namespace gyrostab::firmware
