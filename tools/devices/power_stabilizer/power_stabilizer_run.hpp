// What a power stabilizer run reports: the plant of sim/plants/power_stabilizer_plant.hpp with its meters —
// the closed loop's nutation frequency and decay rate measured after the inner-axis step (else the first step:
// power_stabilizer_checks.hpp, nutation_window) by a recurrence fitted to α[k] (beside the roots of
// (14.23)/(14.29) at that window's operating point, `_predicted`, and of the sampled loop,
// `_predicted_sampled`), the steady deflections beside (14.21), the angles' and
// the drives' peaks, the periodic drift over long runs, the half-step error estimate — the CSV row (the signal
// table's columns by name, tools/devices/power_stabilizer/power_stabilizer_signals.toml; those of options the
// variant lacks stay 0 and are not recorded) and the report blocks. One template over the plant's options; the
// variants are instantiated in
// power_stabilizer_{rigid,dc,elastic,precession}.cpp, one translation unit per group.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "gyrostab_signals/power_stabilizer_outputs.hpp"
#include "sim/analysis/drive_peaks.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "sim/analysis/nutation_meter.hpp"
#include "sim/analysis/periodic_drift.hpp"
#include "sim/analysis/running_stats.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_checks.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_sampled.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"
#include "tools/loop/periodic_drift_report.hpp"

namespace gyrostab::tools {

template <class Motor, class Structure, bool kDcDrive, template <class> class Integrator,
          class Fidelity = models::FullGimbal>
class PowerStabilizerRun {
 public:
  using Plant = plants::PowerStabilizerPlant<Motor, Structure, kDcDrive, Integrator, Fidelity>;
  using Model = typename Plant::Model;
  using SensorFrame = typename Plant::SensorFrame;
  using ActuatorFrame = typename Plant::ActuatorFrame;
  using Record = msg::power_stabilizer::Record;
  static constexpr bool kElastic = Plant::kElastic;
  static constexpr bool kBackEmf = Plant::kBackEmf;
  static constexpr bool kPrecession = Plant::kPrecession;

  // The runtime guard's names (state_guard.hpp) and the reduced-model comparison's signals.
  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }
  static constexpr int kComparedSignals = 2;
  static const char* compared_signal_name(int i) { return i == 0 ? "alpha_rad" : "beta_rad"; }
  double compared_signal(int i) const { return i == 0 ? plant_.alpha_rad() : plant_.beta_rad(); }

  explicit PowerStabilizerRun(const PowerStabilizerScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        nutation_window_(nutation_window(s.plant.disturbance, s.measure_window_s)),
        meter_(nutation_window_.step_s + 0.02, nutation_window_.end_s),
        drift_(s.drift_period_s > 0.0 ? analysis::PeriodicDrift(4, std::llround(s.drift_period_s / s.loop.tick_s()),
                                                                std::llround(s.drift_from_s / s.loop.tick_s()))
                                      : analysis::PeriodicDrift()),
        meter_every_(meter_interval(s)),
        fit_(nutation_window_.step_s + 0.02, std::min(nutation_window_.end_s, s.loop.duration_s),
             static_cast<double>(meter_every_) * s.loop.tick_s(), fit_order(s), fit_channels(s, meter_every_)),
        window_(static_cast<std::int64_t>(std::min(s.plant.disturbance.t1, s.plant.disturbance.t2) / s.loop.tick_s()),
                static_cast<std::int64_t>(1.0 / s.loop.tick_s())) {}

  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    // What the firmware's frame got wrong (encoder counts, rate noise): inputs of the loop for the fit.
    sensor_error_[0] = f.alpha_rad - plant_.alpha_rad();
    sensor_error_[1] = f.beta_rad - plant_.beta_rad();
    sensor_error_[2] = f.alpha_rate_rad_s - plant_.alpha_rate_rad_s();
    sensor_error_[3] = f.beta_rate_rad_s - plant_.beta_rate_rad_s();
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    plant_.begin_tick(tick);
    if constexpr (!kDcDrive) window_.before_tick(tick, plant_.state(), plant_.inputs());
    plant_.integrate(tick, peaks_);
    if constexpr (!kDcDrive) window_.after_tick(tick, plant_.state());
    plant_.end_tick(tick);
    if constexpr (!kDcDrive) {
      if constexpr (kBackEmf) {
        peaks_.add(0, 0.0, plant_.inputs().u1, plant_.motor1_torque_Nm(t + s_.loop.tick_s()));
      } else {
        peaks_.add(0, 0.0, 0.0, plant_.inputs().M1K);
        peaks_.add(1, 0.0, 0.0, plant_.inputs().M2K);
      }
    }
    // The meter samples at the law's rate (1 kHz): at a 10 kHz base tick the friction's stick-slip steps in
    // α' would otherwise count as extrema; and no faster than ~100 samples per predicted period.
    if ((tick + 1) % meter_every_ == 0) {
      meter_.add(t + s_.loop.tick_s(), plant_.alpha_rate_rad_s());
      fit_.add(t + s_.loop.tick_s(), plant_.alpha_rad(), sensor_error_.data());
    }
    alpha_.add(plant_.alpha_rad());
    beta_.add(plant_.beta_rad());
    if (drift_.enabled()) {
      const double v[4] = {plant_.alpha_rad(), plant_.beta_rad(), plant_.alpha_rate_rad_s(), plant_.beta_rate_rad_s()};
      drift_.add(tick, v);
    }
  }
  bool finite() const { return plant_.finite(); }

