// What a position-gyro platform run reports: the plant of sim/plants/position_gyro_platform_plant.hpp with its
// meters — the steady lag (δ − α) before the slew and during it against (16.7) M1^SP/k, the platform's and the
// gyro frame's slew rates against (16.7) −M2^K/H, the closed loop's dominant root after the disturbance step —
// fitted to the inner gimbal's angle β[k] (with a platform mode faster than the nutation the slowest mode is
// the gyro's nutation, which the pick-off barely shows) with the pick-off's noise as an input
// (sim/analysis/linear_prediction_fit.hpp), and from β's extrema — against the dominant root of (16.8) and of
// the sampled loop,
// the gain band of (16.9) — the half-step error estimate, the CSV columns, and the scene's plant and
// controller for the run modes.
#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/position_gyro_platform/position_gyro_platform_roots.hpp"
#include "gyrostab_signals/position_gyro_platform_outputs.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/position_gyro_platform/position_gyro_platform_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::PositionGyroPlatformPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicPositionGyroPlatformController<firmware::posix::MonotonicClock>;

// Sum over a window of ticks [first, end).
struct WindowMean {
  std::int64_t first{0}, end{0}, n{0};
  double sum{0.0};
  void add(std::int64_t tick, double v) {
    if (tick < first || tick >= end) return;
    sum += v;
    ++n;
  }
  nlohmann::json json() const { return n > 0 ? nlohmann::json(sum / static_cast<double>(n)) : nlohmann::json(nullptr); }
};

nlohmann::json root_json(std::complex<double> r) { return {{"re", r.real()}, {"im", r.imag()}}; }

class PositionGyroPlatformRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::position_gyro_platform::Record;

  explicit PositionGyroPlatformRun(const PositionGyroPlatformScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        window_(std::min<std::int64_t>(s.plant.disturbance_tick, s.loop.ticks() / 2),
                std::max<std::int64_t>(1, static_cast<std::int64_t>(0.5 / s.loop.tick_s()))),
        fit_first_(s.plant.disturbance_tick + ticks_of(s.fit_delay_s)),
        fit_end_(static_cast<std::int64_t>(s.controller.law.slew_start_tick)),
        extrema_(1e-12),
        // From 20 ms after the step to the slew (another input): β at the law's rate, the pick-off noise the
        // law read as the input (when the law runs every tick: a slower law reads only some of the draws).
        divisor_(std::max<std::int64_t>(1, static_cast<std::int64_t>(s.controller.runtime.control_divisor))),
        lp_(static_cast<double>(s.plant.disturbance_tick) * s.loop.tick_s() + 0.02,
            std::min(static_cast<double>(s.controller.law.slew_start_tick) * s.loop.tick_s(), s.loop.duration_s),
            s.controller.runtime.control_period_s(), sampled_order(s), divisor_ == 1 ? 1 : 0) {
    const std::int64_t w = ticks_of(s.lag_window_s);
    const auto start = static_cast<std::int64_t>(s.controller.law.slew_start_tick);
    const auto stop = static_cast<std::int64_t>(s.controller.law.slew_stop_tick);
    lag_before_ = {start - w, start};
    lag_slewing_ = {stop - w, stop};
    rate_first_ = stop - w;
    rate_end_ = stop;
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    pickoff_error_ = f.pickoff_rad - plant_.pickoff_rad();
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    plant_.begin_tick(tick);
    window_.before_tick(tick, plant_.state(), plant_.inputs());
    plant_.integrate(tick);
    window_.after_tick(tick, plant_.state());
    ticks_ = tick + 1;
    // The state at the end of this tick belongs to tick + 1.
    const std::int64_t k = ticks_;
    const double t = static_cast<double>(k) * s_.loop.tick_s();
    const double e = plant_.pickoff_rad();
    pickoff_max_ = std::max(pickoff_max_, std::fabs(e));
    if (k >= fit_first_ && k < fit_end_) extrema_.add(t, plant_.beta_rad());
    if (k % divisor_ == 0) lp_.add(t, plant_.beta_rad(), &pickoff_error_);
    lag_before_.add(k, e);
    lag_slewing_.add(k, e);
    if (k == rate_first_) {
      delta_first_ = plant_.platform_rad();
      alpha_first_ = plant_.gyro_frame_rad();
    }
    if (k == rate_end_) {
      delta_end_ = plant_.platform_rad();
      alpha_end_ = plant_.gyro_frame_rad();
      rate_measured_ = true;
    }
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    r.pickoff_rad = plant_.pickoff_rad();
    r.lag_book_rad = plant_.inputs().disturbance / s_.controller.law.k;
    r.platform_rad = plant_.platform_rad();
    r.platform_rate_rad_s = plant_.platform_rate_rad_s();
    r.gyro_frame_rad = plant_.gyro_frame_rad();
    r.beta_rad = plant_.beta_rad();
    r.platform_torque_Nm = last_.platform_torquer_Nm;
    r.gyro_torque_Nm = last_.gyro_torquer_Nm;
    r.disturbance_Nm = plant_.inputs().disturbance;
    r.base_rad = plant_.base_rad(t);
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const firmware::PositionGyroPlatformParams& law = s_.controller.law;
    const double Tc = s_.controller.runtime.control_period_s();
    const double tau = static_cast<double>(law.latency_ticks) * s_.loop.tick_s();
    const firmware::PlatformGainBand band = firmware::platform_gain_band(law.plant);
    const double rho = firmware::platform_sampled_radius(law.plant, law.k, Tc, tau);
    const double m2 = std::clamp(-law.plant.H * law.slew_rate_rad_s, -law.gyro_torque_limit_Nm, law.gyro_torque_limit_Nm);
    nlohmann::json f{{"ticks", ticks_},
                     {"gain_k_Nm_rad", law.k},
                     {"band_exists", band.exists},
                     {"band_lower_Nm_rad", band.exists ? nlohmann::json(band.lower) : nlohmann::json(nullptr)},
                     {"band_upper_Nm_rad", band.exists ? nlohmann::json(band.upper) : nlohmann::json(nullptr)},
                     {"sampled_spectral_radius", rho},
                     {"sampled_slowest_decay_1_s", -std::log(rho) / Tc},
                     {"lag_book_16_7_rad", lag_book()},
                     {"lag_before_slew_rad", lag_before_.json()},
                     {"lag_slewing_rad", lag_slewing_.json()},
                     {"slew_rate_book_16_7_rad_s", -m2 / law.plant.H},
                     {"pickoff_max_rad", pickoff_max_}};
    const double span = static_cast<double>(rate_end_ - rate_first_) * s_.loop.tick_s();
    f["slew_rate_platform_rad_s"] = rate_measured_ ? nlohmann::json((delta_end_ - delta_first_) / span) : nlohmann::json(nullptr);
    f["slew_rate_gyro_frame_rad_s"] = rate_measured_ ? nlohmann::json((alpha_end_ - alpha_first_) / span) : nlohmann::json(nullptr);
    const std::complex<double> rc = oracles::platform_dominant_root(oracles::platform_continuous_roots(law.plant, law.k));
    const std::complex<double> rs =
        oracles::platform_dominant_root(oracles::platform_sampled_roots(law.plant, law.k, Tc, tau));
    f["dominant_root_16_8"] = root_json(rc);
    f["dominant_root_sampled"] = root_json(rs);
    f["decay_rate_per_s_predicted"] = -rc.real();
    f["frequency_rad_s_predicted"] = rc.imag();
    f["decay_rate_per_s_predicted_sampled"] = -rs.real();
    f["frequency_rad_s_predicted_sampled"] = rs.imag();
    const int n = extrema_.count();
    f["extrema"] = n;
    if (n >= 4) {
      const double eq = extrema_.equilibrium(n - 3);
      const double sigma = std::log(std::fabs(extrema_.value(0) - eq) / std::fabs(extrema_.value(n - 1) - eq)) /
                           (extrema_.time(n - 1) - extrema_.time(0));
      f["dominant_root_extrema"] = root_json({-sigma, 2.0 * std::numbers::pi / extrema_.period()});
    } else {
      f["dominant_root_extrema"] = nullptr;
    }
    if (lp_.valid()) {
      const std::complex<double> m = analysis::nearest_root(lp_.roots(), rc);
      f["dominant_root_measured"] = root_json(m);
      f["decay_rate_per_s"] = -m.real();
      f["frequency_rad_s"] = m.imag();
    } else {
      f["dominant_root_measured"] = nullptr;
      f["decay_rate_per_s"] = nullptr;
      f["frequency_rad_s"] = nullptr;
    }
    return f;
  }

  // report.json "error_estimate": 0.5 s from the disturbance step (the loop's transient).
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Model& m, const Plant::Inputs& in) { m.inputs = in; };
    return error_estimate_json<Plant::Model::kStateSize>(
        window_.estimate<dynamics::Rk4>(plant_.model(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"delta_rad", "delta_rate_rad_s", "alpha_rad", "alpha_rate_rad_s", "beta_rad", "beta_rate_rad_s"},
        "none watched: the torquers, the dampers and the disturbance act");
  }

 private:
  std::int64_t ticks_of(double t) const { return static_cast<std::int64_t>(std::llround(t / s_.loop.tick_s())); }
  double lag_book() const { return s_.plant.disturbance_Nm / s_.controller.law.k; }

  // The fit's order: the sampled loop's non-zero roots and two spare.
  static int sampled_order(const PositionGyroPlatformScene& s) {
    const firmware::PositionGyroPlatformParams& law = s.controller.law;
    const double tau = static_cast<double>(law.latency_ticks) * s.loop.tick_s();
    return static_cast<int>(
               oracles::platform_sampled_roots(law.plant, law.k, s.controller.runtime.control_period_s(), tau).size()) +
           2;
  }

  const PositionGyroPlatformScene& s_;
  Plant plant_;
  analysis::HalfStepWindow<Plant::Model, Plant::Inputs> window_;
  std::int64_t fit_first_, fit_end_;
  analysis::ExtremaMeter<64> extrema_;
  std::int64_t divisor_;
  analysis::LinearPredictionMeter lp_;
  double pickoff_error_{0.0};
  WindowMean lag_before_{}, lag_slewing_{};
  std::int64_t rate_first_{0}, rate_end_{0};
  double delta_first_{0.0}, delta_end_{0.0}, alpha_first_{0.0}, alpha_end_{0.0};
  bool rate_measured_{false};
  double pickoff_max_{0.0};
  ActuatorFrame last_{};
  std::int64_t ticks_{0};
};

struct PositionGyroPlatformTraits {
  using Scene = PositionGyroPlatformScene;
  using Binding = PositionGyroPlatformRun;
  using Controller = tools::Controller;
};

}  // namespace

std::unique_ptr<DeviceScene> make_position_gyro_platform_scene(std::unique_ptr<PositionGyroPlatformScene> s) {
  return std::make_unique<DeviceSceneOf<PositionGyroPlatformTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
