// Servo gyro / CMG controller (Magnus §14.4, (14.41)-(14.44)): the axis-2 motor holds β' at Ω (rate loop,
// PI + feed-forward of (14.43)), so that the gyroscopic reaction puts M1 = −H cosβ Ω on axis 1; inside the
// common controller runtime (fault monitor, scheduler, header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/servo_gyro_law.hpp. Reference: either a constant rate Ω (ServoGyroReference::kRate,
// the book's vibrator drive, default Ω = 10 rad/s = sqrt(c1/A) of the plant's default oscillator) or a
// torque demand on axis 1 (kAxis1Torque: Ω = −M1/(H cosβ) each control tick, |cosβ| floored near gimbal
// lock, kGimbalLockGuard); set_reference() changes the value at run time.
// Frames: the servo gyro's own (tools/devices/servo_gyro/servo_gyro_signals.toml, docs/icd/servo_gyro.md).
// Reads drive_angle_rad = β [rad], drive_rate_rad_s = β' [rad/s], alpha_rate_rad_s = α' [rad/s].
// Writes motor_torque_Nm = M2 [N m]; precession_brake = 0 (the axis-2 brake: 1 only in the safe state);
// status bits kRateLoopSaturated, kGimbalLockGuard + the runtime's.
// Rates: the rate loop every control_divisor base ticks with dt = T_c (its PI integrates over T_c). The axis-2
// motor is torque-driven (no current loop: the servo gyro has no winding-current sensor).
// Docs: docs/models/servo-gyro.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/servo_gyro_law.hpp"
#include "gyrostab_signals/servo_gyro_frames.hpp"

namespace gyrostab::firmware {

enum class ServoGyroReference : std::uint8_t {
  kRate,         // reference = Ω [rad/s]
  kAxis1Torque,  // reference = M1 demand on axis 1 [N m]
};

struct ServoGyroConfig {
  RuntimeConfigOf<msg::servo_gyro::SensorFrame> runtime{};
  ServoGyroParams law{};
  ServoGyroReference reference_kind{ServoGyroReference::kRate};
  double reference{10.0};  // Ω [rad/s] or M1 [N m], per reference_kind
};

class ServoGyroLaw {
 public:
  using SensorFrame = msg::servo_gyro::SensorFrame;
  using ActuatorFrame = msg::servo_gyro::ActuatorFrame;

  explicit ServoGyroLaw(const ServoGyroConfig& c)
      : params_(c.law),
        loop_(c.law, c.runtime.control_period_s()),
        kind_(c.reference_kind),
        reference_(c.reference) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    const double beta = in.drive_angle_rad;
    double rate = reference_;
    if (kind_ == ServoGyroReference::kAxis1Torque) {
      const ServoGyroRate r = servo_gyro_rate_for_torque(params_, reference_, beta);
      rate = r.rate;
      if (r.limited) cmd.status |= bit(LawStatusBit::kGimbalLockGuard);
    }
    const ServoGyroOutput o =
        loop_.step({rate, beta, in.drive_rate_rad_s, in.alpha_rate_rad_s});
    cmd.motor_torque_Nm = o.torque_Nm;
    cmd.precession_brake = 0.0;
    if (o.saturated) cmd.status |= bit(LawStatusBit::kRateLoopSaturated);
  }
  void reset() { loop_.reset(); }
  void set_reference(double value) { reference_ = value; }
  double reference() const { return reference_; }
  const ServoGyroRateLoop& loop() const { return loop_; }

 private:
  ServoGyroParams params_;
  ServoGyroRateLoop loop_;
  ServoGyroReference kind_;
  double reference_;
};

template <MonotonicClock Clock = NullClock>
class BasicServoGyroController : public ControllerRuntime<ServoGyroLaw, Clock> {
  using Base = ControllerRuntime<ServoGyroLaw, Clock>;

 public:
  using Config = ServoGyroConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    if (!std::isfinite(c.reference)) return ConfigCheck::refused("servo gyro: reference must be finite");
    return check_servo_gyro(c.law, c.runtime.control_period_s());
  }

  explicit BasicServoGyroController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, ServoGyroLaw(c), check(c), clock) {}

  // New reference (Ω [rad/s] or M1 [N m], per Config::reference_kind), used from the next control run.
  // A non-finite value is ignored.
  void set_reference(double value) {
    if (std::isfinite(value)) this->mutable_device().set_reference(value);
  }
};

using ServoGyroController = BasicServoGyroController<>;

}  // namespace gyrostab::firmware
