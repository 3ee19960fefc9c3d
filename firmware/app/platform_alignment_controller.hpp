// Platform alignment controller (Magnus §16.5, (16.52), Fig. 16.13): levelling and gyrocompassing of a
// local-level inertial platform from its two level accelerometers, inside the common controller runtime
// (fault monitor, scheduler, header, safe state: controller_runtime.hpp). The stabilization servos (gyro
// pick-off → gimbal motor) are analog and, in the book's analysis, so fast that the platform turns at its
// gyros' torquing commands (sim/models/platform_alignment.hpp).
//
// Law: firmware/control/platform_alignment_loops.hpp — levelling ω_cN = Ω_N − K1 θ̂_N + I_N,
// ω_cE = −K1 θ̂_E + I_E; azimuth ω_cU = Ω_U − k_a I_E after the levelling phase.
// Frames: the platform alignment's own (tools/devices/platform_alignment/platform_alignment_signals.toml,
// docs/icd/platform_alignment.md; plant: sim/plants/platform_alignment_plant.hpp). Reads:
//   theta_east_rad  = θ̂_E = a_N/g0, the platform's apparent tilt about its east axis [rad]
//   theta_north_rad = θ̂_N = −a_E/g0, the apparent tilt about its north axis [rad]
//   (g0 = 9.80665 m/s²; a_E, a_N the east and north accelerometers sampled at the frame's time.)
// Writes east_torquer_Nm = torquer of the east gyro, north_torquer_Nm = of the north gyro (M = −H ω_c, (16.2))
// [N m]; zenith_torquer_V = the zenith gyro's torquer voltage u = ω_cU/K_Z [V]; status
// kInstrumentTorqueLimited + the runtime's. No brake: the safe state's zero commands leave the platform at its
// gyros' drift.
// Introspection (in-process runs): the loops' phase, integrators and heading estimate.
// Docs: docs/models/platform-alignment.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "firmware/control/platform_alignment_loops.hpp"
#include "gyrostab_signals/platform_alignment_frames.hpp"

namespace gyrostab::firmware {

struct PlatformAlignmentConfig {
  RuntimeConfigOf<msg::platform_alignment::SensorFrame> runtime{};
  PlatformAlignmentLoopParams law{};
};

class PlatformAlignmentLaw {
 public:
  using SensorFrame = msg::platform_alignment::SensorFrame;
  using ActuatorFrame = msg::platform_alignment::ActuatorFrame;

  explicit PlatformAlignmentLaw(const PlatformAlignmentConfig& c)
      : loops_(c.law, c.runtime.control_period_s()) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    // A frame the fault monitor holds (same tick as the last one used) is not integrated twice.
    const bool fresh = !used_any_ || in.tick != last_tick_;
    used_any_ = true;
    last_tick_ = in.tick;
    const PlatformAlignmentCommand c = loops_.step(in.theta_east_rad, in.theta_north_rad, fresh);
    cmd.east_torquer_Nm = c.M_east;
    cmd.north_torquer_Nm = c.M_north;
    cmd.zenith_torquer_V = c.u_zenith;
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