  // report.json "error_estimate": 1 s from the first disturbance step.
  nlohmann::json error_estimate() const {
    if constexpr (kDcDrive) {
      return {{"available", false},
              {"why", "not estimated: the dc drives step with the plant inside the tick (inputs change per sub-step)"}};
    } else {
      const auto apply = [](Model& m, const models::PowerStabilizerInputs& in) { m.inputs = in; };
      std::array<const char*, Model::kStateSize> names{};
      for (int i = 0; i < Model::kStateSize; ++i) names[static_cast<std::size_t>(i)] = state_name(i);
      const int order = Integrator<Model>::kName == std::string("rk4") ? 4 : 2;
      return error_estimate_json<Model::kStateSize>(
          window_.template estimate<Integrator>(plant_.model(), apply, s_.loop.tick_ns, s_.loop.substeps, order),
          names, "none watched: motors, disturbances and bearing friction act");
    }
  }

  void record(Record& r) const {
    r.alpha_rad = plant_.alpha_rad();
    r.beta_rad = plant_.beta_rad();
    r.alpha_rate_rad_s = plant_.alpha_rate_rad_s();
    r.beta_rate_rad_s = plant_.beta_rate_rad_s();
    if constexpr (kDcDrive) {
      r.M1_motor_Nm = plant_.drive1().gear_torque();  // what the motors put on the axes through the gears
      r.M2_motor_Nm = plant_.drive2().gear_torque();
    } else if constexpr (kBackEmf) {
      r.M1_motor_Nm = kPrecession ? s_.plant.motor.s * plant_.inputs().u1 -
                                        s_.plant.motor.viscous() * plant_.alpha_rate_rad_s()
                                  : plant_.motor1_torque_Nm(0.0);
      r.M2_motor_Nm = 0.0;
    } else {
      r.M1_motor_Nm = last_.motor1_torque_Nm;
      r.M2_motor_Nm = last_.motor2_torque_Nm;
    }
    r.M1_disturbance_Nm = plant_.disturbance1_Nm();
    r.M2_disturbance_Nm = plant_.disturbance2_Nm();
    r.status_bits = static_cast<double>(last_.status);
    if constexpr (kDcDrive) {
      r.motor1_current_A = plant_.drive1().current();
      r.motor2_current_A = plant_.drive2().current();
      r.motor1_voltage_V = plant_.drive1().last_interval().voltage_mean;
      r.motor2_voltage_V = plant_.drive2().last_interval().voltage_mean;
    }
    if constexpr (kBackEmf) r.motor1_voltage_V = plant_.inputs().u1;
    if constexpr (kElastic) r.platform_rad = plant_.platform_rad();
  }

