// Coning platform controller (Magnus §15.5, docs/models/coning.md): the platform's servo is slaved so that
// the single-axis gyro on it reads zero, inside the common controller runtime (fault monitor, scheduler,
// header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/coning_null_law.hpp — θ from the gyro's output angle β (P: integrated (c2/H) β; I:
// (d2/H) β), V = −(k_p θ + k_i ∫θ)/K_v.
// Reads (SensorFrame; plant: sim/plants/coning_plant.hpp): gimbal_angle_rad[kAxis2] = β [rad] (also filled, not
// read: gimbal_rate_rad_s[kAxis2] = β', carrier_angle_rad[kYaw] = platform azimuth relative to the base,
// carrier_rate_rad_s = the platform's absolute rate).
// Writes (ActuatorFrame): motor_voltage_V[kAxis1] = V [V]; gimbal torques 0; precession_brake = 0 (1 in the
// safe state, where the runtime zeroes V: the drive stops and the platform moves with the base);
// status kDriveVoltageSaturated + the runtime's. A frame the fault monitor holds (same tick) is not
// integrated twice: the law repeats its last command.
// Docs: docs/models/coning.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/coning_null_law.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct ConingConfig {
  RuntimeConfig runtime{};
  ConingNullParams law{};
};

class ConingLaw {
 public:
  explicit ConingLaw(const ConingConfig& c) : loop_(c.law, c.runtime.control_period_s()) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    if (!used_any_ || in.tick != last_tick_) {
      last_ = loop_.step(in.gimbal_angle_rad[msg::kAxis2]);
      used_any_ = true;
      last_tick_ = in.tick;
    }
    cmd.gimbal_torque_Nm[msg::kAxis1] = 0.0;
    cmd.gimbal_torque_Nm[msg::kAxis2] = 0.0;
    cmd.motor_voltage_V[msg::kAxis1] = last_.voltage;
    cmd.precession_brake = 0.0;
    if (last_.saturated) cmd.status |= bit(LawStatusBit::kDriveVoltageSaturated);
  }
  void reset() {
    loop_.reset();
    last_ = {};
    used_any_ = false;
  }
  const ConingNullLoop& loop() const { return loop_; }

 private:
  ConingNullLoop loop_;
  ConingNullOutput last_{};
  std::uint64_t last_tick_{0};
  bool used_any_{false};
};

template <MonotonicClock Clock = NullClock>
class BasicConingController : public ControllerRuntime<ConingLaw, Clock> {
  using Base = ControllerRuntime<ConingLaw, Clock>;

 public:
  using Config = ConingConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_coning_null(c.law, c.runtime.control_period_s());
  }

  explicit BasicConingController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, ConingLaw(c), check(c), clock) {}
};

using ConingController = BasicConingController<>;

}  // namespace gyrostab::firmware
