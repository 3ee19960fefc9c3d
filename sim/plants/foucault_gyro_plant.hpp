// Foucault's declinometer or inclinometer gyro (Magnus §13.1, (13.1)-(13.4)) on an Earth-fixed base, as a scene
// runs it: sim/models/foucault_gyro.hpp released from rest at the scene's angle at t = 0, integrated by RK4
// with the scene's sub-steps. The instrument has no torquer and no cage: the controller commands nothing.
//
// State: [angle, rate] in rad, rad/s — α, α' (declinometer) or ϑ, ϑ' (inclinometer).
// Frames: the Foucault gyros' own (tools/devices/foucault_gyro/foucault_gyro_signals.toml,
// docs/icd/foucault_gyro.md): in, no command; out, the ideal pick-off on the free axis, angle_rad = α,
// rate_rad_s = α' (declinometer, axis 1 up) or angle_rad = ϑ, rate_rad_s = ϑ' (inclinometer, axis 2 east).
// No random streams. Allocation-free after construction. Docs: docs/models/foucault-gyro.md. Oracle:
// tests/oracle/foucault_gyro_test.cpp; the shipped scenes sim/scenes/foucault-*.toml run in tests/determinism
// and tests/alloc.
#pragma once

#include <cstdint>

#include "gyrostab_signals/foucault_gyro_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/foucault_gyro.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"

namespace gyrostab::plants {

struct FoucaultGyroPlantParams {
  models::FoucaultGyroParams gyro{};
  double angle0{0.5235987755982988};  // α0 or ϑ0 at release (absolute, from rest) [rad]
};

class FoucaultGyroPlant {
 public:
  using SensorFrame = msg::foucault_gyro::SensorFrame;
  using ActuatorFrame = msg::foucault_gyro::ActuatorFrame;
  using Model = models::FoucaultGyro;
  using Dynamics = Model;
  using State = Model::State;
  struct HeldInputs {};  // none: the instrument is not driven

  FoucaultGyroPlant(const FoucaultGyroPlantParams& p, const PlantTiming& t)
      : p_(p), t_(t), gyro_(p.gyro), integ_(gyro_), driver_(integ_, t.tick_ns, t.substeps) {
    x_ = Model::make_state(p.angle0, 0.0);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.angle_rad = angle_rad();
    f.rate_rad_s = rate_rad_s();
  }

  void actuate(const ActuatorFrame&) {}

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }

  bool finite() const { return x_.allFinite(); }

  double angle_rad() const { return x_[Model::kAngle]; }
  double rate_rad_s() const { return x_[Model::kRate]; }
  // α or ϑ − φ [rad].
  double offset_rad() const { return gyro_.offset(angle_rad()); }
  // The rotor's torque on the frame along the free axis at the current angle ((13.2) M1, (13.4)) [N m].
  double directive_torque_Nm() const { return gyro_.directive_torque(angle_rad()); }
  HeldInputs held_inputs() const { return {}; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return gyro_; }
  const FoucaultGyroPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 2;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"angle_rad", "rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const FoucaultGyroPlantParams& p_;
  PlantTiming t_;
  Model gyro_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
};

}  // namespace gyrostab::plants
