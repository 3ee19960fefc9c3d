// The U-gyro (rate gyro with an asymmetric rotor, Magnus §15.4, (15.27)-(15.29)) on a rate table, as a scene
// runs it: sim/models/u_gyro.hpp with the case turning at a constant rate Ω about the input axis from t = 0,
// the spin held by its motor, integrated by RK4 with the scene's sub-steps. The gyro has no torquer and no
// brake: the controller commands nothing.
//
// State: [β, β', γ] in rad, rad/s, rad (named accessors below). Frames: the U-gyro's own
// (tools/devices/u_gyro/u_gyro_signals.toml, docs/icd/u_gyro.md): in, no command (the table rate Ω is the
// scene's); out, table_rate_rad_s = Ω (the table, along the input axis), beta_rad, beta_rate_rad_s = β, β'
// (the output pick-off, ideal), rotor_speed_rad_s = γ'.
// No random streams. Allocation-free after construction. Docs: docs/models/u-gyro.md. Oracle:
// tests/oracle/u_gyro_test.cpp; the shipped scene sim/scenes/u-gyro-rate-table.toml runs in tests/determinism
// and tests/alloc.
#pragma once

#include <cstdint>

#include "gyrostab_signals/u_gyro_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/u_gyro.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"

namespace gyrostab::plants {

struct UGyroPlantParams {
  models::UGyroParams gyro{};
  double table_rate{0.5};  // Ω, the case's rate about the input axis from t = 0 [rad/s]
};

class UGyroPlant {
 public:
  using SensorFrame = msg::u_gyro::SensorFrame;
  using ActuatorFrame = msg::u_gyro::ActuatorFrame;
  using Model = models::UGyro;
  using Dynamics = Model;
  using State = Model::State;
  struct HeldInputs {
    double Omega{0.0};  // [rad/s]
  };

  UGyroPlant(const UGyroPlantParams& p, const PlantTiming& t)
      : p_(p), t_(t), gyro_(p.gyro), integ_(gyro_), driver_(integ_, t.tick_ns, t.substeps) {
    gyro_.inputs.Omega = p.table_rate;
    x_ = Model::make_state(0.0, 0.0, 0.0);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.table_rate_rad_s = p_.table_rate;
    f.beta_rad = beta_rad();
    f.beta_rate_rad_s = beta_rate_rad_s();
    f.rotor_speed_rad_s = p_.gyro.spin;
  }

  void actuate(const ActuatorFrame&) {}

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }

  bool finite() const { return x_.allFinite(); }

  double beta_rad() const { return x_[Model::kBeta]; }
  double beta_rate_rad_s() const { return x_[Model::kBetaRate]; }
  double spin_angle_rad() const { return x_[Model::kGamma]; }
  // The torque of rotor and frame inertia on the output axis at the current state [N m].
  double gyro_torque_Nm() const { return gyro_.gyro_torque_on_frame(x_); }
  HeldInputs held_inputs() const { return {gyro_.inputs.Omega}; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return gyro_; }
  const UGyroPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 3;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"beta_rad", "beta_rate_rad_s", "gamma_rad"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const UGyroPlantParams& p_;
  PlantTiming t_;
  Model gyro_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
};

}  // namespace gyrostab::plants
