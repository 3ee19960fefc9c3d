// Power gyro stabilizer (single-rotor, two-axis) with stabilization motors: the full nonlinear gimbal gyro
// with disturbance torques, and, chosen at compile time, a back-EMF geared motor and structural elasticity.
//
// Book: Magnus §14.3, (14.19)-(14.40) (docs/models/power-stabilizer.md). The gyro is
// GimbalGyro (gimbal_gyro.hpp, (10.4) and its base-motion extension), reused, not copied; at small angles
// on a fixed base it is (14.20) without the loops:
//   A α'' + H β' = M1^S + M1^K,      B β'' − H α' = M2^S + M2^K
// (the firmware's loops, firmware/control/power_stabilizer_loops.hpp, supply M^K = (14.19) + rate damping).
// Options (template parameters; an option that is off adds no state, no work and no storage):
//   Drive = TorqueMotors (default): current-controlled torque motors on both axes, M1^K, M2^K are inputs.
//   Drive = BackEmfMotor, (14.26)-(14.28): a geared DC motor on axis 1, current lag neglected, driven by its
//     terminal voltage u1 (input):  M1^K = s (u1 − d α')  — the book's M1^K = s u with u = −r β − d α' when
//     the amplifier gives u1 = −r β; the back-EMF d α' is folded into the gyro's outer-bearing viscous
//     damping (d1 += s d) so the exponential integrator carries it exactly, and the reflected motor inertia
//     κ²I is added to the outer gimbal (A = A^K + κ²I). Axis 2 keeps a torque input (M2K; the book's (14.28)
//     has none: leave it 0).
//   Structure = RigidStructure (default): the platform is the outer gimbal, φ ≡ α.
//   Structure = ElasticPlatform, (14.31): the platform (outer frame, angle φ, inertia A^P) is coupled to the
//     gyro's outer gimbal (angle α, the gyro's A = A^K) by an elastic shaft, torque ±c (φ − α):
//       A^K α'' + H β' = c (φ − α),   B β'' − H α' = M2^S + M2^K,   A^P φ'' = M1^S + M1^K + c (α − φ)
//     with the motor (and its reflected inertia κ²I and back-EMF s d φ', BackEmfMotor) on the platform.
//     Quasi-static (Novozhilov) limit, large c: α = φ cB/(cB + H²) (14.33), c* = c H²/(cB + H²) (14.35),
//     platform frequency ω^P = sqrt(c*/A^P) (14.37).
//
// State (rigid): x = [α (rad), β (rad), α' (rad/s), β' (rad/s), H (N m s)] — GimbalGyro's state; α, β the
//   Cardan angles of the outer/inner gimbal relative to the base (α = β = 0: rotor axis at its neutral).
// State (elastic): x = [α, β, α', β', H, φ (rad), φ' (rad/s)], φ the platform angle about axis 1 relative to
//   the base.
// Parameters (SI): the gyro's GimbalGyroParams (A^R, C^R, A^J, B^J, C^J, A^A, ... [kg m²], d1, d2 bearing
//   viscous [N m s/rad], ...); BackEmfMotor: s torque per volt at the gimbal κ k_t/R [N m/V], d back-EMF
//   per gimbal rate κ k_e [V s/rad], κ gear ratio [-], I motor rotor inertia [kg m²]; ElasticPlatform:
//   c shaft stiffness [N m/rad], AP platform inertia about axis 1 (without the motor) [kg m²].
// Inputs (zero-order hold, `inputs`): M1S, M2S disturbance torques on axis 1 (the platform) and axis 2
//   [N m]; M1K, M2K motor torques of torque-controlled drives [N m] (M1K unused with BackEmfMotor); u1 the
//   terminal voltage of the axis-1 motor [V] (BackEmfMotor only). Rotor spin torque: none (H constant).
// Assumptions: GimbalGyro's (rigid gimbals, intersecting axes, symmetric rotor); motor current lag
//   neglected (L/R ≪ the nutation period, as the book); rigid gear without backlash; the reflected inertia
//   κ²I rotates with the platform (on a moving base its reaction to base angular acceleration is taken as
//   κ²I Ω1' instead of κ I Ω1' — exact on a fixed base); elastic option: massless shaft, linear stiffness,
//   the platform rotates about axis 1 only (its equation on a moving base keeps A^P Ω1' and drops products
//   of base rates).
//   Fidelity = FullGimbal (default): the gyro is GimbalGyro, nutation resolved.
//   Fidelity = PrecessionOnly: the gyro is the precession ("engineering") model P0, GimbalGyroPrecession
//     ((10.19)-(10.22), docs/models/gimbal-gyro.md#precession-model-p0): the inertia of the gimbals is
//     dropped, the state is [α, β, H] and the gimbal rates are outputs (rates()); rigid structure only (the
//     elastic shaft's mode is an inertia effect). Relative error O(ε), ε = ω_P/ω_N; torque-step transients
//     |α| ≤ 2MB/H², |β − Mt/H| ≤ M/(Hω_N) (derived in docs/models/gimbal-gyro.md); singular at gimbal lock
//     (cos β = 0) without damping.
// State (precession): x = [α (rad), β (rad), H (N m s)].
// Integrators: the rigid variants provide gyroscopic_pair() and run under GyroscopicExponential (the default;
//   the back-EMF damping is in the exact flow). The elastic variant does NOT provide it, on purpose: the
//   exponential integrator would advance φ, φ' with its explicit-midpoint "remaining states" step, which is
//   unstable on an undamped oscillation (|R(iy)|² = 1 + y⁴/4), and c (φ − α)/A^K is a stiff forcing of the
//   nutation pair. Use Rk4 with the sub-steps that dynamics::check_step(Method::kRk4, fastest_mode(...),
//   tick) asks for (the fastest mode is the elastic/nutation mode ω² ≈ (c + H²/B)/A^K + c/A^P; e.g. 153 rad/s
//   for the test's platform, where the 1 ms tick itself passes: amplitude factor 0.99913 over 10 s), or
//   ImplicitMidpoint.
// Oracles: tests/oracle/power_stabilizer_test.cpp — closed-loop nutation growth/decay rates and frequency vs
//   the roots of (14.23), the gain boundary (14.25), constant disturbances (14.21), the back-EMF bound
//   (14.30) with the reflected inertia, and the platform frequency (14.37) and ratio (14.33) of the elastic
//   option.
// Docs: docs/models/power-stabilizer.md
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <type_traits>

