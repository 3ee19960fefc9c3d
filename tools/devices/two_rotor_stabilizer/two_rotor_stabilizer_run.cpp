// What a two-rotor stabilizer run reports: the plant of sim/plants/two_rotor_stabilizer_plant.hpp with its
// meters — the frames' peak and final angles, the case angles against the steady states M/k of the final
// disturbance, the law's gain margin; for the gyro frame also a single rotor of spin 2H and case inertia 2B
// (sim/models/two_rotor_gyro_frame.hpp with σ = s = +1) under the same base motion, disturbance and law
// (continuous, integrated beside the plant with the plant's step), and the link torque (TR2); the closed
// loop's nutation measured from β1[k] (a recurrence fitted after the first step, linear_prediction_fit.hpp)
// beside the continuous root (`_predicted`) and the sampled loop's (`_predicted_sampled`, two_rotor_sampled.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/two_rotor_stabilizer_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "tools/devices/two_rotor_stabilizer/two_rotor_sampled.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/two_rotor_stabilizer/two_rotor_stabilizer_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::TwoRotorStabilizerPlant;
using Axis = models::TwoRotorTwoAxis;
using Controller = firmware::BasicTwoRotorStabilizerController<firmware::posix::MonotonicClock>;

// The single rotor of the comparison with the law closed continuously.
struct SingleRotor {
  static constexpr int kStateSize = 4;
  using Model = models::TwoRotorGyroFrame<plants::TwoRotorBase>;
  using State = Model::State;
  mutable Model m;
  plants::TwoRotorDisturbance dist;
  double k, dK;
  void derivative(double t, const State& x, State& dx) const {
    m.inputs.M1S = t >= dist.M1_time_s ? dist.M1_Nm : 0.0;
    m.inputs.M2S = t >= dist.M2_time_s ? dist.M2_Nm : 0.0;
    m.inputs.M1K = -k * x[Model::kBeta] - dK * x[Model::kAlphaRate];
    m.derivative(t, x, dx);
  }
  void project(State&) const {}
};

models::TwoRotorFrameParams single_of(models::TwoRotorFrameParams p) {
  p.spin_sign = 1.0;
  p.link_sign = 1.0;
  return p;
}

class TwoRotorRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::two_rotor_stabilizer::Record;

  explicit TwoRotorRun(const TwoRotorStabilizerScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        single_{SingleRotor::Model(single_of(s.plant.frame), s.plant.base), s.plant.disturbance,
                s.controller.law.k1, s.controller.law.dK1},
        single_rk_(single_),
        single_x_(SingleRotor::State::Zero()),
        gain_margin_(firmware::two_rotor_gain_scale_max(s.controller.law)),
        sampled_(two_rotor_sampled(s)),
        law_every_(std::max<std::int64_t>(1, static_cast<std::int64_t>(s.controller.runtime.control_divisor))),
        fit_(first_step_s(s) + 0.02,
             std::min({first_step_s(s) + 0.02 + s.nutation_window_s, next_step_s(s), s.loop.duration_s}),
             sampled_.timing.period_s,
             static_cast<int>(sampled_.roots.s.size()) + 2),
        window_(s.loop.ticks() / 2, std::max<std::int64_t>(1, static_cast<std::int64_t>(1.0 / s.loop.tick_s()))) {}

  void sense(std::int64_t tick, SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    if (frame()) {
      link_ = plant_.link_torque_Nm(t);
      link_peak_ = std::max(link_peak_, std::fabs(link_));
      const double h = s_.loop.tick_s() / s_.loop.substeps;
      for (int i = 0; i < s_.loop.substeps; ++i) single_rk_.step(t + i * h, h, single_x_);
      single_peak_ = std::max(single_peak_, std::fabs(single_x_[SingleRotor::Model::kAlpha]));
    }
    window_.before_tick(tick, plant_.state(), plant_.held_inputs());
    plant_.advance(tick);
    window_.after_tick(tick, plant_.state());
    if ((tick + 1) % law_every_ == 0)
      fit_.add(static_cast<double>(tick + 1) * s_.loop.tick_s(), plant_.value(Axis::kBeta1));
    alpha_peak_ = std::max(alpha_peak_, std::fabs(plant_.value(Axis::kAlpha)));
    gamma_peak_ = std::max(gamma_peak_, std::fabs(plant_.value(Axis::kGamma)));
    ticks_ = tick + 1;
  }
  bool finite() const { return plant_.finite() && single_x_.allFinite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.alpha_rad = plant_.value(Axis::kAlpha);
    r.gamma_rad = plant_.value(Axis::kGamma);
    r.beta1_rad = plant_.value(Axis::kBeta1);
    r.beta2_rad = plant_.value(Axis::kBeta2);
    r.M1K_Nm = last_.frame1_torque_Nm;
    r.M2K_Nm = last_.frame2_torque_Nm;
    r.single_rotor_alpha_rad = frame() ? single_x_[SingleRotor::Model::kAlpha] : 0.0;
    r.link_torque_Nm = link_;
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const auto& d = s_.plant.disturbance;
    const auto& l = s_.controller.law;
    const double t_end = static_cast<double>(ticks_) * s_.loop.tick_s();
    const double M1 = t_end >= d.M1_time_s ? d.M1_Nm : 0.0;
    const double M2 = t_end >= d.M2_time_s ? d.M2_Nm : 0.0;
    nlohmann::json f{{"alpha_peak_rad", alpha_peak_},
                     {"alpha_final_rad", plant_.value(Axis::kAlpha)},
                     {"beta1_final_rad", plant_.value(Axis::kBeta1)},
                     {"beta1_expected_rad", M1 / l.k1},
                     {"gain_margin", std::isfinite(gain_margin_) ? nlohmann::json(gain_margin_) : nullptr},
                     {"ticks", ticks_}};
    // The least-damped oscillatory pair of the closed loop (the cases' nutation under the rate damping): the
    // continuous root, the sampled loop's, and the one the run shows. The plant's sensors are ideal, so the
    // recurrence of β1[k] is the loop's exactly (on a base at rest).
    const auto number_or_null = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
    f["nutation_decay_rate_per_s_predicted"] = number_or_null(-sampled_.continuous.real());
    f["nutation_frequency_rad_s_predicted"] = number_or_null(sampled_.continuous.imag());
    f["nutation_decay_rate_per_s_predicted_sampled"] = number_or_null(-sampled_.sampled.real());
    f["nutation_frequency_rad_s_predicted_sampled"] = number_or_null(sampled_.sampled.imag());
    f["sampled_loop_max_abs_z"] = sampled_.roots.max_abs_z;
    if (fit_.valid() && std::isfinite(sampled_.continuous.real())) {
      const std::complex<double> m = analysis::nearest_root(fit_.roots(), sampled_.continuous);
      f["nutation_decay_rate_per_s"] = -m.real();
      f["nutation_frequency_rad_s"] = m.imag();
    } else {
      f["nutation_decay_rate_per_s"] = nullptr;
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_measurement"] = std::isfinite(sampled_.continuous.real())
                                      ? "not measured: no disturbance step, or the window ends before enough samples"
                                      : "not measured: the closed loop has no oscillatory root";
    }
    if (frame()) {
      f["single_rotor_alpha_peak_rad"] = single_peak_;
      f["single_rotor_alpha_final_rad"] = single_x_[SingleRotor::Model::kAlpha];
      f["link_torque_peak_Nm"] = link_peak_;
    } else {
      f["gamma_peak_rad"] = gamma_peak_;
      f["beta2_final_rad"] = plant_.value(Axis::kBeta2);
      f["beta2_expected_rad"] = -l.spin_sign * M2 / l.k2;
    }
    return f;
  }

  // report.json "error_estimate": one second from the middle of the run.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics& m, const Plant::HeldInputs& in) {
      m.M1K = in.M1K;
      m.M2K = in.M2K;
    };
    return error_estimate_json<8>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"alpha_rad", "gamma_rad", "beta1_rad", "beta2_rad", "alpha_rate_rad_s", "gamma_rate_rad_s", "beta1_rate_rad_s",
         "beta2_rate_rad_s"},
        "none watched: the motors and the dampers act");
  }

 private:
  bool frame() const { return s_.plant.kind == plants::TwoRotorPlantKind::kGyroFrame; }
  // The first step that acts (a zero step excites nothing); +∞ without one.
  static double first_step_s(const TwoRotorStabilizerScene& s) {
    const auto& d = s.plant.disturbance;
    double t = std::numeric_limits<double>::infinity();
    if (d.M1_Nm != 0.0) t = std::min(t, d.M1_time_s);
    if (d.M2_Nm != 0.0) t = std::min(t, d.M2_time_s);
    return t;
  }
  // The step after it (the window ends there: a second input breaks the recurrence); +∞ without one.
  static double next_step_s(const TwoRotorStabilizerScene& s) {
    const auto& d = s.plant.disturbance;
    const double first = first_step_s(s);
    double t = std::numeric_limits<double>::infinity();
    if (d.M1_Nm != 0.0 && d.M1_time_s > first) t = std::min(t, d.M1_time_s);
    if (d.M2_Nm != 0.0 && d.M2_time_s > first) t = std::min(t, d.M2_time_s);
    return t;
  }

  const TwoRotorStabilizerScene& s_;
  Plant plant_;
  SingleRotor single_;
  dynamics::Rk4<SingleRotor> single_rk_;
  SingleRotor::State single_x_;
  double gain_margin_;
  TwoRotorSampled sampled_;
  std::int64_t law_every_;
  analysis::LinearPredictionMeter fit_;
  ActuatorFrame last_{};
  double alpha_peak_{0.0}, gamma_peak_{0.0}, single_peak_{0.0}, link_{0.0}, link_peak_{0.0};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
};

struct TwoRotorTraits {
  using Scene = TwoRotorStabilizerScene;
  using Binding = TwoRotorRun;
  using Controller = tools::Controller;
  // The law's torque limit on both frame motors.
  static hil::ActuatorLimits actuator_limits(const Scene& s) {
    msg::two_rotor_stabilizer::ActuatorFrame l =
        hil::ActuatorLimits::unlimited<msg::two_rotor_stabilizer::ActuatorFrame>();
    l.frame1_torque_Nm = l.frame2_torque_Nm = s.controller.law.torque_limit_Nm;
    return hil::ActuatorLimits::of(l);
  }
  static nlohmann::json limits(const Scene& s) {
    return {{"motor_torque_limit_Nm", s.controller.law.torque_limit_Nm}};
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_two_rotor_stabilizer_scene(std::unique_ptr<TwoRotorStabilizerScene> s) {
  return std::make_unique<DeviceSceneOf<TwoRotorTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
