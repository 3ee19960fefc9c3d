// What a monorail run reports: the plant of sim/plants/monorail_plant.hpp with its meters — tilt statistics
// after the settling time, the case-angle and motor-torque peaks, the steady leans into the gust and into the
// curve (the mean over the last second of each plateau) beside the small-angle prediction of (14.6), the
// overturning — the gain window (k_lo, k_hi) of (14.5) on the straight and in the curve with the configured
// k, the decay rates of (14.3)/(14.6), the CSV columns, the half-step error estimate, and the scene's plant
// and controller for the run modes.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "sim/analysis/running_stats.hpp"
#include "sim/analysis/window_mean.hpp"
#include "tools/devices/monorail/monorail_curve.hpp"
#include "gyrostab_signals/monorail_outputs.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/monorail/monorail_sampled.hpp"
#include "tools/devices/monorail/monorail_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::MonorailPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicMonorailController<firmware::posix::MonotonicClock>;

nlohmann::json json_of(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

// Where a steady lean is measured: the last second of a constant load (the gust's plateau, the curve's
// constant part), clipped to the scene's duration; inactive if there is no such plateau.
struct LeanWindow {
  bool active{false};
  double from_s{0.0}, to_s{0.0};
};

LeanWindow plateau_window(double plateau_from, double plateau_to, double duration_s) {
  LeanWindow w;
  w.to_s = std::min(plateau_to, duration_s);
  w.from_s = std::max(plateau_from, w.to_s - 1.0);
  w.active = std::isfinite(plateau_from) && w.to_s > w.from_s;
  return w;
}

class MonorailRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::monorail::Record;

  explicit MonorailRun(const MonorailScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        settle_tick_(tick_at(s.settle_s)),
        window_(first_load_tick(), static_cast<std::int64_t>(1.0 / s.loop.tick_s())),
        divisor_(std::max<std::int64_t>(1, static_cast<std::int64_t>(s.controller.runtime.control_divisor))),
        release_fit_(0.02, release_end_s(s), s.loop.tick_s() * static_cast<double>(divisor_), release_fit_order(s),
                     divisor_ == 1 ? 4 : 0) {
    const motion::Gust& g = s.plant.track.gust;
    const motion::CurveProfile& c = s.plant.track.curve;
    gust_window_ = g.M1 != 0.0
                       ? plateau_window(g.start_s + g.rise_s, g.start_s + g.duration_s, s.loop.duration_s)
                       : LeanWindow{};
    curve_window_ = c.Omega3 != 0.0 ? plateau_window(c.start_s + c.transition_s, c.end_s, s.loop.duration_s)
                                    : LeanWindow{};
    set_window(gust_window_, gust_tilt_, gust_case_);
    set_window(curve_window_, curve_tilt_, curve_case_);
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    // What the frame got wrong (noise, encoder counts): the loop's inputs for the release's fit.
    sensor_error_[0] = f.tilt_rad - plant_.tilt_rad();
    sensor_error_[1] = f.tilt_rate_rad_s - plant_.tilt_rate_rad_s();
    sensor_error_[2] = f.case_angle_rad - plant_.case_angle_rad();
    sensor_error_[3] = f.case_rate_rad_s - plant_.case_rate_rad_s();
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    const Plant::HeldInputs in = plant_.held_inputs();
    window_.before_tick(tick, plant_.state(), in);
    plant_.advance(tick);
    window_.after_tick(tick, plant_.state());
    const std::int64_t now = tick + 1;  // the state is at the start of tick + 1
    const double phi = plant_.tilt_rad(), beta = plant_.case_angle_rad();
    if (now >= settle_tick_) tilt_.add(phi);
    case_peak_ = std::fmax(case_peak_, std::fabs(beta));
    torque_peak_ = std::fmax(torque_peak_, std::fabs(in.command_Nm));
    gust_tilt_.add(now, phi);
    gust_case_.add(now, beta);
    curve_tilt_.add(now, phi);
    curve_case_.add(now, beta);
    if (overturned_tick_ < 0 && plant_.overturned()) overturned_tick_ = now;
    if (now % divisor_ == 0) release_fit_.add(static_cast<double>(now) * s_.loop.tick_s(), phi, sensor_error_.data());
    ticks_ = now;
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    const double t =
        1e-9 * static_cast<double>((static_cast<std::int64_t>(last_.tick) + 1) * s_.loop.tick_ns);
    r.tilt_rad = plant_.tilt_rad();
    r.case_angle_rad = plant_.case_angle_rad();
    r.tilt_rate_rad_s = plant_.tilt_rate_rad_s();
    r.case_rate_rad_s = plant_.case_rate_rad_s();
    r.Omega3_rad_s = plant_.Omega3_rad_s(t);
    r.gust_moment_Nm = plant_.gust_moment_Nm(t);
    r.centrifugal_moment_Nm = plant_.centrifugal_moment_Nm(t);
    r.motor_torque_Nm = last_.motor_torque_Nm;
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const models::MonorailParams& car = s_.plant.car;
    const motion::MonorailTrack& track = s_.plant.track;
    const firmware::MonorailMotorParams& law = s_.controller.law;
    const double d_total = law.d + law.d_mechanical;
    const double W = track.curve.Omega3;
    const firmware::MonorailGainWindow straight = firmware::monorail_gain_window(law);
    const firmware::MonorailGainWindow curve = firmware::monorail_gain_window(law_in_curve(law, W));
    const double tick_s = s_.loop.tick_s();
    // The same loops sampled as the closed loop runs them (hold, period, latency): monorail_sampled.hpp.
    const analysis::SampledTiming timing = monorail_timing(s_.controller, tick_s, s_.loop.latency_ticks);
    const MonorailSampled straight_sampled = monorail_sampled(car, s_.controller, 0.0, timing);
    const MonorailSampled curve_sampled = monorail_sampled(car, s_.controller, W, timing);
    nlohmann::json f = {
        {"tilt_rms_rad", tilt_.rms()},
        {"tilt_max_rad", tilt_.peak},
        {"case_angle_max_rad", case_peak_},
        {"motor_torque_max_Nm", torque_peak_},
        {"k_Nm_per_rad", law.k},
        {"k_lo_Nm_per_rad", straight.k_min},
        {"k_hi_Nm_per_rad", straight.k_max},
        {"omega_P_rad_s", straight.omega_P},
        {"omega_N_rad_s", straight.omega_N},
        {"decay_rate_per_s_predicted", -max_real_root(car, law.k, d_total, 0.0)},
        {"curve_Omega3_rad_s", W},
        {"curve_H_Omega3_Nm_per_rad", car.H * W},
        {"curve_radius_m", W != 0.0 && track.speed_m_s > 0.0 ? nlohmann::json(track.speed_m_s / std::fabs(W))
                                                             : nlohmann::json()},
        // (14.6)'s necessary condition; violated by (14.7) c > HΩ3 > q.
        {"curve_condition_14_7_holds", (car.c - car.H * W) * (car.q - car.H * W) > 0.0},
        {"curve_k_lo_Nm_per_rad", curve.gyro_strong_enough ? nlohmann::json(curve.k_min) : nlohmann::json()},
        {"curve_k_hi_Nm_per_rad", curve.gyro_strong_enough ? nlohmann::json(curve.k_max) : nlohmann::json()},
        {"curve_decay_rate_per_s_predicted", -max_real_root(car, law.k, d_total, W)},
        {"gust_lean_rad", json_of(gust_tilt_.mean())},
        {"gust_lean_rad_predicted", predicted_lean(gust_window_)},
        {"gust_case_angle_rad", json_of(gust_case_.mean())},
        {"gust_case_angle_rad_predicted", predicted_case_angle(gust_window_)},
        {"curve_lean_rad", json_of(curve_tilt_.mean())},
        {"curve_lean_rad_predicted", predicted_lean(curve_window_)},
        {"curve_case_angle_rad", json_of(curve_case_.mean())},
        {"curve_case_angle_rad_predicted", predicted_case_angle(curve_window_)},
        {"overturned", overturned_tick_ >= 0},
        {"overturned_at_s", overturned_tick_ >= 0
                                ? nlohmann::json(static_cast<double>(overturned_tick_) * tick_s)
                                : nlohmann::json()},
        {"statistics_from_s", s_.settle_s},
        {"ticks", ticks_}};
    f["decay_rate_per_s_predicted_sampled"] = straight_sampled.decay_rate_per_s;
    // The release from phi0 on the straight, before the first load: the slowest mode of the recurrence fitted
    // to φ[k] with the frames' errors as inputs (linear_prediction_fit.hpp).
    if (release_fit_.valid() && s_.plant.track.curve(0.0) == 0.0) {
      double slowest = -std::numeric_limits<double>::infinity();
      for (const std::complex<double>& r : straight_sampled.roots.s) slowest = std::max(slowest, r.real());
      std::complex<double> want{slowest, 0.0};
      for (const std::complex<double>& r : straight_sampled.roots.s)
        if (r.real() == slowest) want = {r.real(), std::fabs(r.imag())};
      const std::complex<double> m = analysis::nearest_root(release_fit_.roots(), want);
      f["decay_rate_per_s"] = -m.real();
    } else {
      f["decay_rate_per_s"] = nullptr;
    }
    f["curve_decay_rate_per_s_predicted_sampled"] = curve_sampled.decay_rate_per_s;
    f["sampled_loop_max_abs_z"] = std::max(straight_sampled.roots.max_abs_z, curve_sampled.roots.max_abs_z);
    f["gust_lean_rad_predicted_sampled"] = predicted_sampled(gust_window_, timing, 0);
    f["gust_case_angle_rad_predicted_sampled"] = predicted_sampled(gust_window_, timing, 1);
    f["curve_lean_rad_predicted_sampled"] = predicted_sampled(curve_window_, timing, 0);
    f["curve_case_angle_rad_predicted_sampled"] = predicted_sampled(curve_window_, timing, 1);
    return f;
  }

  // report.json "error_estimate": 1 s from the first load (the gust's or the curve's start, else t = 0; the
  // run's middle if that is earlier), where the car and the case move most.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics& p, const Plant::HeldInputs& in) {
      p.command_Nm = in.command_Nm;
      p.brake_Nms = in.brake_Nms;
    };
    return error_estimate_json<4>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"tilt_rad", "case_angle_rad", "tilt_rate_rad_s", "case_rate_rad_s"},
        "none watched: gust, curve, motor and brake act");
  }

 private:
  std::int64_t tick_at(double t_s) const {
    if (!std::isfinite(t_s)) return std::numeric_limits<std::int64_t>::max();
    return static_cast<std::int64_t>(std::llround(t_s / s_.loop.tick_s()));
  }
  void set_window(const LeanWindow& w, analysis::WindowMean& tilt, analysis::WindowMean& case_angle) const {
    tilt.from = case_angle.from = w.active ? tick_at(w.from_s) : 0;
    tilt.to = case_angle.to = w.active ? tick_at(w.to_s) : 0;
  }
  // The release's window ends at the first load (gust or curve), 20 s at most.
  static double release_end_s(const MonorailScene& s) {
    const motion::Gust& g = s.plant.track.gust;
    const motion::CurveProfile& c = s.plant.track.curve;
    double t = std::min(20.0, s.loop.duration_s);
    if (g.M1 != 0.0) t = std::min(t, g.start_s);
    if (c.Omega3 != 0.0) t = std::min(t, c.start_s);
    return t;
  }
  static int release_fit_order(const MonorailScene& s) {
    const MonorailSampled m = monorail_sampled(s.plant.car, s.controller, 0.0,
                                               monorail_timing(s.controller, s.loop.tick_s(), s.loop.latency_ticks));
    return static_cast<int>(m.roots.s.size()) + 2;
  }

  std::int64_t first_load_tick() const {
    const motion::Gust& g = s_.plant.track.gust;
    const motion::CurveProfile& c = s_.plant.track.curve;
    double t = std::numeric_limits<double>::infinity();
    if (g.M1 != 0.0) t = std::min(t, g.start_s);
    if (c.Omega3 != 0.0) t = std::min(t, c.start_s);
    if (!std::isfinite(t)) t = 0.0;
    return std::min(tick_at(t), s_.loop.ticks() / 2);
  }

  // Small-angle steady state of (14.6) with the law M2 = k (φ + tilt bias) − d β' under the window's constant
  // roll moment M1 (gust + c v Ω3 / g), at the window's middle: A φ'' + Hβ' + (HΩ3 − c) φ = M1 gives
  // φ = −M1 / (c − HΩ3) — the car leans against the moment, whatever the gains — and
  // B β'' + ... + (HΩ3 − q) β − k φ_measured = 0 gives β = −k (φ + bias) / (q − HΩ3).
  static double window_time(const LeanWindow& w) { return 0.5 * (w.from_s + w.to_s); }
  nlohmann::json predicted_lean(const LeanWindow& w) const {
    if (!w.active) return nlohmann::json();
    const models::MonorailParams& car = s_.plant.car;
    const double t = window_time(w), W = s_.plant.track.curve(t);
    const double M1 = s_.plant.track.gust(t) + car.c * plant_.lateral_g(t);
    return -M1 / (car.c - car.H * W);
  }
  nlohmann::json predicted_case_angle(const LeanWindow& w) const {
    if (!w.active) return nlohmann::json();
    const models::MonorailParams& car = s_.plant.car;
    const double t = window_time(w), W = s_.plant.track.curve(t);
    const double phi = predicted_lean(w).get<double>();
    return -s_.controller.law.k * (phi + s_.plant.sensors.tilt_bias_rad) / (car.q - car.H * W);
  }

  // The sampled loop's fixed point under the window's moment and the tilt bias: [φ, β][which]. With the car's
  // large-angle terms (the case settles at 0.17-0.22 rad in the shipped scene, where sin β is 0.5-0.8 % below β);
  // the linear fixed point where that does not converge.
  nlohmann::json predicted_sampled(const LeanWindow& w, const analysis::SampledTiming& timing, int which) const {
    if (!w.active) return nlohmann::json();
    const models::MonorailParams& car = s_.plant.car;
    const double t = window_time(w), W = s_.plant.track.curve(t);
    const double bias = s_.plant.sensors.tilt_bias_rad;
    Eigen::Vector2d x = monorail_sampled_steady_large_angle(car, s_.controller, W, timing, s_.plant.track.gust(t),
                                                            plant_.lateral_g(t), bias);
    if (!x.allFinite())
      x = monorail_sampled_steady(car, s_.controller, W, timing, s_.plant.track.gust(t) + car.c * plant_.lateral_g(t), bias);
    return std::isfinite(x[which]) ? nlohmann::json(x[which]) : nlohmann::json();
  }

  const MonorailScene& s_;
  Plant plant_;
  std::int64_t settle_tick_;
  LeanWindow gust_window_, curve_window_;
  analysis::WindowMean gust_tilt_, gust_case_, curve_tilt_, curve_case_;
  ActuatorFrame last_{};
  analysis::RunningStats tilt_;
  double case_peak_{0.0}, torque_peak_{0.0};
  std::int64_t overturned_tick_{-1};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
  std::int64_t divisor_;
  analysis::LinearPredictionMeter release_fit_;
  std::array<double, 4> sensor_error_{};
};

struct MonorailTraits {
  using Scene = MonorailScene;
  using Binding = MonorailRun;
  using Controller = tools::Controller;
  // The law's torque limit on the case motor.
  static hil::ActuatorLimits actuator_limits(const Scene& s) {
    msg::monorail::ActuatorFrame l = hil::ActuatorLimits::unlimited<msg::monorail::ActuatorFrame>();
    l.motor_torque_Nm = s.controller.law.torque_limit_Nm;
    return hil::ActuatorLimits::of(l);
  }
  // The car lies on the ground at |φ| = π/2 (sim/plants/car_on_track.hpp); the case has no end stops.
  static nlohmann::json limits(const Scene& s) {
    return {{"motor_torque_limit_Nm", s.controller.law.torque_limit_Nm},
            {"tilt_overturned_rad", 0.5 * std::numbers::pi}};
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_monorail_scene(std::unique_ptr<MonorailScene> s) {
  return std::make_unique<DeviceSceneOf<MonorailTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
