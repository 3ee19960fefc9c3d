// What an inertial platform run reports: the plant of sim/plants/inertial_platform_plant.hpp with its meters,
// per level channel, measured beside the book's — the period of the tilt e from its extrema against the
// loop's 2π/ω, ω² = (g/R_loop)(H_loop/H) ((16.38)/(16.44): 84.4 min when tuned); max |e| against the tuned
// bound sqrt(e0² + (Δω0/ω_S)²) of (16.46)/(16.49) (any vehicle motion); the loop's velocity error
// v_err = R_loop ω_cmd − R Ω (ω_cmd read from the torquer command, M = −H_loop ω_cmd) and the position error
// ∫v_err dt, with the book's amplitudes e0 sqrt(gR) and 2 R e0 (16.47) (book: 2.2 km for 0.01°); the servo
// offset β0 = M^S/k (16.2) — the half-step error estimate, the CSV columns, the figures, and the scene's
// plant and controller for the run modes.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "sim/models/inertial_platform_stability.hpp"
#include "gyrostab_signals/inertial_platform_outputs.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/inertial_platform/inertial_platform_sampled.hpp"
#include "tools/devices/inertial_platform/inertial_platform_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicInertialPlatformController<firmware::posix::MonotonicClock>;
constexpr double kPi = std::numbers::pi;

// Channel i's torquer command (torquer1_Nm, torquer2_Nm) [N m].
double torquer_Nm(const plants::InertialPlatformActuatorFrame& cmd, int i) {
  return i == 0 ? cmd.torquer1_Nm : cmd.torquer2_Nm;
}

// The Schuler mode measured: a recurrence fitted to the tilt sampled every extrema_sample_s over the whole run
// (both channels' Schuler pairs, which the cross terms couple, and two spare orders; the servo modes are gone at
// that sampling), its root nearest the prediction (sim/analysis/linear_prediction_fit.hpp).
constexpr int kSchulerFitOrder = 6;

struct ChannelStats {
  analysis::ExtremaMeter<64> extrema{};
  analysis::LinearPredictionMeter fit{0.0, 0.0, 1.0, 1};
  double tilt_max{0.0};
  double velocity_error_max{0.0};
  double position_error{0.0}, position_error_max{0.0};
};

template <class Model>
class InertialPlatformRun {
  using Plant = plants::InertialPlatformPlant<Model>;
  static constexpr int kChannels = Plant::kChannels;

 public:
  using SensorFrame = typename Plant::SensorFrame;
  using ActuatorFrame = typename Plant::ActuatorFrame;
  using Record = msg::inertial_platform::Record;

  explicit InertialPlatformRun(const InertialPlatformScene& s)
      : s_(s), plant_(s.plant, s.loop.plant_timing()), window_(s.loop.ticks() / 2, 1000) {
    const double dt = static_cast<double>(s.extrema_every_ticks) * s.loop.tick_s();
    for (ChannelStats& c : stats_) {
      c.extrema = analysis::ExtremaMeter<64>(s.extrema_hysteresis);
      c.fit = analysis::LinearPredictionMeter(0.0, s.loop.duration_s + 0.5 * dt, dt, kSchulerFitOrder);
    }
    for (int i = 0; i < kChannels; ++i) stats_[static_cast<std::size_t>(i)].fit.add(0.0, plant_.tilt_rad(i));
    remember_rates(0);
  }

  void sense(std::int64_t tick, SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    plant_.begin_tick(tick);
    window_.before_tick(tick, plant_.state(), plant_.inputs());
    plant_.integrate(tick);
    window_.after_tick(tick, plant_.state());
    plant_.end_tick();
    remember_rates(tick + 1);
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    const double R = s_.plant.vehicle.earth.radius, RL = s_.controller.law.radius, HL = s_.controller.law.H;
    for (int i = 0; i < kChannels; ++i) {
      ChannelStats& c = stats_[static_cast<std::size_t>(i)];
      const double e = plant_.tilt_rad(i);
      c.tilt_max = std::max(c.tilt_max, std::fabs(e));
      if (ticks_ % s_.extrema_every_ticks == 0) {
        c.extrema.add(t1, e);
        c.fit.add(t1, e);
      }
      // The loop's velocity estimate from its torquer command; the channel's true v = ±R Ω at the time
      // the command estimates (the end of the control step it came from, latency_ticks earlier).
      const double w_cmd = -torquer_Nm(last_, i) / HL;
      const double v_err = RL * w_cmd - R * rate_history(tick + 1 - s_.loop.latency_ticks, i);
      c.velocity_error_max = std::max(c.velocity_error_max, std::fabs(v_err));
      c.position_error += v_err * s_.loop.tick_s();
      c.position_error_max = std::max(c.position_error_max, std::fabs(c.position_error));
    }
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    double theta[2];
    plant_.apparent_tilts(t, theta);
    r.tilt1_rad = plant_.tilt_rad(0);
    r.tilt2_rad = kChannels > 1 ? plant_.tilt_rad(1) : 0.0;
    r.theta1_rad = theta[0];
    r.theta2_rad = theta[1];
    r.torquer1_Nm = last_.torquer1_Nm;
    r.torquer2_Nm = last_.torquer2_Nm;
    r.gyro1_rad = plant_.gyro_angle_rad(0);
    r.velocity_error1_m_s = s_.controller.law.radius * (-last_.torquer1_Nm / s_.controller.law.H) -
                            s_.plant.vehicle.earth.radius * rate_history(ticks_ - s_.loop.latency_ticks, 0);
    r.status_bits = static_cast<double>(last_.status);
  }

