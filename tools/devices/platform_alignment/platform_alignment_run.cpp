// What a platform alignment run reports: the plant of sim/plants/platform_alignment_plant.hpp with its meters
// beside the closed forms of tools/devices/platform_alignment/platform_alignment_closed_forms.hpp — when the azimuth phase began
// (the zenith torquer leaving its Earth-rate compensation), the alignment time (the platform within the
// scene's tolerances from then to the end) against the loop's prediction, the azimuth loop's time constant
// measured on the heading error against the cubic's slow root and the 1/cosφ law, the misalignment at the
// end against the steady state of the biases and drifts (θ_E = −b_N/g, θ_N = b_E/g, ψ ≈ −ε_E/(ω^E cosφ)),
// the east gyro's (16.52) signal of the initial heading error, the latitude limit — the half-step error
// estimate, the CSV columns, the figures, and the scene's plant and controller for the run modes.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "gyrostab_signals/platform_alignment_outputs.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/platform_alignment/platform_alignment_sampled.hpp"
#include "tools/devices/platform_alignment/platform_alignment_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::PlatformAlignmentPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicPlatformAlignmentController<firmware::posix::MonotonicClock>;

nlohmann::json or_null(bool have, double v) {
  return have ? nlohmann::json(v) : nlohmann::json(nullptr);
}

class PlatformAlignmentRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::platform_alignment::Record;

  explicit PlatformAlignmentRun(const PlatformAlignmentScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        g_(firmware::platform_alignment_gains(s.controller.law)),
        g_site_(oracles::gains_at(s.controller.law, s.plant.platform.latitude)),
        steady_(oracles::steady_misalignment(g_, s.plant.platform, s.plant.gravity)),
        level_command_(g_.Omega_U / s.controller.law.azimuth_torquer_scale),
        window_(s.loop.ticks() / 2, 1000),
        slow_root_(oracles::azimuth_slow_root(g_site_)),
        sampled_(platform_alignment_sampled(s, slow_root_)),
        divisor_(std::max<std::int64_t>(1, static_cast<std::int64_t>(s.controller.runtime.control_divisor))),
        fit_(s.controller.law.levelling_min_s, s.loop.duration_s, s.controller.runtime.control_period_s(),
             static_cast<int>(sampled_.roots.s.size()) + 2, 2) {
    measure();
  }

  // The errors of the apparent tilts the firmware reads (sensed − the model's accelerometers at rest): the
  // base's gusts and the noise, the inputs of the fitted recurrence (the biases, constant, go into its c).
  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    const dynamics::Vec3 a =
        plant_.model().accelerometers(plant_.state(), dynamics::Vec3(0.0, 0.0, s_.plant.gravity));
    tilt_error_[0] = f.theta_east_rad - a.y() / plants::kAlignmentGravityScale;
    tilt_error_[1] = f.theta_north_rad + a.x() / plants::kAlignmentGravityScale;
    // The heading error when the frame was read, once the loop is near its equilibrium: below kFitBelowRad.
    if (switch_tick_ >= 0 && tick % divisor_ == 0 &&
        std::fabs(m_.heading_error - steady_.heading_error) < kFitBelowRad)
      fit_.add(static_cast<double>(tick) * s_.loop.tick_s(), m_.heading_error, tilt_error_.data());
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    // The azimuth phase: the zenith torquer leaves the Earth-rate compensation of the levelling phase.
    const double u = last_.zenith_torquer_V;
    if (switch_tick_ < 0 && u != level_command_ && u != 0.0) {  // 0: the safe state's
      switch_tick_ = tick;
      at_switch_ = m_;
      // What the east gyro senses on the levelled platform as it stands, before the azimuth loop moves it:
      // the Earth's rate on the platform's east axis P1 from the run's attitude q_GP (tilts included).
      east_gyro_at_switch_ = plant_.model().earth_rate_on_platform(plant_.state()).x();
    }
    window_.before_tick(tick, plant_.state(), plant_.inputs());
    plant_.advance(tick);
    window_.after_tick(tick, plant_.state());
    ticks_ = tick + 1;
    measure();
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.tilt_east_rad = m_.tilt_east;
    r.tilt_north_rad = m_.tilt_north;
    r.heading_error_rad = m_.heading_error;
    const std::array<double, 3>& a = plant_.accelerometers();
    r.accel_east_m_s2 = a[0];
    r.accel_north_m_s2 = a[1];
    r.accel_up_m_s2 = a[2];
    const dynamics::Vec3& w = plant_.inputs().rate_command;
    r.rate_east_rad_s = w.x();
    r.rate_north_rad_s = w.y();
    r.rate_zenith_rad_s = w.z();
    r.status_bits = static_cast<double>(last_.status);
  }

  // Until the first command: the platform turns with the geographic frame (caged on the Earth rate).
  ActuatorFrame initial_command() const {
    ActuatorFrame a{};
    a.north_torquer_Nm = -s_.plant.H * g_.Omega_N;
    a.zenith_torquer_V = level_command_;
    return a;
  }

  nlohmann::json figures() const {
    const double T = s_.loop.tick_s(), phi = s_.plant.platform.latitude, we = s_.plant.platform.earth_rate;
    const double tau_pred = 1.0 / std::fabs(slow_root_);
    // The azimuth root measured: the fitted recurrence's root nearest the cubic's.
    double tau_fit = -1.0;
    if (fit_.valid()) tau_fit = -1.0 / analysis::nearest_root(fit_.roots(), {slow_root_, 0.0}).real();
    const bool switched = switch_tick_ >= 0, aligned = in_tolerance_;
    const double t_switch = switched ? static_cast<double>(switch_tick_) * T : 0.0;
    oracles::AlignmentTimeInputs in = alignment_time_inputs(s_);
    const double t_pred_scene = oracles::alignment_time(in, phi);
    in.switch_time = t_switch;
    const double t_pred = oracles::alignment_time(in, phi);
    return {
        {"ticks", ticks_},
        {"latitude_rad", phi},
        {"latitude_limit_rad", s_.latitude_limit},
        {"max_time_s", s_.max_time_s},
        {"east_gyro_signal_16_52_rad_s", -we * std::cos(phi) * std::sin(s_.plant.initial.heading_error)},
        {"east_gyro_rate_at_azimuth_start_rad_s", or_null(switched, east_gyro_at_switch_)},
        {"east_gyro_rate_at_azimuth_start_rad_s_predicted",
         or_null(switched, -we * std::cos(phi) * std::sin(at_switch_.heading_error))},
        {"east_gyro_rate_at_azimuth_start_rel_error",
         or_null(switched && at_switch_.heading_error != 0.0,
                 east_gyro_at_switch_ / (-we * std::cos(phi) * std::sin(at_switch_.heading_error)) - 1.0)},
        {"azimuth_start_s", or_null(switched, t_switch)},
        {"azimuth_start_predicted_s", s_.predicted_switch_s},
        {"tilt_east_at_azimuth_start_rad", or_null(switched, at_switch_.tilt_east)},
        {"tilt_north_at_azimuth_start_rad", or_null(switched, at_switch_.tilt_north)},
        {"heading_error_at_azimuth_start_rad", or_null(switched, at_switch_.heading_error)},
        {"alignment_time_s", or_null(aligned, static_cast<double>(last_out_tick_) * T)},
        {"alignment_time_predicted_s", or_null(std::isfinite(t_pred), t_pred)},
        {"alignment_time_predicted_before_run_s", or_null(std::isfinite(t_pred_scene), t_pred_scene)},
        {"azimuth_time_constant_s", or_null(tau_fit > 0.0, tau_fit)},
        {"azimuth_time_constant_fit_samples", fit_.samples()},
        {"azimuth_time_constant_tan_law_s", or_null(tau_measured_ > 0.0, tau_measured_)},
        {"azimuth_time_constant_predicted_s", tau_pred},
        {"azimuth_time_constant_predicted_sampled_s", -1.0 / sampled_.slow_root.real()},
        {"sampled_loop_max_abs_z", sampled_.roots.max_abs_z},
        {"azimuth_time_constant_cos_law_s", s_.controller.law.azimuth_time_constant_equator / std::cos(phi)},
        {"tilt_east_end_rad", m_.tilt_east},
        {"tilt_north_end_rad", m_.tilt_north},
        {"heading_error_end_rad", m_.heading_error},
        {"tilt_east_steady_rad", steady_.tilt_east},
        {"tilt_north_steady_rad", steady_.tilt_north},
        {"heading_error_steady_rad", steady_.heading_error},
        {"heading_error_drift_term_rad", -s_.plant.platform.drift.x() / (we * std::cos(phi))},
        {"aligned_at_end", aligned},
    };
  }

  // report.json "error_estimate": 1000 ticks from the run's middle.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Model& m, const Plant::Inputs& in) { m.inputs = in; };
    return error_estimate_json<4>(
        window_.estimate<dynamics::Rk4>(plant_.model(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        Plant::kStateNames, "|q_GP| = 1, held by projection");
  }

 private:
  void measure() {
    m_ = plant_.misalignment();
    in_tolerance_ = std::fabs(m_.heading_error) <= s_.heading_tolerance &&
                    std::fabs(m_.tilt_east) <= s_.tilt_tolerance && std::fabs(m_.tilt_north) <= s_.tilt_tolerance;
    if (!in_tolerance_) last_out_tick_ = ticks_ + 1;
    if (switch_tick_ < 0) return;
    // The azimuth time constant on tan(|ψ − ψ_ss|/2) (the quasi-static loop's exact decay), from 5 levelling
    // time constants after the switch (those roots down to e^-5) over two e-folds.
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    const double t_a = static_cast<double>(switch_tick_) * s_.loop.tick_s() +
                       5.0 / (s_.controller.law.levelling_damping * s_.controller.law.levelling_bandwidth);
    const double d = std::tan(0.5 * std::fabs(m_.heading_error - steady_.heading_error));
    if (ref_t_ < 0.0) {
      if (t >= t_a) {
        ref_t_ = t;
        ref_d_ = d;
      }
    } else if (tau_measured_ < 0.0 && ref_d_ > 0.0 && d <= ref_d_ * std::exp(-2.0)) {
      tau_measured_ = (t - ref_t_) / std::log(ref_d_ / d);
    }
  }

  const PlatformAlignmentScene& s_;
  Plant plant_;
  firmware::PlatformAlignmentGains g_, g_site_;
  models::PlatformMisalignment steady_;
  double level_command_;
  ActuatorFrame last_{};
  models::PlatformMisalignment m_{}, at_switch_{};
  double east_gyro_at_switch_{0.0};  // ω_IG · P1 at the azimuth phase's start [rad/s]
  bool in_tolerance_{false};
  std::int64_t last_out_tick_{0}, switch_tick_{-1};
  double ref_t_{-1.0}, ref_d_{0.0}, tau_measured_{-1.0};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Model, Plant::Inputs> window_;
  // The fit's window opens when |ψ − ψ_ss| is below this [rad] (sin ψ then within ψ²/6 = 1.5e-4 of ψ) and runs
  // to the end. At the law's rate a window this long holds the slow root to ~3e-4 under the shipped gusts (a
  // sinusoid among the inputs, whose lags span only two dimensions); a shorter one (from 0.01 rad) scatters by
  // ±9e-4 from seed to seed (docs/sampled-data.md).
  static constexpr double kFitBelowRad = 0.03;
  double slow_root_;
  PlatformAlignmentSampled sampled_;
  std::int64_t divisor_;
  std::array<double, 2> tilt_error_{};
  analysis::LinearPredictionMeter fit_;
};

struct PlatformAlignmentTraits {
  using Scene = PlatformAlignmentScene;
  using Binding = PlatformAlignmentRun;
  using Controller = tools::Controller;
  static nlohmann::json limits(const Scene& s) {
    return {{"heading_tolerance_rad", s.heading_tolerance},
            {"tilt_tolerance_rad", s.tilt_tolerance},
            {"max_time_s", s.max_time_s}};
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_platform_alignment_scene(std::unique_ptr<PlatformAlignmentScene> s) {
  return std::make_unique<DeviceSceneOf<PlatformAlignmentTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