  nlohmann::json figures() const {
    const auto& l = s_.controller.loops;
    const auto& dist = s_.plant.disturbance;
    const std::complex<double> root = predicted_nutation(s_.measure_loops);
    const firmware::GainCheck g = firmware::check_power_stabilizer_gains(l);
    nlohmann::json f{{"nutation_frequency_rad_s_predicted", root.imag()},
                     {"nutation_decay_rate_per_s_predicted", -root.real()},
                     {"steady_alpha_rad", plant_.alpha_rad()},
                     {"steady_beta_rad", plant_.beta_rad()},
                     {"alpha_max_rad", alpha_.peak},
                     {"beta_max_rad", beta_.peak},
                     {"gain_margin", g.gain_scale_max},
                     {"open_loop_nutation_rad_s", s_.plant.H / std::sqrt(l.A * l.B)}};
    // The same loop as the `_predicted` figures, sampled as the closed loop runs it (hold, period, latency):
    // power_stabilizer_sampled.hpp, docs/sampled-data.md.
    const PowerStabilizerSampled sampled = power_stabilizer_sampled(s_.measure_loops, power_stabilizer_timing(s_));
    f["nutation_frequency_rad_s_predicted_sampled"] = sampled.nutation.imag();
    f["nutation_decay_rate_per_s_predicted_sampled"] = -sampled.nutation.real();
    f["sampled_loop_max_abs_z"] = sampled.roots.max_abs_z;
    const Eigen::Vector2d steady = power_stabilizer_sampled_steady(
        s_.op_loops, power_stabilizer_timing(s_), dist.M1, dist.M2);
    const auto finite_or_null = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
    f["steady_alpha_rad_predicted_sampled"] = finite_or_null(steady[0]);
    f["steady_beta_rad_predicted_sampled"] = finite_or_null(steady[1]);
    if constexpr (kBackEmf) {
      // (14.27) at rest: s r β = M1^S; α is neutral (λ = 0 of (14.29)): a constant M2^S makes it precess.
      f["steady_beta_rad_predicted"] = dist.M1 / (l.s * l.r);
      f["steady_alpha_rad_predicted"] = nullptr;
      f["r_max_V_per_rad"] = g.r_max;
      f["motor1_voltage_peak_V"] = peaks_.voltage_V[0];
      f["motor1_torque_peak_Nm"] = peaks_.torque_Nm[0];
    } else {
      // (14.21) holds on a base at rest; on a rolling base the gimbal angles (relative to the base) also
      // carry the base motion.
      f["steady_alpha_rad_predicted"] = l.k2 != 0.0 ? -dist.M2 / l.k2 : 0.0;
      f["steady_beta_rad_predicted"] = l.k1 != 0.0 ? dist.M1 / l.k1 : 0.0;
      f["k_max_equal_Nm_per_rad"] = g.k_max_equal;
      f["motor1_torque_peak_Nm"] = peaks_.torque_Nm[0];
      f["motor2_torque_peak_Nm"] = peaks_.torque_Nm[1];
    }
    if constexpr (kDcDrive) {
      f["motor1_current_peak_A"] = peaks_.current_A[0];
      f["motor2_current_peak_A"] = peaks_.current_A[1];
      f["motor1_voltage_peak_V"] = peaks_.voltage_V[0];
      f["motor2_voltage_peak_V"] = peaks_.voltage_V[1];
      f["reflected_inertia_kg_m2"] = plant_.drive1().reflected_inertia();
      f["drive_peak_torque_Nm"] = plant_.drive1().peak_torque();
    }
    if constexpr (kElastic) {
      // (14.33)-(14.37): c* = c H²/(c B + H²), ω^P = sqrt(c*/A^P), α/φ = c B/(c B + H²).
      const double c = s_.plant.platform.c, B = l.B, H = s_.plant.H;
      const double c_star = c * H * H / (c * B + H * H);
      f["platform_frequency_rad_s_predicted"] = std::sqrt(c_star / plant_.model().platform_inertia());
      f["effective_stiffness_Nm_per_rad_predicted"] = c_star;
      f["alpha_over_phi_predicted"] = c * B / (c * B + H * H);
      f["steady_platform_rad"] = plant_.platform_rad();
    }
    // The measurement fits one exponentially decaying oscillation. Coulomb/stick-slip drive friction and the
    // elastic platform's extra mode make the response something else, and (14.23)'s roots do not model them:
    // there the measured figures are withheld (null) with the reason, never reported wrong.
    if (s_.plant.beta0 != 0.0) f["operating_point_beta_rad"] = s_.plant.beta0;
    // Where the nutation is measured (nutation_window) and the loop the nutation predictions linearise.
    f["nutation_window_from_s"] = nutation_window_.step_s + 0.02;
    f["nutation_window_to_s"] = nutation_window_.end_s;
    f["nutation_operating_point_beta_rad"] = s_.measure_beta_rad;
    if (kPrecession) {
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_decay_rate_per_s"] = nullptr;
      f["nutation_measurement"] = "not measured: the precession model (P0) has no nutation";
    } else if (kDcDrive || kElastic) {
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_decay_rate_per_s"] = nullptr;
      f["nutation_measurement"] = kDcDrive ? "not measured: the drives' stick-slip friction is not in (14.23)"
                                           : "not measured: the elastic platform adds a mode (14.31) not in (14.23)";
    } else if (meter_.valid() && fit_.valid()) {
      // The root of the recurrence fitted to α[k] nearest the continuous root (linear_prediction_fit.hpp):
      // every sample counts, so the seeded rate noise that drives the loop leaves it unbiased.
      const std::complex<double> measured = analysis::nearest_root(fit_.roots(), root);
      f["nutation_frequency_rad_s"] = measured.imag();
      f["nutation_decay_rate_per_s"] = -measured.real();
      f["nutation_frequency_rad_s_extrema"] = meter_.angular_frequency();
      f["nutation_decay_rate_per_s_extrema"] = -meter_.growth_rate();
    } else {
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_decay_rate_per_s"] = nullptr;
      f["nutation_measurement"] = "not measured: fewer than three nutation periods in the window";
    }
    return f;
  }

