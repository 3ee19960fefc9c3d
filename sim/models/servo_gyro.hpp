// Servo gyro (control moment gyro) as a gyroscopic drive for a vibrator: a gimballed rotor whose inner
// gimbal (axis 2) is turned by a motor, so that the rotor's spin momentum turns and puts a periodic torque
// on the outer axis 1, which carries an oscillator (bell, vibrator).
//
// Book: Magnus §14.4, equations (14.41)-(14.44), Fig. 14.9 (docs/models/servo-gyro.md). Linearized in the
// rates α', β' but not in β (cf. (4.63)):
//   (14.41)  A α'' + H cosβ β' = M1,     B β'' − H cosβ α' = M2
// With the motor turning axis 2 uniformly, β' = Ω, β = Ωt: the gyroscopic torque on axis 1 is
//   (14.42)  M1^KR = −H Ω cos Ωt,
// and in the steady state α = α_A cos(Ωt − φ) the motor must supply, besides its other losses,
//   (14.43)  M2^K = −H cosβ α' = H Ω α_A sin(Ωt − φ) cos Ωt,
//   (14.44)  (M1^KR)max / (M2^K)max = 1/α_A   (α_A in rad: 5.7° gives ×10).
// Implemented (Q = 0 gives (14.41) exactly; Q ≠ 0 adds the rate-squared terms of the full gimbal (10.4)):
//   I(β) α'' − Q sin2β α'β' + H cosβ β' = M1 − c1 α − d1 α'            I(β) = A − Q sin²β
//   B β'' + Q sinβ cosβ α'² − H cosβ α' = M2 − d2 β'
// Axis 1 carries the oscillator: c1, d1 are its spring and damping (the book leaves them unnamed).
// Two drive modes:
//   rate-driven (default, the book's assumption): an ideal speed-controlled motor holds β' = Omega (input);
//     the β' slot of the state is set to Omega by project(), and motor_torque() is the torque it takes,
//     M2 = −H cosβ α' + Q sinβ cosβ α'² + d2 Ω (Omega held constant over a step, so β'' = 0);
//   torque-driven: the motor torque M2 (input) drives the second equation (for a drive model with its own
//     electrics and speed loop).
// [derived] (14.44) is the resonant case. From (14.43), max|M2^K| = ½ H Ω α_A (1 + |sin φ|), so in general
// (M1^KR)max/(M2^K)max = 2/(α_A (1 + |sin φ|)): 1/α_A when α lags the drive torque by 90° (the vibrator at
// resonance, the book's use), up to 2/α_A for an oscillator far from resonance.
//
// State x = [α (rad), β (rad), α' (rad/s), β' (rad/s)].
// Parameters (SI): A axis-1 inertia of outer gimbal + inner gimbal + rotor + oscillator at β = 0 [kg m²];
// B inner gimbal + rotor about axis 2 [kg m²]; Q = A^R + A^J − C^J of (10.4) [kg m²]; H spin momentum
// [N m s]; c1 oscillator stiffness on axis 1 [N m/rad]; d1 damping on axis 1 [N m s/rad]; d2 viscous
// friction on axis 2 [N m s/rad]; rate_driven (bool).
// Inputs (zero-order hold): Omega drive rate of axis 2 [rad/s] (rate-driven); M1 external torque on axis 1
// [N m]; M2 motor torque on axis 2 [N m] (torque-driven).
// Assumptions (book): carrier fixed; spin constant (H fixed); rates small (α'², α'β' terms of (10.4) only
// through Q); the oscillator is rigidly attached to axis 1 (the book suggests a tuned elastic link near
// resonance — model it as a second body if needed).
// Oracle: tests/oracle/servo_gyro_test.cpp — torque gain 1/α_A (14.44) at resonance (α_A = 5.7° → ×10.05),
// the general gain 2/(α_A(1 + |sin φ|)) off resonance, motor power = oscillator dissipation, and energy
// conservation in the torque-driven mode.
// Docs: docs/models/servo-gyro.md
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace gyrostab::models {

struct ServoGyroParams {
  double A{2.0};           // axis-1 inertia incl. the oscillator, β = 0 [kg m²]
  double B{0.5};           // inner gimbal + rotor about axis 2 [kg m²]
  double Q{0.0};           // A^R + A^J − C^J of (10.4): I(β) = A − Q sin²β [kg m²]
  double H{1.0};           // rotor spin momentum [N m s]
  double c1{200.0};        // oscillator stiffness on axis 1 [N m/rad]
  double d1{10.0};         // damping on axis 1 [N m s/rad]
  double d2{0.0};          // viscous friction on axis 2 [N m s/rad]
  bool rate_driven{true};  // β' held at the input Omega by an ideal speed-controlled motor

  // nullptr if the parameters are physically possible, else the reason (for scene validation).
  const char* invalid_reason() const {
    if (!(A > 0.0) || !(B > 0.0)) return "A, B must be > 0";
    if (!(A - Q > 0.0)) return "A - Q must be > 0 (I(beta) = A - Q sin^2 beta)";
    if (!(H >= 0.0)) return "H must be >= 0";
    if (!(c1 >= 0.0) || !(d1 >= 0.0) || !(d2 >= 0.0)) return "c1, d1, d2 must be >= 0";
    return nullptr;
  }
};

struct ServoGyroInputs {
  double Omega{0.0};  // drive rate of axis 2, rate-driven mode [rad/s]
  double M1{0.0};     // external torque on axis 1 [N m]
  double M2{0.0};     // motor torque on axis 2, torque-driven mode [N m]
};

class ServoGyro {
 public:
  static constexpr int kStateSize = 4;
  using State = Eigen::Matrix<double, 4, 1>;
  static constexpr const char* kName = "servo-gyro";
  // The state's components, by name.
  static constexpr int kAlpha = 0, kBeta = 1, kAlphaRate = 2, kBetaRate = 3;

  explicit ServoGyro(const ServoGyroParams& p = {}) : p_(p) {}

  ServoGyroInputs inputs{};  // held between steps

  const ServoGyroParams& params() const { return p_; }

  static State make_state(double alpha, double beta, double alpha_rate, double beta_rate) {
    State x;
    x << alpha, beta, alpha_rate, beta_rate;
    return x;
  }

  void derivative(double /*t*/, const State& x, State& dx) const {
    const double sb = std::sin(x[1]), cb = std::cos(x[1]);
    const double u = x[2], v = p_.rate_driven ? inputs.Omega : x[3];
    const double axis1 = inputs.M1 - p_.c1 * x[0] - p_.d1 * u - p_.H * cb * v + 2.0 * p_.Q * sb * cb * u * v;
    dx[0] = u;
    dx[1] = v;
    dx[2] = axis1 / (p_.A - p_.Q * sb * sb);
    dx[3] = p_.rate_driven ? 0.0 : (inputs.M2 - p_.d2 * v + p_.H * cb * u - p_.Q * sb * cb * u * u) / p_.B;
  }
  void project(State& x) const {
    if (p_.rate_driven) x[3] = inputs.Omega;
  }

  // (14.42): the gyroscopic torque on axis 1, M1^KR = −H cosβ β' [N m].
  double gyro_torque_axis1(const State& x) const { return -p_.H * std::cos(x[1]) * beta_rate(x); }
  // Rate-driven: the torque [N m] the motor supplies to hold β' = Omega, (14.43) plus friction and the Q
  // term. Torque-driven: the input M2.
  double motor_torque(const State& x) const {
    if (!p_.rate_driven) return inputs.M2;
    const double sb = std::sin(x[1]), cb = std::cos(x[1]);
    return -p_.H * cb * x[2] + p_.Q * sb * cb * x[2] * x[2] + p_.d2 * inputs.Omega;
  }
  // Energy ½ I(β) α'² + ½ B β'² + ½ c1 α² [J]; conserved in the torque-driven mode without M1, M2, d1, d2.
  double energy(const State& x) const {
    const double sb = std::sin(x[1]);
    return 0.5 * (p_.A - p_.Q * sb * sb) * x[2] * x[2] + 0.5 * p_.B * x[3] * x[3] + 0.5 * p_.c1 * x[0] * x[0];
  }

 private:
  double beta_rate(const State& x) const { return p_.rate_driven ? inputs.Omega : x[3]; }

  ServoGyroParams p_;
};

}  // namespace gyrostab::models
