// The two-rotor stabilizers as they run in a scene (Magnus §14.3.4, Figs. 14.7, 14.8): kind kGyroFrame — the
// gyro frame of sim/models/two_rotor_gyro_frame.hpp on a moving base (constant rates plus a harmonic rotation
// about one base axis); kind kTwoAxis — the two-axis stabilizer of sim/models/two_rotor_two_axis.hpp (fixed
// base). Held motor torques from the firmware, step disturbance torques, integrated by RK4 with the scene's
// sub-steps. Sensors: ideal pick-offs (angles and rates as they are; the loops' noise is not the subject).
//
// State (one layout for both kinds): [α, γ, β1, β2 (rad), α', γ', β1', β2' (rad/s)]; the gyro frame uses α and
// β1 = β (the linked cases' angle), γ and β2 stay 0.
// Frames: the two-rotor stabilizer's own (tools/devices/two_rotor_stabilizer/two_rotor_stabilizer_signals.toml,
// docs/icd/two_rotor_stabilizer.md): in, frame1_torque_Nm = M1^K on frame 1 and frame2_torque_Nm = M2^K on
// frame 2 (two-axis; the gyro frame ignores it); out, γ, β2, γ', β2' (two-axis; 0 for the gyro frame) and α, β1,
// α', β1' (frame 1 and the case its loop reads). No brake.
// Allocation-free after construction. Docs: docs/models/two-rotor-stabilizer.md. Oracle:
// tests/oracle/two_rotor_stabilizer_test.cpp; the shipped scenes sim/scenes/two-rotor-*.toml run in
// tests/determinism and tests/alloc.
#pragma once

#include <cmath>
#include <cstdint>

#include "gyrostab_signals/two_rotor_stabilizer_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/two_rotor_gyro_frame.hpp"
#include "sim/models/two_rotor_two_axis.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"

namespace gyrostab::plants {

enum class TwoRotorPlantKind : std::uint8_t { kGyroFrame, kTwoAxis };

// Base motion of the gyro frame: constant rates plus Φ sin(ν t) about base axis `axis` (0, 1, 2).
struct TwoRotorBase {
  dynamics::Vec3 rate{dynamics::Vec3::Zero()};  // constant base rate, base axes [rad/s]
  int axis{1};                                  // axis of the harmonic rotation (0-based)
  double amplitude{0.0};                        // Φ [rad]
  double frequency{0.5};                        // ν [rad/s]
  models::BaseSample operator()(double t) const {
    models::BaseSample b{rate, dynamics::Vec3::Zero(), dynamics::Vec3::UnitZ()};
    if (amplitude != 0.0) {
      b.w_B[axis] += amplitude * frequency * std::cos(frequency * t);
      b.dw_B[axis] = -amplitude * frequency * frequency * std::sin(frequency * t);
    }
    return b;
  }
};

struct TwoRotorDisturbance {
  double M1_Nm{0.0}, M1_time_s{0.0};  // step on frame 1 [N m], from [s]
  double M2_Nm{0.0}, M2_time_s{0.0};  // step on case I (gyro frame) / frame 2 (two-axis) [N m], from [s]
};

struct TwoRotorPlantParams {
  TwoRotorPlantKind kind{TwoRotorPlantKind::kGyroFrame};
  models::TwoRotorFrameParams frame{};
  models::TwoRotorTwoAxisParams two_axis{};
  TwoRotorBase base{};
  TwoRotorDisturbance disturbance{};
};

// Both models behind one 8-state derivative; the held torques as inputs.
struct TwoRotorDynamics {
  static constexpr int kStateSize = 8;
  using State = Eigen::Matrix<double, 8, 1>;
  using Frame = models::TwoRotorGyroFrame<TwoRotorBase>;
  using Axis = models::TwoRotorTwoAxis;
  TwoRotorPlantKind kind;
  mutable Frame frame;
  mutable Axis axis;
  TwoRotorDisturbance disturbance;
  double M1K{0.0}, M2K{0.0};  // held motor torques [N m]

  double M1S(double t) const { return t >= disturbance.M1_time_s ? disturbance.M1_Nm : 0.0; }
  double M2S(double t) const { return t >= disturbance.M2_time_s ? disturbance.M2_Nm : 0.0; }

