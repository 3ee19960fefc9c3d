// Two-rotor stabilizer controller (Magnus §14.3.4, Figs. 14.7, 14.8): the stabilization motor(s) on the
// frame(s) driven by the gyros' case angles, inside the common controller runtime (fault monitor, scheduler,
// header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/two_rotor_stabilizer_law.hpp (M1^K = −k1 β1 − dK1 α'; two-axis also
// M2^K = σ k2 β2 − dK2 γ'); the start-up check refuses gains outside the Hurwitz region of the closed loop's
// characteristic polynomial, with the largest stable k1 as the bound.
// Frames: the two-rotor stabilizer's own (tools/devices/two_rotor_stabilizer/two_rotor_stabilizer_signals.toml,
// docs/icd/two_rotor_stabilizer.md).
// Reads beta1_rad = β1 [rad], alpha_rate_rad_s = α' [rad/s]; two-axis also beta2_rad = β2 [rad],
// gamma_rate_rad_s = γ' [rad/s].
// Writes frame1_torque_Nm = M1^K, frame2_torque_Nm = M2^K (0 for the gyro frame) [N m]; status bit
// kRateLoopSaturated when a torque is clipped. No brake: the safe state is zero motor torque. Torque-mode
// motors (no current loop).
// Docs: docs/models/two-rotor-stabilizer.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/two_rotor_stabilizer_law.hpp"
#include "gyrostab_signals/two_rotor_stabilizer_frames.hpp"

namespace gyrostab::firmware {

struct TwoRotorStabilizerConfig {
  RuntimeConfigOf<msg::two_rotor_stabilizer::SensorFrame> runtime{};
  TwoRotorStabilizerParams law{};
};

class TwoRotorStabilizerLaw {
 public:
  using SensorFrame = msg::two_rotor_stabilizer::SensorFrame;
  using ActuatorFrame = msg::two_rotor_stabilizer::ActuatorFrame;

  explicit TwoRotorStabilizerLaw(const TwoRotorStabilizerConfig& c) : p_(c.law) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) const {
    const TwoRotorTorques t =
        two_rotor_torques(p_, in.beta1_rad, in.alpha_rate_rad_s, in.beta2_rad, in.gamma_rate_rad_s);
    cmd.frame1_torque_Nm = t.M1;
    cmd.frame2_torque_Nm = t.M2;
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
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_two_rotor_stabilizer(c.law, c.runtime.control_period_s());
  }

  explicit BasicTwoRotorStabilizerController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, TwoRotorStabilizerLaw(c), check(c), clock) {}
};

using TwoRotorStabilizerController = BasicTwoRotorStabilizerController<>;

}  // namespace gyrostab::firmware
