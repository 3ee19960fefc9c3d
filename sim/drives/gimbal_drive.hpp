// Gimbal drive: the actuator of one gimbal axis, composed from its parts (docs/models/drives.md):
//
//   command (voltage, or torque for a current-regulated drive), enable
//     → DcTorqueMotor: bus clip, PWM as ZOH, exact current over the step, current clamp   (dc_torque_motor.hpp)
//     → τ_m = k_t ī  (ī the step's mean current: the exact impulse of the step)
//     → GearTrain: τ_gear = η N τ_m (or N τ_m/η back-driven), ω_m = N ω_axis for the back-EMF  (gear_train.hpp)
//     → BearingFriction: Coulomb + viscous + Karnopp stick-slip on the axis                   (bearing_friction.hpp)
//     → torque on the gimbal axis, held over the step; plus a "hold" flag when the joint is stuck
//   sensors: winding current at the step end; encoder on the motor shaft (sim/sensors/encoder.hpp)
//
// Coupling to a gimbal axis model (the axis inertia and dynamics belong to the device model, e.g.
// sim/models/gimbal_gyro.hpp, which takes the axis torque as a held input M1/M2):
//   - explicit, drive first: per plant step the drive is stepped with the axis state at the step start and
//     returns the axis torque for [t, t + h]; then the device model integrates the step with that torque.
//   - reflected inertia: the scene builder adds reflected_inertia() = N²(J_m + J_in) to the axis inertia of
//     the device model once, at construction. GimbalGyro: outer axis 1 → GimbalGyroParams::AA; inner axis 2
//     → BJ. (For axis 1 this is exact on a fixed base; for axis 2 the motor rotor's own gyroscopic coupling,
//     its momentum J_m N β' carried round by the outer gimbal, is neglected — relative size J_m N/B.)
//     Bearing friction then lives here: set the model's own d_i, r_i of that axis to 0.
//   - the friction's stick decision needs the net other torque τ_a on the axis and the axis inertia J at the
//     step start (AxisLoad). For a model with torque input M, probe_axis_load() gets both from two
//     derivative evaluations (the acceleration is affine in M: J = ΔM/Δa, τ_ext = J a(M = 0)).
//   - when step() says hold, the caller sets the axis rate to 0 before integrating; the returned torque
//     then cancels the probed load exactly, so a pure-inertia axis stays exactly at rest (a coupled model
//     may drift within a step by its load's change over the step; the next hold zeroes the rate again).
// The per-step sequence of a scene runner (axis 2 of a GimbalGyro, state x = [α, β, α', β', H]):
//   construction: p.BJ += drive.reflected_inertia(); p.d2 = p.r2 = 0; check(drive params) == nullptr;
//                 require h < drive.max_stable_step(axis inertia)
//   each controller tick: drive.command(voltage, torque, actuator_frame.status);   (held until the next)
//   each plant step:      AxisLoad load = probe_axis_load(gyro, gyro.torques.M2, t, x, 3, drive.peak_torque());
//                         DriveOutput out = drive.step(h, x[3], load);
//                         if (out.hold) x[3] = 0.0;
//                         gyro.torques.M2 = out.torque;  integrator.step(t, h, x);
//   each sensor sample:   DriveReadings r = drive.readings(x[1]);   (the device puts them in its frame)
//
// Error of the explicit coupling (the held speed; the current error itself is bounded in
// dc_torque_motor.hpp: |δi| ≤ k_e α h/R). Mechanically, the back-EMF damping b_e = N² k_t k_e/R and the
// viscous b act on the axis explicitly (torque from the step-start speed). For h ≫ L/R the slow mode
// J ω' = −(b + b_e) ω is advanced by the factor 1 − h/τ_em per step instead of e^{−h/τ_em},
// τ_em = J/(b + b_e): stable for h < 2 τ_em (max_stable_step), monotone for h < τ_em, and a speed step
// response is off by at most ≈ (h/τ_em)/(2e) of the step (first order in h; test).
//
// Enable and faults, as real drives do (CiA 402 "operation enabled", ODrive watchdog): disabled, faulted or
// told kSafeState by the actuator frame, the bridge is open: zero current, zero motor torque; the bearing
// friction still acts. A watchdog (command_timeout > 0) latches kCommandTimeout when no command has
// arrived for longer than command_timeout (a missing actuator frame); clear_fault() re-arms it.
// Sensors: current() is the winding current at the end of the last step (a sample at the frame time);
// encoder counts are of the motor-shaft angle N θ_axis, wrapped to int32 as the contract carries them.
// Hot path: step() O(1), no heap; the probe costs two model derivatives.
// Test: tests/oracle/gimbal_drive_test.cpp, tests/alloc/drive_alloc_test.cpp.
// Docs: docs/models/drives.md#gimbal-drive-composition-and-its-coupling-to-a-device
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "firmware/msg/fault_bits.hpp"
#include "sim/drives/bearing_friction.hpp"
#include "sim/drives/dc_torque_motor.hpp"
#include "sim/drives/gear_train.hpp"
#include "sim/sensors/encoder.hpp"

