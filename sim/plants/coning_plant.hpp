// The coning platform as a scene runs it (Magnus §15.5; sim/models/coning_platform.hpp): a platform on a
// vibrating base, turned about its axis 3 by a geared servo at the held drive voltage, carrying a P- or
// I-gyro with its input axis along the platform's axis 3; integrated by RK4 with the scene's sub-steps. The base
// moves by the platform's vibration generator or by the scene's [motion] (prescribed, recorded).
// Start: at rest relative to the base (φ = φ' = 0), the gyro at β = β' = 0.
//
// State: [φ (rad), φ' (rad/s), β (rad), β' (rad/s)] (named accessors below). Frames: the coning platform's
// own (tools/devices/coning/coning_signals.toml, docs/icd/coning.md): in, drive_voltage_V = V [V], clipped at
// ±voltage_limit (the safe state's zero voltage stops the drive); out, platform_azimuth_rad = φ wrapped to
// (−π, π] (the drive's encoder, ideal), platform_rate_rad_s = the platform's absolute angular velocity in
// platform axes (truth, for logs), beta_rad, beta_rate_rad_s = β, β' (the gyro's pick-off, ideal).
// No random streams. Allocation-free after construction. Docs: docs/models/coning.md. Oracle:
// tests/oracle/coning_test.cpp; the shipped scenes sim/scenes/coning-*.toml run in tests/determinism and
// tests/alloc.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/coning_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/coning_platform.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"

namespace gyrostab::plants {

struct ConingPlantParams {
  models::ConingPlatformParams platform{};
  double voltage_limit{10.0};  // the drive's supply: |V| ≤ this [V]
  // The scene's [motion] (sim/motion/scene_base_motion.hpp) when it moves the base instead of the platform's
  // own vibration generator; with `from_motion` false the base is ConingPlatform::generated(platform).
  bool from_motion{false};
  motion::SceneBaseMotion base{};
};

class ConingPlant {
 public:
  using SensorFrame = msg::coning::SensorFrame;
  using ActuatorFrame = msg::coning::ActuatorFrame;
  using Model = models::ConingPlatform;
  using Dynamics = Model;
  using State = Model::State;
  struct HeldInputs {
    double voltage{0.0};  // [V]
  };

  ConingPlant(const ConingPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        model_(p.from_motion ? Model(p.platform, p.base) : Model(p.platform)),
        integ_(model_), driver_(integ_, t.tick_ns, t.substeps) {
    x_ = Model::make_state(0.0, 0.0, 0.0, 0.0);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.platform_azimuth_rad = std::remainder(phi_rad(), 2.0 * std::numbers::pi);
    const dynamics::Vec3 w = platform_rate_rad_s(tick_time(tick));
    for (int i = 0; i < 3; ++i) f.platform_rate_rad_s[i] = w[i];
    f.beta_rad = beta_rad();
    f.beta_rate_rad_s = beta_rate_rad_s();
  }

  void actuate(const ActuatorFrame& cmd) {
    model_.inputs.voltage = std::clamp(cmd.drive_voltage_V, -p_.voltage_limit, p_.voltage_limit);
  }

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }

  bool finite() const { return x_.allFinite(); }

  double tick_time(std::int64_t tick) const { return 1e-9 * static_cast<double>(tick * t_.tick_ns); }
  double phi_rad() const { return x_[Model::kPhi]; }
  double phi_rate_rad_s() const { return x_[Model::kPhiRate]; }
  double beta_rad() const { return x_[Model::kBeta]; }
  double beta_rate_rad_s() const { return x_[Model::kBetaRate]; }
  // The platform's absolute angular velocity at time t, platform axes [rad/s].
  dynamics::Vec3 platform_rate_rad_s(double t) const {
    dynamics::Vec3 w, dw;
    model_.platform_rates(t, x_, w, dw);
    return w;
  }
  // The gyro's reading: P (c2/H) β [rad/s]; I (d2/H) β [rad].
  double indicated() const { return sensors::coning_gyro_indicated(p_.platform.gyro, beta_rad()); }
  HeldInputs held_inputs() const { return {model_.inputs.voltage}; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return model_; }
  const ConingPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 4;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"phi_rad", "phi_rate_rad_s", "beta_rad", "beta_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const ConingPlantParams& p_;
  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
};

}  // namespace gyrostab::plants
