// A free two-gimbal position gyro on a yawing, pitching, rolling vehicle, as a scene runs it (Magnus §12.1,
// (12.2)-(12.20)): the vehicle attitude of sim/models/position_gyro_gimbal_error.hpp integrated by RK4 with
// the scene's sub-steps from the prescribed rates (or a scene's [motion]: prescribed, recorded), and the gimbal
// pick-offs read from it. The gyro has no
// torquers and no brake: the controller commands nothing.
//
// State: q_WF (x, y, z, w) [-] (named accessors below). Frames: the gimbal error's own
// (tools/devices/gimbal_error/gimbal_error_signals.toml, docs/icd/gimbal_error.md): in, no command; out,
// roll_rad, pitch_rad, yaw_rad = φ, ϑ, ψ of the prescribed motion (the vehicle's own attitude reference,
// wrapped to [−π, π)); body_rate_rad_s = w_WF_F (body rates); alpha_rad = α, beta_rad = β (ideal pick-offs,
// α wrapped to [−π, π)).
// No random streams. Allocation-free after construction. Docs: docs/models/gimbal-error.md. Oracle:
// tests/oracle/gimbal_error_test.cpp; the shipped scene sim/scenes/gimbal-error-heading-gyro-turn.toml runs in
// tests/determinism and tests/alloc.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/gimbal_error_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/position_gyro_gimbal_error.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"

namespace gyrostab::plants {

// An angle in [−π, π).
inline double wrap_angle(double a) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double w = a - kTwoPi * std::floor((a + std::numbers::pi) / kTwoPi);
  return w >= std::numbers::pi ? w - kTwoPi : w;
}

struct GimbalErrorPlantParams {
  models::PositionGyroGimbalErrorParams gyro{};
};

class GimbalErrorPlant {
 public:
  using SensorFrame = msg::gimbal_error::SensorFrame;
  using ActuatorFrame = msg::gimbal_error::ActuatorFrame;
  using Model = models::PositionGyroGimbalError;
  using Dynamics = Model;
  using State = Model::State;
  struct HeldInputs {};  // nothing is held: the gyro takes no command

  GimbalErrorPlant(const GimbalErrorPlantParams& p, const PlantTiming& t)
      : p_(p), t_(t), model_(p.gyro), integ_(model_), driver_(integ_, t.tick_ns, t.substeps) {
    x_ = model_.initial_state(0.0);
    angles_ = model_.gimbal_angles_of(x_);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    const double t = time_s(tick);
    const std::array<double, 3> e = p_.gyro.euler(t);
    f.roll_rad = wrap_angle(e[0]);
    f.pitch_rad = wrap_angle(e[1]);
    f.yaw_rad = wrap_angle(e[2]);
    const dynamics::Vec3 w = p_.gyro.rate(t);
    f.body_rate_rad_s[0] = w.x();
    f.body_rate_rad_s[1] = w.y();
    f.body_rate_rad_s[2] = w.z();
    f.alpha_rad = wrap_angle(angles_.alpha);
    f.beta_rad = angles_.beta;
  }

  void actuate(const ActuatorFrame&) {}

  // Integrates [k, k + 1).
  void advance(std::int64_t tick) {
    driver_.advance_tick(tick, x_);
    angles_ = model_.gimbal_angles_of(x_);
  }

  bool finite() const { return x_.allFinite(); }

  double time_s(std::int64_t tick) const { return 1e-9 * static_cast<double>(tick * t_.tick_ns); }
  // The gimbal angles at the current state [rad] (α unwrapped in (−π, π]).
  double alpha_rad() const { return angles_.alpha; }
  double beta_rad() const { return angles_.beta; }
  HeldInputs held_inputs() const { return {}; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return model_; }
  const GimbalErrorPlantParams& params() const { return p_; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 4;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"q_WF_x", "q_WF_y", "q_WF_z", "q_WF_w"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const GimbalErrorPlantParams& p_;
  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  models::GimbalAngles angles_{};
};

}  // namespace gyrostab::plants