  // report.json "plant" (what this loop assembled: only what the scene names is in it) and, with
  // [report] drift_period_s, "drift".
  nlohmann::json report_extra() const {
    const auto& p = s_.plant;
    nlohmann::json parts = nlohmann::json::array();
    parts.push_back(kPrecession ? "precession model P0 (10.19)-(10.22), no nutation states"
                                : "gimbal gyro (10.4) with nutation");
    if constexpr (kBackEmf) parts.push_back("back-EMF motor (14.26), current lag neglected");
    if constexpr (kDcDrive) parts.push_back("motor electrics: dc drives on both axes (winding current, gear, friction)");
    if constexpr (kElastic) parts.push_back("structural elasticity: platform on a shaft (14.31)");
    if (p.base.kind == motion::BaseMotionKind::kHarmonicRoll && p.base.harmonic.amplitude > 0.0)
      parts.push_back("base motion: harmonic roll");
    if (p.base.kind == motion::BaseMotionKind::kPrescribed) parts.push_back("base motion: prescribed yaw, pitch, roll");
    if (p.base.kind == motion::BaseMotionKind::kRecorded) parts.push_back("base motion: recorded (interpolated)");
    if (p.base.vibration.count > 0) parts.push_back("base vibration");
    if (p.gyro.d1 > 0.0 || p.gyro.d2 > 0.0) parts.push_back("bearing viscous friction");
    if constexpr (kDcDrive) {
      if (p.drive.friction.coulomb > 0.0) parts.push_back("bearing Coulomb friction (stick-slip)");
    }
    const auto& n = p.rate_gyro.noise;
    if (n.white_density > 0.0 || n.bias != 0.0 || n.bias_random_walk > 0.0) parts.push_back("rate gyro noise");
    using Order = sensors::LowpassParams::Order;
    const Order order = p.rate_gyro.bandwidth.order;
    const int filter = order == Order::kNone ? 0 : order == Order::kFirst ? 1 : 2;  // states per rate gyro
    nlohmann::json j;
    j["plant"] = {{"model", Model::kName},
                  {"fidelity", kPrecession ? "precession" : "full"},
                  {"components", parts},
                  {"mechanical_states", Model::kStateSize},
                  {"electrical_states", kDcDrive ? 2 : 0},
                  {"sensor_filter_states", 2 * filter},
                  {"state_size", Plant::kLoopStateSize + 2 * filter},
                  {"device_bytes", sizeof(PowerStabilizerRun)},
                  {"integrator", Integrator<Model>::kName},
                  {"plant_substeps", s_.loop.substeps}};
    if (drift_.enabled()) {
      static const char* const names[] = {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"};
      j["drift"] = periodic_drift_json(drift_, names, s_.loop.tick_s());
      j["drift"]["bound_rad"] = drift_bound();
      const double worst = std::max(drift_.worst(0), drift_.worst(1));
      j["drift"]["within_bound"] = drift_.compared_ticks() > 0 && worst <= drift_bound();
    }
    return j;
  }

 private:
  // The angles' bound on the periodic drift: two encoder counts. The loop is exponentially stable and the
  // law memoryless, so an integration error is forgotten at the loop's decay rate instead of accumulating;
  // what can remain is the loop settling, from period to period, on neighbouring encoder counts (its only
  // non-smooth element), each count moving the angles by less than one count in the steady state.
  double drift_bound() const {
    return 2.0 * 2.0 * std::numbers::pi / static_cast<double>(s_.plant.encoder_counts_per_rev);
  }
  // The meter's sampling: every control_divisor ticks, or a multiple of it giving ~100 samples per period of
  // the predicted oscillation. A slow loop (the gimbal-lock approach: a 31 s period) sampled at 1 kHz would
  // count the encoder's one-count torque jitter near each turning point as extrema.
  static std::int64_t meter_interval(const PowerStabilizerScene& s) {
    const auto divisor = static_cast<std::int64_t>(s.controller.runtime.control_divisor);
    const double w = predicted_nutation(s.measure_loops).imag();
    if (!(w > 0.0)) return divisor;
    const double per_period = 2.0 * std::numbers::pi / w / (100.0 * s.loop.tick_s() * static_cast<double>(divisor));
    return divisor * std::max<std::int64_t>(1, static_cast<std::int64_t>(per_period));
  }

  // The fit's order: the sampled loop's non-zero roots (plant, law, commands in flight) and two for a slow
  // base motion's forced response.
  static int fit_order(const PowerStabilizerScene& s) {
    if (kPrecession || kDcDrive || kElastic) return 1;
    return static_cast<int>(power_stabilizer_sampled(s.measure_loops, power_stabilizer_timing(s)).roots.s.size()) + 2;
  }

  // The sensor errors are the loop's inputs when they are white noise and quantisation sampled once per law
  // period: a rate gyro's bandwidth filter makes its error depend on the state, and a meter slower than the law
  // would alias them. Otherwise the fit takes α alone.
  static int fit_channels(const PowerStabilizerScene& s, std::int64_t meter_every) {
    if (kPrecession || kDcDrive || kElastic) return 0;
    if (s.plant.rate_gyro.bandwidth.order != sensors::LowpassParams::Order::kNone) return 0;
    return meter_every == static_cast<std::int64_t>(s.controller.runtime.control_divisor) ? 4 : 0;
  }

  const PowerStabilizerScene& s_;
  Plant plant_;
  NutationWindow nutation_window_;
  analysis::NutationMeter meter_;
  analysis::PeriodicDrift drift_;
  std::int64_t meter_every_;
  analysis::LinearPredictionMeter fit_;
  std::array<double, 4> sensor_error_{};
  ActuatorFrame last_{};
  analysis::RunningStats alpha_, beta_;
  analysis::DrivePeaks peaks_;
  analysis::HalfStepWindow<Model, models::PowerStabilizerInputs> window_;
};

}  // namespace gyrostab::tools
