// Servo gyro / CMG controller (Magnus §14.4, (14.41)-(14.44)): the axis-2 motor holds β' at Ω (rate loop,
// PI + feed-forward of (14.43)), so that the gyroscopic reaction puts M1 = −H cosβ Ω on axis 1; inside the
// common controller runtime (fault monitor, scheduler, header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/servo_gyro_law.hpp. Reference: either a constant rate Ω (ServoGyroReference::kRate,
// the book's vibrator drive, default Ω = 10 rad/s = sqrt(c1/A) of the plant's default oscillator) or a
// torque demand on axis 1 (kAxis1Torque: Ω = −M1/(H cosβ) each control tick, |cosβ| floored near gimbal
// lock, kGimbalLockGuard); set_reference() changes the value at run time.
// Reads (SensorFrame): gimbal_angle_rad[kAxis2] = β [rad], gimbal_rate_rad_s[kAxis2] = β' [rad/s],
// gimbal_rate_rad_s[kAxis1] = α' [rad/s]; with the drive enabled also motor_current_A[kAxis2] [A].
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis2] = M2 [N m]; gimbal_torque_Nm[kAxis1] = 0;
// precession_brake = 0 (1 only in the safe state); motor_voltage_V[kAxis2] from the current loop when the
// drive is enabled; status bits kRateLoopSaturated, kGimbalLockGuard + the runtime's.
// Rates: the rate loop every control_divisor base ticks with dt = T_c (its PI integrates over T_c); the
// drive every drive_divisor ticks.
// Docs: docs/models/servo-gyro.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/servo_gyro_law.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

enum class ServoGyroReference : std::uint8_t {
  kRate,         // reference = Ω [rad/s]
  kAxis1Torque,  // reference = M1 demand on axis 1 [N m]
};

struct ServoGyroConfig {
  RuntimeConfig runtime{};
  DriveConfig drive{};  // current loop on axis 2 (optional)
  ServoGyroParams law{};
  ServoGyroReference reference_kind{ServoGyroReference::kRate};
  double reference{10.0};  // Ω [rad/s] or M1 [N m], per reference_kind
};

class ServoGyroLaw {
 public:
  static constexpr std::uint32_t kDriveAxes = 1u << msg::kAxis2;

  explicit ServoGyroLaw(const ServoGyroConfig& c)
      : params_(c.law),
        loop_(c.law, c.runtime.control_period_s()),
        kind_(c.reference_kind),
        reference_(c.reference) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    const double beta = in.gimbal_angle_rad[msg::kAxis2];
    double rate = reference_;
    if (kind_ == ServoGyroReference::kAxis1Torque) {
      const ServoGyroRate r = servo_gyro_rate_for_torque(params_, reference_, beta);
      rate = r.rate;
      if (r.limited) cmd.status |= bit(LawStatusBit::kGimbalLockGuard);
    }
    const ServoGyroOutput o =
        loop_.step({rate, beta, in.gimbal_rate_rad_s[msg::kAxis2], in.gimbal_rate_rad_s[msg::kAxis1]});
    cmd.gimbal_torque_Nm[msg::kAxis1] = 0.0;
    cmd.gimbal_torque_Nm[msg::kAxis2] = o.torque_Nm;
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
    const ConfigCheck r = check_runtime(c.runtime, c.drive, ServoGyroLaw::kDriveAxes);
    if (!r.ok) return r;
    if (!std::isfinite(c.reference)) return ConfigCheck::refused("servo gyro: reference must be finite");
    return check_servo_gyro(c.law, c.runtime.control_period_s());
  }

  explicit BasicServoGyroController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, c.drive, ServoGyroLaw::kDriveAxes, ServoGyroLaw(c), check(c), clock) {}

  // New reference (Ω [rad/s] or M1 [N m], per Config::reference_kind), used from the next control run.
  // A non-finite value is ignored.
  void set_reference(double value) {
    if (std::isfinite(value)) this->mutable_device().set_reference(value);
  }
};

using ServoGyroController = BasicServoGyroController<>;

}  // namespace gyrostab::firmware
