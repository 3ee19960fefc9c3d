// Gear train between a gimbal torque motor and its gimbal axis ("gear ratio with reflected inertia",
// docs/models/drives.md).
//
//   ω_m = N ω_axis,   θ_m = N θ_axis                       (N = motor turns per axis turn; N < 0 reverses)
//   τ_axis = η N τ_m      when the motor delivers power (τ_m ω_m ≥ 0, including standstill)
//   τ_axis = N τ_m / η    when the load back-drives the motor (τ_m ω_m < 0): the gear loss then adds to the
//                         braking torque, |τ_axis ω_axis| η = |τ_m ω_m|
//   J_reflected = N² (J_m + J_in)                          the motor rotor and gear input stage, seen at the axis
//
// Parameters: N [-] ≠ 0, efficiency η ∈ (0, 1] [-], input-stage inertia J_in (gear parts turning at motor
// speed) [kg m²] ≥ 0. Assumptions: rigid teeth, no backlash, no gear inertia on the output side (add it to
// the axis); η applies to the electromagnetic torque, the reflected inertia is lossless (the loss on the
// inertial torque, (1 − η) N² J_m ω̇, is neglected: exact for η = 1).
// How the reflected inertia reaches the dynamics: the axis model integrates the axis with the motor rotor
// included, so the scene builder adds reflected_inertia() to the axis inertia of the device model once, at
// construction (see gimbal_drive.hpp for the GimbalGyro parameter to add it to).
// Test: tests/oracle/gimbal_drive_test.cpp (acceleration τ N/(J_load + N² J_m), efficiency by power direction).
// Docs: docs/models/drives.md#gear-train
#pragma once

#include <cmath>

namespace gyrostab::drives {

struct GearTrainParams {
  double ratio{1.0};          // N: motor angle per axis angle [-]
  double efficiency{1.0};     // η [-]
  double input_inertia{0.0};  // J_in: gear stages turning with the motor [kg m²]
};

class GearTrain {
 public:
  static const char* check(const GearTrainParams& p) {
    if (!(std::isfinite(p.ratio) && p.ratio != 0.0)) return "gear train: ratio must be finite and non-zero";
    if (!(p.efficiency > 0.0 && p.efficiency <= 1.0)) return "gear train: efficiency must be in (0, 1]";
    if (!(p.input_inertia >= 0.0 && std::isfinite(p.input_inertia)))
      return "gear train: input_inertia must be >= 0 kg m^2";
    return nullptr;
  }

  explicit GearTrain(const GearTrainParams& p = {}) : p_(p) {}

  const GearTrainParams& params() const { return p_; }
  double ratio() const { return p_.ratio; }
  double motor_speed(double axis_rate) const { return p_.ratio * axis_rate; }     // [rad/s]
  double motor_angle(double axis_angle) const { return p_.ratio * axis_angle; }   // [rad]

  // Torque on the axis [N m] from the motor torque [N m] at the axis rate [rad/s].
  double axis_torque(double motor_torque, double axis_rate) const {
    const double ideal = p_.ratio * motor_torque;
    return motor_torque * motor_speed(axis_rate) >= 0.0 ? p_.efficiency * ideal : ideal / p_.efficiency;
  }

  // N² (J_m + J_in) [kg m²].
  double reflected_inertia(double motor_inertia) const {
    return p_.ratio * p_.ratio * (motor_inertia + p_.input_inertia);
  }

 private:
  GearTrainParams p_;
};

}  // namespace gyrostab::drives