  // The loop's initial torque: the level frame's rate at t = 0 (no start transient).
  ActuatorFrame initial_command() const {
    ActuatorFrame a{};
    a.torquer1_Nm = -s_.controller.law.H * s_.controller.law.initial_rate[0];
    if constexpr (kChannels > 1) a.torquer2_Nm = -s_.controller.law.H * s_.controller.law.initial_rate[1];
    return a;
  }

  nlohmann::json figures() const {
    const double g = s_.plant.vehicle.earth.gravity, R = s_.plant.vehicle.earth.radius;
    const double RL = s_.controller.law.radius, HL = s_.controller.law.H, wS = std::sqrt(g / R);
    nlohmann::json f{{"ticks", ticks_}, {"axes", s_.plant.axes}, {"schuler_period_s", 2.0 * kPi / wS}};
    if constexpr (!std::is_same_v<Model, models::SingleAxisPlatform>) {
      // The platform's servo roots with every cross term, the slowest decay beside the stability margin.
      const models::ServoStability st = models::servo_stability<Model>(plant_.model().params());
      constexpr bool kPosition = std::is_same_v<Model, models::TwoPositionGyroPlatform>;
      f["gyros"] = kPosition ? "two_position" : "three_integrating";
      if constexpr (!kPosition)
        f["coupling"] = plant_.model().params().coupling == models::PlatformCoupling::kFull ? "full" : "decoupled";
      f["servo_root_worst_re_per_s"] = st.worst.real();
      f["servo_root_worst_im_rad_s"] = std::fabs(st.worst.imag());
    }
    const std::optional<InertialPlatformSampled> sampled = inertial_platform_sampled<Model>(s_);
    if (sampled) f["sampled_loop_max_abs_z"] = sampled->roots.max_abs_z;
    else f["sampled_loop"] = "not computed: the law reads the last tick's mean only once per control period";
    nlohmann::json ch = nlohmann::json::array();
    for (int i = 0; i < kChannels; ++i) {
      const ChannelStats& c = stats_[static_cast<std::size_t>(i)];
      const models::PlatformAxisParams& a = s_.plant.axis[i].params;
      const double w_loop = std::sqrt(g / RL * HL / a.H);
      const double dw0 = s_.velocity_error0[i] / RL;
      const double e0 = s_.plant.axis[i].tilt0;
      nlohmann::json j{{"channel", i + 1},
                       {"period_loop_book_s", 2.0 * kPi / w_loop},
                       {"tilt_max_rad", c.tilt_max},
                       {"tilt_bound_tuned_rad", std::hypot(e0, dw0 / wS)},
                       {"tilt_end_rad", plant_.tilt_rad(i)},
                       {"velocity_error_max_m_s", c.velocity_error_max},
                       {"velocity_error_amplitude_book_16_47_m_s", std::fabs(e0) * std::sqrt(g * R)},
                       {"position_error_max_m", c.position_error_max},
                       {"position_error_max_book_16_47_m", 2.0 * R * std::fabs(e0)},
                       {"servo_offset_book_16_2_rad", servo_offset_book(a)},
                       {"gyro_angle_end_rad", plant_.gyro_angle_rad(i)},
                       {"servo_gain_limit_16_5", std::is_same_v<Model, models::TwoPositionGyroPlatform>
                                                     ? nlohmann::json(nullptr)  // no upper bound (16.9)
                                                     : nlohmann::json(a.k_max())},
                       {"drift_position_rate_book_16_50_m_s", -a.drift * R},
                       {"extrema", c.extrema.count()}};
      j["period_measured_s"] =
          c.extrema.count() >= 2 ? nlohmann::json(c.extrema.period()) : nlohmann::json(nullptr);
      j["period_s_predicted_sampled"] =
          sampled ? nlohmann::json(2.0 * kPi / sampled->schuler[i].imag()) : nlohmann::json(nullptr);
      // Negative: the computer's lag makes the Schuler mode grow (schuler_loop.hpp).
      j["decay_rate_per_s_predicted_sampled"] =
          sampled ? nlohmann::json(-sampled->schuler[i].real()) : nlohmann::json(nullptr);
      // The fitted root nearest the loop's; null for a channel that does not swing (fewer than two extrema:
      // started level, its recurrence fits only the noise and the vehicle's forced response).
      const std::complex<double> want = sampled ? sampled->schuler[i] : std::complex<double>(0.0, w_loop);
      std::complex<double> got{0.0, 0.0};
      if (c.extrema.count() >= 2 && c.fit.valid()) {
        const std::vector<std::complex<double>> roots = c.fit.roots();
        if (!roots.empty()) got = analysis::nearest_root(roots, want);
      }
      j["period_s"] = got.imag() > 0.0 ? nlohmann::json(2.0 * kPi / got.imag()) : nlohmann::json(nullptr);
      j["fit_samples"] = c.fit.samples();
      ch.push_back(j);
    }
    f["channels"] = ch;
    return f;
  }