#include "sim/dynamics/damped_gyroscopic_flow.hpp"
#include "sim/models/base_motion.hpp"
#include "sim/models/gimbal_gyro.hpp"
#include "sim/models/gimbal_gyro_precession.hpp"

namespace gyrostab::models {

// Drive options (axis 1).
struct TorqueMotors {
  static constexpr bool kVoltageDriven = false;
};
struct BackEmfMotor {
  static constexpr bool kVoltageDriven = true;
  double s{2.0};       // torque per volt at the gimbal, κ k_t / R [N m/V]
  double d{0.25};      // back-EMF per gimbal rate, incl. gear, κ k_e [V s/rad]
  double kappa{10.0};  // gear ratio, motor turns per gimbal turn [-]
  double I{4.0e-3};    // motor rotor inertia [kg m²]
  double reflected_inertia() const { return kappa * kappa * I; }  // κ²I [kg m²]
  double viscous() const { return s * d; }  // back-EMF damping torque per rad/s [N m s/rad]
};

// Structure options.
struct RigidStructure {
  static constexpr int kExtraStates = 0;
};
struct ElasticPlatform {
  static constexpr int kExtraStates = 2;  // φ, φ'
  double c{2.0e4};                        // shaft stiffness between platform and gyro outer gimbal [N m/rad]
  double AP{200.0};                       // platform inertia about axis 1, without the motor [kg m²]
};

// Fidelity options (the gyro's model).
struct FullGimbal {
  static constexpr bool kPrecession = false;  // GimbalGyro (10.4): nutation and precession
};
struct PrecessionOnly {
  static constexpr bool kPrecession = true;  // GimbalGyroPrecession (10.19)-(10.22): precession only (P0)
};

struct PowerStabilizerInputs {
  double M1S{0.0};  // disturbance torque on axis 1 (the platform) [N m]
  double M2S{0.0};  // disturbance torque on axis 2 [N m]
  double M1K{0.0};  // axis-1 motor torque, torque-controlled drive (TorqueMotors) [N m]
  double M2K{0.0};  // axis-2 motor torque [N m]
  double u1{0.0};   // axis-1 motor terminal voltage (BackEmfMotor) [V]
};

// What the plant shows to sensors and logs.
struct PowerStabilizerSignals {
  double alpha{0.0}, beta{0.0};            // gimbal angles [rad]
  double alpha_rate{0.0}, beta_rate{0.0};  // gimbal rates relative to the base [rad/s]
  double platform_angle{0.0};              // φ (≡ α when rigid) [rad]
  double platform_rate{0.0};               // φ' [rad/s]
  double motor_torque1{0.0};  // M1^K actually applied by the axis-1 motor, back-EMF included [N m]
  double H{0.0};              // spin momentum [N m s]
};

template <class Base = FixedBase, class Drive = TorqueMotors, class Structure = RigidStructure,
          class Fidelity = FullGimbal>
class PowerStabilizer {
 public:
  static constexpr bool kElastic = Structure::kExtraStates > 0;
  static constexpr bool kVoltageDriven = Drive::kVoltageDriven;
  static constexpr bool kPrecession = Fidelity::kPrecession;
  static_assert(!(kPrecession && kElastic), "the precession model P0 has no gimbal inertia: rigid structure only");
  static constexpr int kStateSize = (kPrecession ? 3 : 5) + Structure::kExtraStates;
  using State = Eigen::Matrix<double, kStateSize, 1>;
  using Gyro = std::conditional_t<kPrecession, GimbalGyroPrecession<Base>, GimbalGyro<Base>>;
  static constexpr const char* kName = "power-stabilizer";
  // The state's components, by name: the gimbal angles and rates (the precession model has no rates), the
  // spin momentum H, and the elastic platform's angle and rate.
  static constexpr int kAlpha = 0, kBeta = 1, kAlphaRate = 2, kBetaRate = 3;
  static constexpr int kSpin = kPrecession ? 2 : 4;
  static constexpr int kPlatform = 5, kPlatformRate = 6;

