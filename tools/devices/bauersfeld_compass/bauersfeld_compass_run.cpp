// What a spatial-compass run reports: the plant of sim/plants/bauersfeld_compass_plant.hpp with its meters —
// the tilt of the sphere's axis a1 from the geocentric vertical (largest, at the end: ~1e-12 rad when tuned
// and started per (13.64), whatever the vehicle does); the azimuth error of a3 against the tuned compass's
// closed form atan2(−v_N, v_E + ω^E R cosφ) and δ against sin δ = H |ω_IG horizontal| / (2 f)
// (sim/oracles/bauersfeld_compass.hpp); the periods of the two tilt components from their zero crossings
// beside (13.63); the tuning ratio H²/(f m s |R^M|). The CSV columns, the half-step error estimate, and the
// scene's plant and controller for the run modes.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/bauersfeld_compass_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/hysteresis_crossings.hpp"
#include "sim/oracles/bauersfeld_compass.hpp"
#include "tools/devices/bauersfeld_compass/bauersfeld_compass_scene.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::BauersfeldCompassPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = BauersfeldCompassController<firmware::posix::MonotonicClock>;

// An angle difference in (−π, π].
double angle_diff(double a, double b) {
  return std::remainder(a - b, 2.0 * std::numbers::pi);
}

class BauersfeldCompassRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::bauersfeld_compass::Record;

  explicit BauersfeldCompassRun(const BauersfeldCompassScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        window_(s.loop.ticks() / 2,
                std::max<std::int64_t>(1, static_cast<std::int64_t>(600.0 / s.loop.tick_s()))),
        east_(s.period_threshold),
        north_(s.period_threshold) {
    measure(0);
  }

  void sense(std::int64_t tick, SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    window_.before_tick(tick, plant_.state(), plant_.held_inputs());
    plant_.advance(tick);
    window_.after_tick(tick, plant_.state());
    ticks_ = tick + 1;
    measure(ticks_);
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& row) const {
    constexpr double deg = 180.0 / std::numbers::pi;
    const models::BauersfeldReading& r = plant_.reading();
    const motion::EarthVehicleSample& v = plant_.motion();
    row.tilt_east_rad = r.tilt_east;
    row.tilt_north_rad = r.tilt_north;
    row.tilt_rad = r.tilt;
    row.azimuth_error_rad = r.azimuth;
    row.azimuth_book_rad = plant_.azimuth_book_rad();
    row.delta_rad = plant_.delta_rad();
    row.delta_book_rad = plant_.delta_book_rad();
    row.speed_m_s = v.speed;
    row.heading_deg = v.heading * deg;
    row.latitude_deg = v.latitude * deg;
    row.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const models::BauersfeldCompassParams& c = s_.plant.compass;
    const double RM = bauersfeld_radius_M(s_);
    const double ratio = models::bauersfeld_tuning_ratio(c, RM);
    const auto period = [](const analysis::HysteresisCrossings& x) {
      return x.crossings() >= 2 ? nlohmann::json(x.period() / 60.0) : nlohmann::json(nullptr);
    };
    return {{"tuning_ratio", ratio},
            {"f_Nm", c.f},
            {"f_tuned_Nm", models::bauersfeld_tuned_spring(c.H, c.m, c.s, RM)},
            {"radius_M_m", RM},
            {"effective_inertia_kg_m2", c.effective_inertia()},
            {"schuler_period_book_min", oracles::bauersfeld_period(RM, c.gravity) / 60.0},
            {"step_s", s_.loop.tick_s() / s_.loop.substeps},
            {"ticks", ticks_},
            {"tilt_max_rad", tilt_max_},
            {"tilt_max_time_s", tilt_max_t_},
            {"tilt_end_rad", plant_.reading().tilt},
            {"azimuth_error_max_abs_rad", azimuth_max_},
            {"azimuth_deviation_from_book_max_rad", azimuth_dev_},
            {"delta_min_rad", delta_min_},
            {"delta_max_rad", delta_max_},
            {"delta_deviation_from_book_max_rad", delta_dev_},
            {"sin_delta_max", sin_delta_max_},
            {"delta_real", sin_delta_max_ < 1.0},
            {"rate_bound_rad_s", s_.rate_bound},
            {"sin_delta_bound", c.H * s_.rate_bound / (2.0 * c.f)},
            {"period_east_min", period(east_)},
            {"period_north_min", period(north_)},
            {"period_crossings_east", east_.crossings()},
            {"period_crossings_north", north_.crossings()}};
  }

  // report.json "error_estimate": 600 s from the run's middle.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics&, const Plant::HeldInputs&) {};
    return error_estimate_json<6>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"a1_x", "a1_y", "a1_z", "a1_rate_x_1_s", "a1_rate_y_1_s", "a1_rate_z_1_s"},
        "|a1| = 1 and a1·a1' = 0, held by projection");
  }

 private:
  void measure(std::int64_t tick) {
    const double t = 1e-9 * static_cast<double>(tick * s_.loop.tick_ns);
    const models::BauersfeldReading& r = plant_.reading();
    if (r.tilt > tilt_max_) {
      tilt_max_ = r.tilt;
      tilt_max_t_ = t;
    }
    azimuth_max_ = std::max(azimuth_max_, std::fabs(r.azimuth));
    azimuth_dev_ = std::max(azimuth_dev_, std::fabs(angle_diff(r.azimuth, plant_.azimuth_book_rad())));
    delta_min_ = std::min(delta_min_, plant_.delta_rad());
    delta_max_ = std::max(delta_max_, plant_.delta_rad());
    delta_dev_ = std::max(delta_dev_, std::fabs(plant_.delta_rad() - plant_.delta_book_rad()));
    sin_delta_max_ = std::max(sin_delta_max_, plant_.sin_delta());
    east_.add(t, r.tilt_east);
    north_.add(t, r.tilt_north);
  }

  const BauersfeldCompassScene& s_;
  Plant plant_;
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
  analysis::HysteresisCrossings east_, north_;
  ActuatorFrame last_{};
  double tilt_max_{0.0}, tilt_max_t_{0.0}, azimuth_max_{0.0}, azimuth_dev_{0.0};
  double delta_min_{1e300}, delta_max_{0.0}, delta_dev_{0.0}, sin_delta_max_{0.0};
  std::int64_t ticks_{0};
};

struct BauersfeldCompassTraits {
  using Scene = BauersfeldCompassScene;
  using Binding = BauersfeldCompassRun;
  using Controller = tools::Controller;
};

}  // namespace

std::unique_ptr<DeviceScene> make_bauersfeld_compass_scene(std::unique_ptr<BauersfeldCompassScene> s) {
  return std::make_unique<DeviceSceneOf<BauersfeldCompassTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