  // report.json "error_estimate": 1000 ticks from the run's middle (the frame's motion is interpolated within
  // the tick exactly as in the run, so the re-integration at half the step sees the same forcing).
  nlohmann::json error_estimate() const {
    const auto apply = [](Model& m, const typename Model::Inputs& in) { m.inputs = in; };
    return error_estimate_json<Model::kStateSize>(
        window_.template estimate<dynamics::Rk4>(plant_.model(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        Plant::state_names(), "none watched: vehicle motion, servo and Schuler-loop torques act");
  }

 private:
  // The channel pick-off's offset under the constant disturbance: (16.2)/(16.15) β0 = M^S/k; position gyros
  // (16.22) α^Y = −M^S_1/k, β^X = −M^S_2/k.
  static double servo_offset_book(const models::PlatformAxisParams& a) {
    return (std::is_same_v<Model, models::TwoPositionGyroPlatform> ? -1.0 : 1.0) * a.disturbance / a.k;
  }

  static constexpr std::int64_t kHistory = kMaxLatencyTicks + 2;
  // The level frame's rate about channel i at the start of tick k (k ≥ 0, within the last kHistory ticks).
  void remember_rates(std::int64_t k) {
    for (int i = 0; i < kChannels; ++i)
      rate_hist_[static_cast<std::size_t>(k % kHistory)][static_cast<std::size_t>(i)] =
          plant_.frame_rate_rad_s(i);
  }
  double rate_history(std::int64_t k, int i) const {
    k = k < 0 ? 0 : k;
    return rate_hist_[static_cast<std::size_t>(k % kHistory)][static_cast<std::size_t>(i)];
  }

  const InertialPlatformScene& s_;
  Plant plant_;
  analysis::HalfStepWindow<Model, typename Model::Inputs> window_;
  ActuatorFrame last_{};
  std::array<ChannelStats, 2> stats_{};
  std::array<std::array<double, 2>, static_cast<std::size_t>(kHistory)> rate_hist_{};
  std::int64_t ticks_{0};
};

struct InertialPlatformTraits {
  using Scene = InertialPlatformScene;
  // Every variant records the same Record (the table's columns); make_plant picks the scene's variant.
  using Binding = InertialPlatformRun<models::ThreeAxisPlatform>;
  using Controller = tools::Controller;
  static nlohmann::json limits(const Scene& s) {     return {{"torquer_limit_Nm", s.controller.law.torque_limit_Nm}}; }
  static std::unique_ptr<PlantPort> make_plant(const Scene& s, const PlantOptions&) {
    if (s.plant.axes == 1) return make_plant_port<InertialPlatformRun<models::SingleAxisPlatform>>(s);
    if (s.plant.gyros == plants::PlatformGyros::kTwoPosition)
      return make_plant_port<InertialPlatformRun<models::TwoPositionGyroPlatform>>(s);
    return make_plant_port<InertialPlatformRun<models::ThreeAxisPlatform>>(s);
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_inertial_platform_scene(std::unique_ptr<InertialPlatformScene> s) {
  return std::make_unique<DeviceSceneOf<InertialPlatformTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
