// Platform alignment controller (Magnus §16.5, (16.52), Fig. 16.13): levelling and gyrocompassing of a
// local-level inertial platform from its two level accelerometers, inside the common controller runtime
// (fault monitor, scheduler, header, safe state: controller_runtime.hpp). The stabilization servos (gyro
// pick-off → gimbal motor) are analog and, in the book's analysis, so fast that the platform turns at its
// gyros' torquing commands (sim/models/platform_alignment.hpp).
//
// Law: firmware/control/platform_alignment_loops.hpp — levelling ω_cN = Ω_N − K1 θ̂_N + I_N,
// ω_cE = −K1 θ̂_E + I_E; azimuth ω_cU = Ω_U − k_a I_E after the levelling phase.
// Reads (SensorFrame; plant: sim/plants/platform_alignment_plant.hpp):
//   carrier_angle_rad[kRoll]  = θ̂_E = a_N/g0, the platform's apparent tilt about its east axis [rad]
//   carrier_angle_rad[kPitch] = θ̂_N = −a_E/g0, the apparent tilt about its north axis [rad]
//   (g0 = 9.80665 m/s²; a_E, a_N the east and north accelerometers sampled at the frame's time.)
// Writes (ActuatorFrame): gimbal_torque_Nm[kAxis1] = torquer of the east gyro, [kAxis2] = of the north gyro
// (M = −H ω_c, (16.2)) [N m]; motor_voltage_V[kAxis1] = the zenith gyro's torquer voltage u = ω_cU/K_Z [V]
// (the contract has two torque slots; the third torquer is voltage-driven); motor_voltage_V[kAxis2] = 0;
// precession_brake = 0 (none; the safe state's zero commands leave the platform at its gyros' drift);
// status kInstrumentTorqueLimited + the runtime's.
// Introspection (in-process runs): the loops' phase, integrators and heading estimate.
// Docs: docs/models/platform-alignment.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/platform_alignment_loops.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::firmware {

struct PlatformAlignmentConfig {
  RuntimeConfig runtime{};
  PlatformAlignmentLoopParams law{};
};

class PlatformAlignmentLaw {
 public:
  explicit PlatformAlignmentLaw(const PlatformAlignmentConfig& c)
      : loops_(c.law, c.runtime.control_period_s()) {}

  void control(const msg::SensorFrame& in, msg::ActuatorFrame& cmd) {
    // A frame the fault monitor holds (same tick as the last one used) is not integrated twice.
    const bool fresh = !used_any_ || in.tick != last_tick_;
    used_any_ = true;
    last_tick_ = in.tick;
    const PlatformAlignmentCommand c =
        loops_.step(in.carrier_angle_rad[msg::kRoll], in.carrier_angle_rad[msg::kPitch], fresh);
    cmd.gimbal_torque_Nm[msg::kAxis1] = c.M_east;
    cmd.gimbal_torque_Nm[msg::kAxis2] = c.M_north;
    cmd.motor_voltage_V[msg::kAxis1] = c.u_zenith;
    cmd.motor_voltage_V[msg::kAxis2] = 0.0;
    cmd.precession_brake = 0.0;
    if (c.limited) cmd.status |= bit(LawStatusBit::kInstrumentTorqueLimited);
  }
  void reset() { loops_.reset(); }

  const PlatformAlignmentLoops& loops() const { return loops_; }

 private:
  PlatformAlignmentLoops loops_;
  std::uint64_t last_tick_{0};
  bool used_any_{false};
};

template <MonotonicClock Clock = NullClock>
class BasicPlatformAlignmentController : public ControllerRuntime<PlatformAlignmentLaw, Clock> {
  using Base = ControllerRuntime<PlatformAlignmentLaw, Clock>;

 public:
  using Config = PlatformAlignmentConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    return check_platform_alignment_loops(c.law, c.runtime.control_period_s());
  }

  explicit BasicPlatformAlignmentController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, PlatformAlignmentLaw(c), check(c), clock) {}

  const PlatformAlignmentLoops& loops() const { return this->device().loops(); }
};

using PlatformAlignmentController = BasicPlatformAlignmentController<>;

}  // namespace gyrostab::firmware
