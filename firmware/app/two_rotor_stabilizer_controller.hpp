// Two-rotor stabilizer controller (Magnus §14.3.4, Figs. 14.7, 14.8): the stabilization motor(s) on the
// frame(s) driven by the gyros' case angles, inside the common controller runtime (fault monitor, scheduler,
// header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/two_rotor_stabilizer_law.hpp (M1^K = −k1 β1 − dK1 α'; two-axis also
// M2^K = σ k2 β2 − dK2 γ'); the start-up check refuses gains outside the Hurwitz region of the closed loop's
// characteristic polynomial, with the largest stable k1 as the bound.
// Reads (SensorFrame): gimbal_angle_rad[kAxis2] = β1 [rad], gimbal_rate_rad_s[kAxis1] = α' [rad/s]; two-axis
// also carrier_angle_rad[2] = β2 [rad], carrier_rate_rad_s[1] = γ' [rad/s].
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = M1^K, [kAxis2] = M2^K (0 for the gyro frame) [N m];
// precession_brake = 0; status bit kRateLoopSaturated when a torque is clipped.
// Docs: docs/models/two-rotor-stabilizer.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/two_rotor_stabilizer_law.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct TwoRotorStabilizerConfig {
  RuntimeConfig runtime{};
  DriveConfig drive{};  // unused (torque-mode drives); kept for the runtime's common check
  TwoRotorStabilizerParams law{};
};

class TwoRotorStabilizerLaw {
 public:
  static constexpr std::uint32_t kDriveAxes = (1u << msg::kAxis1) | (1u << msg::kAxis2);

  explicit TwoRotorStabilizerLaw(const TwoRotorStabilizerConfig& c) : p_(c.law) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    const TwoRotorTorques t =
        two_rotor_torques(p_, in.gimbal_angle_rad[msg::kAxis2], in.gimbal_rate_rad_s[msg::kAxis1],
                          in.carrier_angle_rad[2], in.carrier_rate_rad_s[1]);
    cmd.gimbal_torque_Nm[msg::kAxis1] = t.M1;
    cmd.gimbal_torque_Nm[msg::kAxis2] = t.M2;
    cmd.precession_brake = 0.0;
    if (t.saturated) cmd.status |= bit(LawStatusBit::kRateLoopSaturated);
  }
  void reset() {}

 private:
  TwoRotorStabilizerParams p_;
};

template <MonotonicClock Clock = NullClock>
class BasicTwoRotorStabilizerController : public ControllerRuntime<TwoRotorStabilizerLaw, Clock> {
  using Base = ControllerRuntime<TwoRotorStabilizerLaw, Clock>;

 public:
  using Config = TwoRotorStabilizerConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, c.drive, TwoRotorStabilizerLaw::kDriveAxes);
    if (!r.ok) return r;
    return check_two_rotor_stabilizer(c.law, c.runtime.control_period_s());
  }

  explicit BasicTwoRotorStabilizerController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, c.drive, TwoRotorStabilizerLaw::kDriveAxes, TwoRotorStabilizerLaw(c), check(c), clock) {}
};

using TwoRotorStabilizerController = BasicTwoRotorStabilizerController<>;

}  // namespace gyrostab::firmware
