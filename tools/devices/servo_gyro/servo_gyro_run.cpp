// What a servo gyro run reports: the plant of sim/plants/servo_gyro_plant.hpp with its meters — over the
// whole drive revolutions after the settling time, the oscillator amplitude α_A and phase φ, the torque peaks
// (M1^KR)max and (M2)max of the applied motor torque and their ratio, the torque amplification, beside the
// book's 1/α_A (14.44) and the general 2/(α_A(1 + |sin φ|)) of sim/models/servo_gyro.hpp; the same ratio from
// the harmonic content (noise-free); the rate loop's tracking; motor power against the dissipation — the CSV
// columns, the half-step error estimate, and the scene's plant and controller for the run modes.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/servo_gyro_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "sim/analysis/servo_drive_sums.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/servo_gyro/servo_gyro_sampled.hpp"
#include "tools/devices/servo_gyro/servo_gyro_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::ServoGyroPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicServoGyroController<firmware::posix::MonotonicClock>;

class ServoGyroRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::servo_gyro::Record;

  explicit ServoGyroRun(const ServoGyroScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        settle_tick_(static_cast<std::int64_t>(std::llround(s.settle_s / s.loop.tick_s()))),
        window_(std::min(settle_tick_, s.loop.ticks() / 2),
                static_cast<std::int64_t>(1.0 / s.loop.tick_s())),
        applies_(rate_loop_applies(s)),
        rate_loop_(applies_ ? servo_gyro_sampled(s) : ServoGyroSampled{}),
        fit_(s.settle_s, applies_ ? s.loop.duration_s : -1.0, s.loop.tick_s(),
             static_cast<int>(rate_loop_.roots.s.size()) + 2, 3) {}

  // The inputs of the fitted recurrence of β' (linear_prediction_fit.hpp): the errors of the signals the rate
  // loop read (the tachometer's, and the axis-1 rate the feed-forward reads) and the torque it did not command.
  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    if (!applies_) return;
    // The feed-forward this frame makes the law add (14.43), applied latency ticks later.
    const std::size_t slots = ff_.size();
    ff_[static_cast<std::size_t>(tick) % slots] =
        s_.controller.law.feedforward
            ? -s_.controller.law.H * std::cos(f.drive_angle_rad) * f.alpha_rate_rad_s
            : 0.0;
    const double v[3] = {f.drive_rate_rad_s - plant_.beta_rate_rad_s(), f.alpha_rate_rad_s - plant_.alpha_rate_rad_s(),
                         coupling_};
    fit_.add(static_cast<double>(tick) * s_.loop.tick_s(), plant_.beta_rate_rad_s(), v);
  }
  // The axis-2 torque the PI did not command over the last tick: the gyroscopic terms of (14.41) (trapezoid
  // over the tick) plus the feed-forward that was applied. With it among the fit's inputs the rate loop's
  // recurrence is exact although the oscillator turns the coupling with cos β (a time-varying loop).
  double gyroscopic_Nm() const {
    const models::ServoGyroParams& g = s_.plant.gyro;
    const double b = plant_.beta_rad(), a1 = plant_.alpha_rate_rad_s();
    return g.H * std::cos(b) * a1 - g.Q * std::sin(b) * std::cos(b) * a1 * a1;
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    const double M2 = plant_.axis2_torque_Nm();
    const Plant::HeldInputs in = plant_.held_inputs();
    const double g0 = applies_ ? gyroscopic_Nm() : 0.0;
    window_.before_tick(tick, plant_.state(), in);
    plant_.advance(tick);
    window_.after_tick(tick, plant_.state());
    if (applies_) {
      const std::int64_t from = tick - s_.loop.latency_ticks;
      const double ff = from >= 0 ? ff_[static_cast<std::size_t>(from) % ff_.size()] : 0.0;
      coupling_ = 0.5 * (g0 + gyroscopic_Nm()) + ff;
    }
    ticks_ = tick + 1;
    if (ticks_ < settle_tick_) return;
    if (!started_) {
      started_ = true;
      beta_start_ = plant_.beta_rad();
    }
    // A completed revolution: the samples so far cover whole revolutions uniformly; keep them.
    const auto revs = static_cast<std::int64_t>(
        std::floor(std::fabs(plant_.beta_rad() - beta_start_) / (2.0 * std::numbers::pi)));
    if (revs > revolutions_) {
      revolutions_ = revs;
      done_ = run_;
    }
    const auto& g = s_.plant.gyro;
    run_.add(plant_.alpha_rad(), plant_.beta_rad(), plant_.alpha_rate_rad_s(), plant_.beta_rate_rad_s(),
             plant_.gyro_torque_axis1_Nm(), M2, s_.controller.reference, g.d1, g.d2);
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.alpha_rad = plant_.alpha_rad();
    r.alpha_rate_rad_s = plant_.alpha_rate_rad_s();
    r.drive_rate_rad_s = plant_.beta_rate_rad_s();
    r.M1_gyro_Nm = plant_.gyro_torque_axis1_Nm();
    r.motor_torque_Nm = last_.motor_torque_Nm;
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const analysis::DriveSums& d = done_;
    nlohmann::json f{{"drive_rate_reference_rad_s", s_.controller.reference},
                     {"revolutions", revolutions_},
                     {"statistics_from_s", s_.settle_s},
                     {"ticks", ticks_}};
    rate_loop_figures(f);
    const char* measured[] = {"alpha_A_rad",
                              "phase_rad",
                              "M1_max_Nm",
                              "M2_max_Nm",
                              "torque_gain",
                              "torque_gain_book",
                              "torque_gain_general",
                              "M1_amplitude_harmonic_Nm",
                              "M2_max_harmonic_Nm",
                              "torque_gain_harmonic",
                              "drive_rate_mean_rad_s",
                              "drive_rate_error_max_rad_s",
                              "motor_power_W",
                              "dissipation_W"};
    if (d.n == 0) {  // no whole revolution after settling (a short run)
      for (const char* key : measured) f[key] = nullptr;
      return f;
    }
    const double n = static_cast<double>(d.n);
    const analysis::HarmonicFit::Result a = d.alpha_fit.solve(), m1 = d.m1_fit.solve(), m2 = d.m2_fit.solve();
    const double alpha_A = a.amplitude();
    const double phase = a.phase();
    const double m2_harmonic = std::fabs(m2.mean) + m2.amplitude();
    const double m1_harmonic = m1.amplitude();
    f["alpha_A_rad"] = alpha_A;
    f["phase_rad"] = phase;
    f["M1_max_Nm"] = d.m1_peak;
    f["M2_max_Nm"] = d.m2_peak;
    f["torque_gain"] = d.m1_peak / d.m2_peak;
    f["torque_gain_book"] = 1.0 / alpha_A;                                            // (14.44)
    f["torque_gain_general"] = 2.0 / (alpha_A * (1.0 + std::fabs(std::sin(phase))));  // the model header's
    f["M1_amplitude_harmonic_Nm"] = m1_harmonic;
    f["M2_max_harmonic_Nm"] = m2_harmonic;
    f["torque_gain_harmonic"] = m1_harmonic / m2_harmonic;
    f["drive_rate_mean_rad_s"] = d.rate / n;
    f["drive_rate_error_max_rad_s"] = d.rate_error_peak;
    f["motor_power_W"] = d.motor_power / n;
    f["dissipation_W"] = d.dissipation / n;
    return f;
  }

  // The rate loop's pair (servo_gyro_sampled.hpp): measured as the two roots of the fitted recurrence nearest
  // the sampled pair's centre.
  void rate_loop_figures(nlohmann::json& f) const {
    if (!applies_) {
      f["rate_loop"] = "not computed: the law runs below the tick rate";
      return;
    }
    const analysis::PairShape c = analysis::pair_shape(rate_loop_.continuous[0], rate_loop_.continuous[1]);
    const analysis::PairShape sp = analysis::pair_shape(rate_loop_.sampled[0], rate_loop_.sampled[1]);
    f["rate_loop_natural_frequency_rad_s_predicted"] = c.natural_frequency;
    f["rate_loop_damping_ratio_predicted"] = c.damping_ratio;
    f["rate_loop_natural_frequency_rad_s_predicted_sampled"] = sp.natural_frequency;
    f["rate_loop_damping_ratio_predicted_sampled"] = sp.damping_ratio;
    f["sampled_loop_max_abs_z"] = rate_loop_.roots.max_abs_z;
    f["rate_loop_fit_samples"] = fit_.samples();
    f["rate_loop_natural_frequency_rad_s"] = nullptr;
    f["rate_loop_damping_ratio"] = nullptr;
    if (!fit_.valid()) return;
    const std::array<std::complex<double>, 2> m =
        analysis::nearest_pair(fit_.roots(), 0.5 * (rate_loop_.sampled[0] + rate_loop_.sampled[1]));
    const analysis::PairShape got = analysis::pair_shape(m[0], m[1]);
    f["rate_loop_natural_frequency_rad_s"] = got.natural_frequency;
    f["rate_loop_damping_ratio"] = got.damping_ratio;
  }
  static bool rate_loop_applies(const ServoGyroScene& s) {
    return s.controller.runtime.control_divisor == 1;
  }

  // report.json "error_estimate": 1 s of the steady drive from the end of the settling time (the run's middle
  // if that is earlier).
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics& p, const Plant::HeldInputs& in) {
      p.command_Nm = in.command_Nm;
      p.brake_Nms = in.brake_Nms;
    };
    return error_estimate_json<4>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"},
        "none watched: the drive motor and friction act");
  }

 private:
  const ServoGyroScene& s_;
  Plant plant_;
  std::int64_t settle_tick_;
  ActuatorFrame last_{};
  bool started_{false};
  double beta_start_{0.0};
  std::int64_t revolutions_{0};
  analysis::DriveSums run_{}, done_{};  // the sums so far, and at the last completed revolution
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
  bool applies_;
  ServoGyroSampled rate_loop_;
  analysis::LinearPredictionMeter fit_;
  std::array<double, kMaxLatencyTicks + 1> ff_{};  // the feed-forward of the last frames, by tick [N m]
  double coupling_{0.0};  // the torque the PI did not command over the last tick [N m]
};

struct ServoGyroTraits {
  using Scene = ServoGyroScene;
  using Binding = ServoGyroRun;
  using Controller = tools::Controller;
  // The law's torque limit on the axis-2 motor.
  static hil::ActuatorLimits actuator_limits(const Scene& s) {
    msg::servo_gyro::ActuatorFrame l = hil::ActuatorLimits::unlimited<msg::servo_gyro::ActuatorFrame>();
    l.motor_torque_Nm = s.controller.law.torque_limit_Nm;
    return hil::ActuatorLimits::of(l);
  }
  static nlohmann::json limits(const Scene& s) { return {{"motor_torque_limit_Nm", s.controller.law.torque_limit_Nm}}; }
};

}  // namespace

std::unique_ptr<DeviceScene> make_servo_gyro_scene(std::unique_ptr<ServoGyroScene> s) {
  return std::make_unique<DeviceSceneOf<ServoGyroTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