  explicit PowerStabilizer(const GimbalGyroParams& gyro = {}, const Drive& drive = {},
                           const Structure& structure = {}, const Base& base = {})
      : drive_(drive), structure_(structure), gyro_(gyro_with_drive(gyro, drive), base) {}

  PowerStabilizerInputs inputs{};  // held between steps

  const Drive& drive() const { return drive_; }
  const Structure& structure() const { return structure_; }
  // The gyro as integrated: rigid + BackEmfMotor has A^A + κ²I and d1 + s d folded in.
  const Gyro& gyro() const { return gyro_; }
  // Inertia about axis 1 the loops see: rigid A^K (+ κ²I); elastic A^K + A^P (+ κ²I) (book: A = A^K + A^P).
  double outer_axis_inertia() const {
    if constexpr (kElastic) {
      return gyro_.params().A() + platform_inertia();
    } else {
      return gyro_.params().A();
    }
  }
  // Platform inertia including the motor's reflected inertia (elastic only) [kg m²].
  double platform_inertia() const requires kElastic {
    if constexpr (kVoltageDriven) {
      return structure_.AP + drive_.reflected_inertia();
    } else {
      return structure_.AP;
    }
  }

  static State make_state(double alpha, double beta, double alpha_rate, double beta_rate,
                          double H) requires(!kElastic && !kPrecession) {
    return Gyro::make_state(alpha, beta, alpha_rate, beta_rate, H);
  }
  static State make_state(double alpha, double beta, double H) requires kPrecession {
    return Gyro::make_state(alpha, beta, H);
  }
  static State make_state(double alpha, double beta, double alpha_rate, double beta_rate, double H,
                          double phi, double phi_rate) requires kElastic {
    State x;
    x << alpha, beta, alpha_rate, beta_rate, H, phi, phi_rate;
    return x;
  }

  void derivative(double t, const State& x, State& dx) const {
    GimbalTorques& tq = gyro_.torques;
    tq.M2 = inputs.M2S + inputs.M2K;
    tq.M3 = 0.0;
    if constexpr (!kElastic) {
      tq.M1 = inputs.M1S + driven_torque1();  // the back-EMF part is in the gyro's d1
      gyro_.derivative(t, x, dx);
    } else {
      const double elastic = structure_.c * (x[5] - x[0]);  // c (φ − α), on the gyro's outer gimbal
      tq.M1 = elastic;
      const typename Gyro::State xg = x.template head<5>();
      typename Gyro::State dxg;
      gyro_.derivative(t, xg, dxg);
      dx.template head<5>() = dxg;
      const double motor = driven_torque1() - back_emf_viscous() * x[6];
      const double base_accel = gyro_.base()(t).dw_B[0];
      dx[5] = x[6];
      dx[6] = (inputs.M1S + motor - elastic) / platform_inertia() - base_accel;
    }
  }
  void project(State& /*x*/) const {}
  // The gyro's stick-slip bearings decide the step with this step's torques (sim/dynamics/step_start.hpp).
  // Rigid full model only: the scenes give the power stabilizer's bearing friction to its drives
  // ([drive] coulomb_Nm), and the gyro's own r1, r2 stay 0 in the elastic and precession variants.
  void begin_step(double t, double h, State& x) const requires(!kElastic && !kPrecession) {
    GimbalTorques& tq = gyro_.torques;
    tq.M2 = inputs.M2S + inputs.M2K;
    tq.M3 = 0.0;
    tq.M1 = inputs.M1S + driven_torque1();
    gyro_.begin_step(t, h, x);
  }