namespace gyrostab::drives {

struct GimbalDriveParams {
  enum class Command {
    kVoltage,  // the controller commands the terminal voltage (the device's voltage command of the axis)
    kTorque,   // current-regulated drive (CiA 402 CST): axis torque (the device's torque command of the axis),
               // converted with the nominal N k_t (no load-side torque sensing: the gear loss η and the
               // friction make the delivered torque differ, as on a real drive)
  };
  DcTorqueMotorParams motor{};
  GearTrainParams gear{};
  BearingFrictionParams friction{};  // of the gimbal bearing, axis side [N m, N m s/rad, rad/s]
  sensors::EncoderParams encoder{};  // on the motor shaft
  Command command{Command::kVoltage};
  double command_timeout{0.0};  // watchdog: fault after this long without a command [s]; 0: off. The elapsed
                                // time sums the step lengths: use a non-integer number of steps (e.g. 2.5
                                // ticks: tolerates one missing frame at 1 kHz) to stay clear of rounding
};

enum class DriveFault : std::uint8_t { kNone, kCommandTimeout };

// What the axis presents to the drive at the step start.
struct AxisLoad {
  double torque{0.0};   // τ_ext: net torque on the axis from everything but this drive [N m]
  double inertia{0.0};  // J: axis inertia including the reflected motor inertia [kg m²]; ≤ 0: unknown
};

// What the drive's sensors read at a sample, for the device to put into its sensor frame.
struct DriveReadings {
  double current_A{0.0};          // winding current at the end of the last step [A]
  std::int32_t encoder_count{0};  // motor-shaft encoder count, wrapped to 32 bits as the frames carry it
  bool fault{false};              // a latched drive fault: the frame's SensorStatusBit::kDriveFault
};

struct DriveOutput {
  double torque{0.0};  // on the gimbal axis, held over the step: gear output + bearing friction [N m]
  bool hold{false};    // joint stuck: set the axis rate to 0 before integrating the step
};

// J and τ_ext of the axis with rate x[rate_index] driven by `torque_input` (a field of `model` that its
// derivative reads), from two derivative evaluations; torque_input is restored. probe_torque sets the
// rounding: J has relative error ≈ ε |τ_ext|/probe_torque, so pass the drive's torque scale.
template <class Model>
AxisLoad probe_axis_load(const Model& model, double& torque_input, double t, const typename Model::State& x,
                         int rate_index, double probe_torque = 1.0) {
  typename Model::State dx;
  const double saved = torque_input;
  torque_input = 0.0;
  model.derivative(t, x, dx);
  const double a0 = dx[rate_index];
  torque_input = probe_torque;
  model.derivative(t, x, dx);
  const double a1 = dx[rate_index];
  torque_input = saved;
  const double per_torque = (a1 - a0) / probe_torque;  // 1/J
  if (!(per_torque > 0.0) || !std::isfinite(per_torque)) return {0.0, 0.0};
  const double J = 1.0 / per_torque;
  return {a0 * J, J};
}

class GimbalDrive {
 public:
  using Command = GimbalDriveParams::Command;

  static const char* check(const GimbalDriveParams& p) {
    if (const char* e = DcTorqueMotor::check(p.motor)) return e;
    if (const char* e = GearTrain::check(p.gear)) return e;
    if (const char* e = BearingFriction::check(p.friction)) return e;
    if (p.encoder.counts_per_rev < 1) return "gimbal drive: encoder counts_per_rev must be >= 1";
    if (!(p.command_timeout >= 0.0)) return "gimbal drive: command_timeout must be >= 0 s";
    return nullptr;
  }

  explicit GimbalDrive(const GimbalDriveParams& p = {})
      : p_(p), motor_(p.motor), gear_(p.gear), friction_(p.friction), encoder_(p.encoder) {}

  const GimbalDriveParams& params() const { return p_; }

  // ---- construction-time figures for the scene builder
  // N²(J_m + J_in), to add to the axis inertia of the device model [kg m²].
  double reflected_inertia() const { return gear_.reflected_inertia(p_.motor.J_m); }
  // Back-EMF damping at the axis, b_e = N² k_t k_e/R [N m s/rad] (voltage mode; a current-regulated drive
  // cancels it while it has voltage headroom).
  double electrical_damping() const {
    const double N = gear_.ratio();
    return N * N * p_.motor.k_t * p_.motor.k_e / p_.motor.R;
  }
  // Largest stable plant step for an axis of total inertia J (incl. reflected): 2J/(b + b_e) [s] (∞ if none).
  double max_stable_step(double axis_inertia) const {
    const double c = p_.friction.viscous + (p_.command == Command::kVoltage ? electrical_damping() : 0.0);
    return c > 0.0 ? 2.0 * axis_inertia / c : std::numeric_limits<double>::infinity();
  }
  // Largest axis torque the drive can deliver, |N| η k_t I_max [N m].
  double peak_torque() const {
    return std::fabs(gear_.ratio()) * p_.gear.efficiency * p_.motor.k_t * p_.motor.current_limit;
  }

