// Inertial platform controller (Magnus §16.4, (16.36)-(16.44), Fig. 16.9): the Schuler loops of a levelled
// platform — accelerometer → integrator → gyro torquer on each horizontal channel — inside the common
// controller runtime (fault monitor, scheduler, header, safe state: controller_runtime.hpp). The
// stabilization servos (gyro pick-off → amplifier → gimbal motor) are analog and part of the plant
// (sim/models/inertial_platform.hpp), as in the book's (16.1)/(16.13); the contract's two torque slots carry
// the two gyro torquers.
//
// Law: firmware/control/schuler_loop.hpp — ω_cmd,i ← ω_cmd,i − (g0/R) θ_i T, M_i = −H ω_cmd,i.
// Frames: the inertial platform's own (tools/devices/inertial_platform/inertial_platform_signals.toml,
// docs/icd/inertial_platform.md; plant: sim/plants/inertial_platform_plant.hpp). Reads:
//   theta1_rad = θ_1, theta2_rad = θ_2: the platform's (the carrier's) apparent tilt about its axes 1, 2 as its
//   accelerometers sense it, specific force / g0 (g0 = 9.80665 m/s²) [rad], AVERAGED over the previous tick —
//   integrating (Δv) accelerometers, Δv/(g0 T): summing them integrates the specific force exactly, where
//   instantaneous samples would make the velocity err by (T/2)|Δf| across every turn (the centripetal force
//   turns with the vehicle) — (single-axis platform: channel 1 only, θ = −b^M/g0 of (16.27)).
//   (also sent, not read: gyro_angle1_rad, gyro_angle2_rad = the channel gyros' output angles β [rad],
//   gyro_rate1_rad_s, gyro_rate2_rad_s = β' [rad/s]; the fault monitor screens them.)
// Writes torquer1_Nm = torquer M^K of the axis-1 gyro, torquer2_Nm = of the axis-2 gyro [N m] ((16.39):
// M^K = −H ω_cmd turns the platform at ω_cmd); status kInstrumentTorqueLimited + the runtime's. No brake: the
// safe state's zero torques leave the platform holding inertial attitude.
// Introspection for the run report: velocity_estimate(i) = R ω_cmd,i [m/s] (in-process runs).
// Docs: docs/models/inertial-platform.md#firmware-law
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/schuler_loop.hpp"
#include "gyrostab_signals/inertial_platform_frames.hpp"

namespace gyrostab::firmware {

struct InertialPlatformConfig {
  RuntimeConfigOf<msg::inertial_platform::SensorFrame> runtime{};
  SchulerLoopParams law{};
};

class InertialPlatformLaw {
 public:
  using SensorFrame = msg::inertial_platform::SensorFrame;
  using ActuatorFrame = msg::inertial_platform::ActuatorFrame;

  explicit InertialPlatformLaw(const InertialPlatformConfig& c) : loop_(c.law, c.runtime.control_period_s()) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    // A frame the fault monitor holds (same tick as the last one used) is not integrated twice: the loop
    // coasts on its estimate (a missed accelerometer sample is a velocity error of θ g0 T, not 2×).
    const bool fresh = !used_any_ || in.tick != last_tick_;
    const double theta[kSchulerChannels] = {in.theta1_rad, in.theta2_rad};
    used_any_ = true;
    last_tick_ = in.tick;
    const SchulerTorques t = loop_.step(theta, fresh);
    cmd.torquer1_Nm = t.M[0];
    cmd.torquer2_Nm = t.M[1];
    if (t.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() { loop_.reset(); }

  const SchulerLoop& loop() const { return loop_; }

 private:
  SchulerLoop loop_;
  std::uint64_t last_tick_{0};
  bool used_any_{false};
};

template <MonotonicClock Clock = NullClock>
class BasicInertialPlatformController : public ControllerRuntime<InertialPlatformLaw, Clock> {
  using Base = ControllerRuntime<InertialPlatformLaw, Clock>;

 public:
  using Config = InertialPlatformConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_schuler_loop(c.law, c.runtime.control_period_s());
  }

  explicit BasicInertialPlatformController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, InertialPlatformLaw(c), check(c), clock) {}

  // R ω_cmd,i of channel i [m/s] (the loop's velocity estimate).
  double velocity_estimate(std::size_t i) const { return this->device().loop().velocity_estimate(i); }
};

using InertialPlatformController = BasicInertialPlatformController<>;

}  // namespace gyrostab::firmware