  // The fast linear part for dynamics::GyroscopicExponential (rigid variants only; see the header).
  dynamics::GyroscopicPair gyroscopic_pair(const State& x) const requires(!kElastic && !kPrecession) {
    return gyro_.gyroscopic_pair(x);
  }
  // Both at once, sharing the gyro's trigonometry (dynamics::GyroscopicExponential prefers it).
  dynamics::GyroscopicPair derivative_with_pair(double t, const State& x, State& dx) const
      requires(!kElastic && !kPrecession) {
    GimbalTorques& tq = gyro_.torques;
    tq.M2 = inputs.M2S + inputs.M2K;
    tq.M3 = 0.0;
    tq.M1 = inputs.M1S + driven_torque1();
    return gyro_.derivative_with_pair(t, x, dx);
  }

  // Gimbal rates (α', β') relative to the base [rad/s]: states of the full model; of the precession model the
  // solution of (10.19)-(10.22) at (t, x) with the held inputs.
  void rates(double t, const State& x, double& alpha_rate, double& beta_rate) const {
    if constexpr (kPrecession) {
      State dx;
      derivative(t, x, dx);
      alpha_rate = dx[0];
      beta_rate = dx[1];
    } else {
      (void)t;
      alpha_rate = x[2];
      beta_rate = x[3];
    }
  }

  // `t` matters for the precession model only (its rates depend on the base motion at t).
  PowerStabilizerSignals signals(const State& x, double t = 0.0) const {
    PowerStabilizerSignals s;
    s.alpha = x[0];
    s.beta = x[1];
    rates(t, x, s.alpha_rate, s.beta_rate);
    s.H = x[kPrecession ? 2 : 4];
    if constexpr (kElastic) {
      s.platform_angle = x[5];
      s.platform_rate = x[6];
    } else {
      s.platform_angle = x[0];
      s.platform_rate = s.alpha_rate;
    }
    s.motor_torque1 = driven_torque1() - back_emf_viscous() * s.platform_rate;
    return s;
  }

  // Mechanical energy on a base at rest [J]: the gimbals' (GimbalGyro::energy, with κ²I in A^A when rigid),
  // plus ½ A^P φ'² + ½ c (φ − α)² when elastic. Conserved without friction, back-EMF and inputs.
  double energy(const State& x) const requires(!kPrecession) {
    if constexpr (!kElastic) {
      return gyro_.energy(x);
    } else {
      const typename Gyro::State xg = x.template head<5>();
      const double stretch = x[5] - x[0];
      return gyro_.energy(xg) + 0.5 * platform_inertia() * x[6] * x[6] +
             0.5 * structure_.c * stretch * stretch;
    }
  }

  // nullptr if the parameters are physically possible, else the reason (for scene validation).
  const char* invalid_reason() const {
    const GimbalGyroParams& p = gyro_.params();
    if (!(p.A() > 0.0) || !(p.B() > 0.0)) return "gyro inertias A, B must be > 0";
    if (!(p.d1 >= 0.0) || !(p.d2 >= 0.0)) return "bearing damping d1, d2 must be >= 0";
    if constexpr (kVoltageDriven) {
      if (!(drive_.s > 0.0)) return "motor s (torque per volt) must be > 0";
      if (!(drive_.d >= 0.0)) return "motor d (back-EMF coefficient) must be >= 0";
      if (!(drive_.kappa > 0.0) || !(drive_.I >= 0.0))
        return "motor gear ratio must be > 0, rotor inertia >= 0";
    }
    if constexpr (kElastic) {
      if (!(structure_.c > 0.0)) return "shaft stiffness c must be > 0";
      if (!(structure_.AP > 0.0)) return "platform inertia AP must be > 0";
    }
    return nullptr;
  }

 private:
  static GimbalGyroParams gyro_with_drive(GimbalGyroParams p, const Drive& drive) {
    if constexpr (kVoltageDriven && !kElastic) {
      p.AA += drive.reflected_inertia();
      p.d1 += drive.viscous();
    }
    (void)drive;
    return p;
  }
  // The axis-1 motor torque from its input, without the back-EMF (handled separately) [N m].
  double driven_torque1() const {
    if constexpr (kVoltageDriven) {
      return drive_.s * inputs.u1;
    } else {
      return inputs.M1K;
    }
  }
  double back_emf_viscous() const {
    if constexpr (kVoltageDriven) {
      return drive_.viscous();
    } else {
      return 0.0;
    }
  }

  [[no_unique_address]] Drive drive_;
  [[no_unique_address]] Structure structure_;
  // derivative() sets the gyro's torque inputs from this model's inputs and state before delegating.
  mutable Gyro gyro_;
};

}  // namespace gyrostab::models