  void derivative(double t, const State& x, State& dx) const {
    if (kind == TwoRotorPlantKind::kTwoAxis) {
      axis.inputs = {M1S(t), M2S(t), M1K, M2K};
      axis.derivative(t, x, dx);
      return;
    }
    frame.inputs = {M1S(t), M1K, M2S(t)};
    const Frame::State xf = Frame::make_state(x[Axis::kAlpha], x[Axis::kBeta1], x[Axis::kAlphaRate],
                                              x[Axis::kBeta1Rate]);
    Frame::State df;
    frame.derivative(t, xf, df);
    dx.setZero();
    dx[Axis::kAlpha] = df[Frame::kAlpha];
    dx[Axis::kBeta1] = df[Frame::kBeta];
    dx[Axis::kAlphaRate] = df[Frame::kAlphaRate];
    dx[Axis::kBeta1Rate] = df[Frame::kBetaRate];
  }
  void project(State&) const {}
};

class TwoRotorStabilizerPlant {
 public:
  using SensorFrame = msg::two_rotor_stabilizer::SensorFrame;
  using ActuatorFrame = msg::two_rotor_stabilizer::ActuatorFrame;
  using Dynamics = TwoRotorDynamics;
  using State = Dynamics::State;
  using Axis = models::TwoRotorTwoAxis;
  struct HeldInputs {
    double M1K{0.0}, M2K{0.0};
  };

  TwoRotorStabilizerPlant(const TwoRotorPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        dyn_{p.kind, Dynamics::Frame(p.frame, p.base), Axis(p.two_axis), p.disturbance},
        integ_(dyn_),
        driver_(integ_, t.tick_ns, t.substeps) {
    x_.setZero();
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.alpha_rad = x_[Axis::kAlpha];
    f.alpha_rate_rad_s = x_[Axis::kAlphaRate];
    f.beta1_rad = x_[Axis::kBeta1];
    f.beta1_rate_rad_s = x_[Axis::kBeta1Rate];
    f.gamma_rad = x_[Axis::kGamma];
    f.gamma_rate_rad_s = x_[Axis::kGammaRate];
    f.beta2_rad = x_[Axis::kBeta2];
    f.beta2_rate_rad_s = x_[Axis::kBeta2Rate];
  }

  void actuate(const ActuatorFrame& cmd) {
    dyn_.M1K = cmd.frame1_torque_Nm;
    dyn_.M2K = p_.kind == TwoRotorPlantKind::kTwoAxis ? cmd.frame2_torque_Nm : 0.0;
  }

  void advance(std::int64_t tick) { driver_.advance_tick(tick, x_); }
  bool finite() const { return x_.allFinite(); }

  double value(int i) const { return x_[i]; }
  // Torque the link puts on case I (gyro frame) at the start of the tick [N m] (TR2).
  double link_torque_Nm(double t) const {
    if (p_.kind != TwoRotorPlantKind::kGyroFrame) return 0.0;
    dyn_.frame.inputs = {dyn_.M1S(t), dyn_.M1K, dyn_.M2S(t)};
    const auto xf = Dynamics::Frame::make_state(x_[Axis::kAlpha], x_[Axis::kBeta1], x_[Axis::kAlphaRate],
                                                x_[Axis::kBeta1Rate]);
    return dyn_.frame.link_torque(t, xf);
  }
  HeldInputs held_inputs() const { return {dyn_.M1K, dyn_.M2K}; }
  const State& state() const { return x_; }
  // Sets the state (the loop's linearisation probes sense() with unit states: two_rotor_sampled.cpp).
  void set_state(const State& x) { x_ = x; }
  const Dynamics& dynamics() const { return dyn_; }
  const TwoRotorPlantParams& params() const { return p_; }

  static constexpr int kGuardedStates = 8;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"alpha_rad",        "gamma_rad",        "beta1_rad",
                                 "beta2_rad",        "alpha_rate_rad_s", "gamma_rate_rad_s",
                                 "beta1_rate_rad_s", "beta2_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  const TwoRotorPlantParams& p_;
  PlantTiming t_;
  Dynamics dyn_;
  dynamics::Rk4<Dynamics> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Dynamics>> driver_;
  State x_;
};

}  // namespace gyrostab::plants
