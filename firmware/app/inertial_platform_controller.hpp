// Inertial platform controller (Magnus §16.4, (16.36)-(16.44), Fig. 16.9): the Schuler loops of a levelled
// platform — accelerometer → integrator → gyro torquer on each horizontal channel — inside the common
// controller runtime (fault monitor, scheduler, header, safe state: controller_runtime.hpp). The
// stabilization servos (gyro pick-off → amplifier → gimbal motor) are analog and part of the plant
// (sim/models/inertial_platform.hpp), as in the book's (16.1)/(16.13); the contract's two torque slots carry
// the two gyro torquers.
//
// Law: firmware/control/schuler_loop.hpp — ω_cmd,i ← ω_cmd,i − (g0/R) θ_i T, M_i = −H ω_cmd,i.
// Reads (SensorFrame; plant: sim/plants/inertial_platform_plant.hpp):
//   carrier_angle_rad[kRoll]  = θ_1, carrier_angle_rad[kPitch] = θ_2: the platform's (the carrier's) apparent
//   tilt about its axes 1, 2 as its accelerometers sense it, specific force / g0 (g0 = 9.80665 m/s²) [rad],
//   AVERAGED over the previous tick — integrating (Δv) accelerometers, Δv/(g0 T): summing them integrates the
//   specific force exactly, where instantaneous samples would make the velocity err by (T/2)|Δf| across
//   every turn (the centripetal force turns with the vehicle) — (single-axis platform: channel 1 only,
//   θ = −b^M/g0 of (16.27)).
//   (also filled, not read: gimbal_angle_rad[kAxis1/2] = gyro output angles β of the channel gyros [rad],
//   gimbal_rate_rad_s[kAxis1/2] = β' [rad/s].)
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = torquer M^K of the axis-1 gyro, [kAxis2] = of the
// axis-2 gyro [N m] ((16.39): M^K = −H ω_cmd turns the platform at ω_cmd); precession_brake = 0 (none; the
// safe state's 1 is ignored by the plant, its zero torques leave the platform holding inertial attitude);
// status kInstrumentTorqueLimited + the runtime's.
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
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct InertialPlatformConfig {
  RuntimeConfig runtime{};
  SchulerLoopParams law{};
};

class InertialPlatformLaw {
 public:
  explicit InertialPlatformLaw(const InertialPlatformConfig& c) : loop_(c.law, c.runtime.control_period_s()) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    // A frame the fault monitor holds (same tick as the last one used) is not integrated twice: the loop
    // coasts on its estimate (a missed accelerometer sample is a velocity error of θ g0 T, not 2×).
    const bool fresh = !used_any_ || in.tick != last_tick_;
    const double theta[kSchulerChannels] = {in.carrier_angle_rad[msg::kRoll], in.carrier_angle_rad[msg::kPitch]};
    used_any_ = true;
    last_tick_ = in.tick;
    const SchulerTorques t = loop_.step(theta, fresh);
    cmd.gimbal_torque_Nm[msg::kAxis1] = t.M[0];
    cmd.gimbal_torque_Nm[msg::kAxis2] = t.M[1];
    cmd.precession_brake = 0.0;
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
