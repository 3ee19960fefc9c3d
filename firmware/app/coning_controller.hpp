// Coning platform controller (Magnus §15.5, docs/models/coning.md): the platform's servo is slaved so that
// the single-axis gyro on it reads zero, inside the common controller runtime (fault monitor, scheduler,
// header, safe state: controller_runtime.hpp).
//
// Law: firmware/control/coning_null_law.hpp — θ from the gyro's output angle β (P: integrated (c2/H) β; I:
// (d2/H) β), V = −(k_p θ + k_i ∫θ)/K_v.
// Frames: the coning platform's own (tools/devices/coning/coning_signals.toml, docs/icd/coning.md; plant:
// sim/plants/coning_plant.hpp). Reads beta_rad = β [rad] (also filled, not read: beta_rate_rad_s = β',
// platform_azimuth_rad = the platform's azimuth relative to the base, platform_rate_rad_s = its absolute rate).
// Writes drive_voltage_V = V [V] (0 in the safe state: the drive stops and the platform moves with the base);
// status kDriveVoltageSaturated + the runtime's. A frame the fault monitor holds (same tick) is not
// integrated twice: the law repeats its last command.
// Docs: docs/models/coning.md#firmware-law
#pragma once

#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/coning_null_law.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "gyrostab_signals/coning_frames.hpp"

namespace gyrostab::firmware {

struct ConingConfig {
  RuntimeConfigOf<msg::coning::SensorFrame> runtime{};
  ConingNullParams law{};
};

class ConingLaw {
 public:
  using SensorFrame = msg::coning::SensorFrame;
  using ActuatorFrame = msg::coning::ActuatorFrame;

  explicit ConingLaw(const ConingConfig& c) : loop_(c.law, c.runtime.control_period_s()) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    if (!used_any_ || in.tick != last_tick_) {
      last_ = loop_.step(in.beta_rad);
      used_any_ = true;
      last_tick_ = in.tick;
    }
    cmd.drive_voltage_V = last_.voltage;
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