  // ---- commands (held until the next one; each re-arms the watchdog)
  void command_voltage(double volts, bool enable) {
    voltage_cmd_ = volts;
    enabled_ = enable;
    since_command_ = 0.0;
  }
  void command_torque(double axis_torque, bool enable) {
    torque_cmd_ = axis_torque;
    enabled_ = enable;
    since_command_ = 0.0;
  }
  // From an actuator frame: the axis's voltage [V] or torque [N m] command by the configured Command, and the
  // frame's status word [bits]; the bridge is disabled while it carries kSafeState.
  void command(double voltage_V, double torque_Nm, std::uint32_t status) {
    const bool enable = !msg::has(status, msg::FaultBit::kSafeState);
    if (p_.command == Command::kVoltage) {
      command_voltage(voltage_V, enable);
    } else {
      command_torque(torque_Nm, enable);
    }
  }
  void clear_fault() {
    fault_ = DriveFault::kNone;
    since_command_ = 0.0;
  }

  // ---- the plant step: torque on the axis over [t, t + h] from the axis rate [rad/s] at t and its load.
  DriveOutput step(double h, double axis_rate, const AxisLoad& load) {
    since_command_ += h;
    if (p_.command_timeout > 0.0 && since_command_ > p_.command_timeout) fault_ = DriveFault::kCommandTimeout;

    // In the dead band the joint is (about to be) held at rest: no back-EMF.
    const double w_axis = friction_.in_dead_band(axis_rate) ? 0.0 : axis_rate;
    const double w_m = gear_.motor_speed(w_axis);
    DcTorqueMotor::Interval iv;
    if (!active()) {
      iv = motor_.disable();
    } else if (p_.command == Command::kVoltage) {
      iv = motor_.advance(h, voltage_cmd_, w_m);
    } else {
      iv = motor_.advance_to_current(h, torque_cmd_ / (gear_.ratio() * p_.motor.k_t), w_m);
    }
    last_ = iv;
    gear_torque_ = gear_.axis_torque(p_.motor.k_t * iv.current_mean, w_axis);
    const FrictionTorque f = friction_.torque(axis_rate, load.torque + gear_torque_, load.inertia, h);
    stuck_ = f.stuck;
    if (f.stuck) {
      friction_torque_ = -(load.torque + gear_torque_);
      return {-load.torque, true};  // exactly cancels the load: zero acceleration
    }
    friction_torque_ = f.torque;
    return {gear_torque_ + f.torque, false};
  }

  // ---- sensors and telemetry
  double current() const { return motor_.current(); }  // at the end of the last step [A]
  // Motor-shaft encoder count of the axis angle [rad], wrapped to 32 bits (two's complement) as in the contract.
  std::int32_t encoder_count(double axis_angle) const {
    const std::int64_t c = encoder_.counts(gear_.motor_angle(axis_angle));
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(c));
  }
  // The winding current, the encoder count of the axis angle [rad] and the fault flag, as sampled now.
  DriveReadings readings(double axis_angle) const {
    return {current(), encoder_count(axis_angle), fault_ != DriveFault::kNone};
  }

  bool active() const { return enabled_ && fault_ == DriveFault::kNone; }
  DriveFault fault() const { return fault_; }
  bool stuck() const { return stuck_; }                          // the last step held the joint
  double gear_torque() const { return gear_torque_; }            // last step, on the axis [N m]
  double friction_torque() const { return friction_torque_; }    // last step, on the axis [N m]
  const DcTorqueMotor::Interval& last_interval() const { return last_; }
  DcTorqueMotor& motor() { return motor_; }
  const DcTorqueMotor& motor() const { return motor_; }
  const GearTrain& gear() const { return gear_; }
  const BearingFriction& friction() const { return friction_; }
  const sensors::Encoder& encoder() const { return encoder_; }

 private:
  GimbalDriveParams p_;
  DcTorqueMotor motor_;
  GearTrain gear_;
  BearingFriction friction_;
  sensors::Encoder encoder_;
  double voltage_cmd_{0.0};
  double torque_cmd_{0.0};
  bool enabled_{false};
  DriveFault fault_{DriveFault::kNone};
  double since_command_{0.0};
  bool stuck_{false};
  double gear_torque_{0.0};
  double friction_torque_{0.0};
  DcTorqueMotor::Interval last_{};
};

}  // namespace gyrostab::drives
