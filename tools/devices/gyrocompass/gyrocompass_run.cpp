// What a gyrocompass run reports: the plant of sim/plants/gyrocompass_plant.hpp with its meters, each
// measured value beside the book's —
//   fixed-base settling: the period and decay rate of α from its extrema (sim/analysis/extrema_meter.hpp)
//   against (13.12) T_K = 2π/ω^K and δ/2, and the strong-coupling period (13.16) for the full form; the
//   equilibrium (Aitken's Δ² on the last extrema, and the final state) against (13.11);
//   per manoeuvre segment: α at the segment's end against the steady equilibrium of (13.22) with damping,
//   α_eq = −(Ω2 + δ β0)/Ω3, β0 = Ω1/(ω^c + Ω3) (= (13.11) at rest, = the speed deviation (13.23) when
//   undamped), the speed deviation (13.23) itself, and the largest |α − α_eq(t)| during the segment — the
//   ballistic deviation, zero for a Schuler-tuned undamped compass (13.26)-(13.28);
//   rolling error: with the swing, the mean α over the last segment minus α_eq against (13.38);
// the half-step error estimate; the CSV columns, the figures, and the scene's plant and controller.
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
#include "sim/analysis/manoeuvre_segment_log.hpp"
#include "gyrostab_signals/gyrocompass_outputs.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/gyrocompass/gyrocompass_sampled.hpp"
#include "tools/devices/gyrocompass/gyrocompass_scene.hpp"
#include "tools/devices/vehicle_instruments/segments_json.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::GyrocompassPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicGyrocompassController<firmware::posix::MonotonicClock>;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = std::numbers::pi / 180.0;

struct CompassSegment : analysis::SegmentSpan {
  double alpha_end{0.0}, alpha_eq_end{0.0}, speed_dev_end{0.0}, latitude_end{0.0};
  double v_north_end{0.0}, v_east_end{0.0}, heading_end{0.0};
  double deviation_max{0.0};                 // max |α − α_eq(t)| [rad]
  double alpha_sum{0.0}, alpha_eq_sum{0.0};  // for the rolling error
};

class GyrocompassRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::gyrocompass::Record;

  explicit GyrocompassRun(const GyrocompassScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        window_(s.loop.ticks() / 2, 1000),
        alpha_extrema_(s.extrema_hysteresis),
        beta_extrema_(s.extrema_hysteresis),
        segments_(s.plant.vehicle),
        // α every extrema_sample_s from 600 s (the nutation, at 0.1 /s, has decayed by e^-60) to the end.
        fit_(600.0, s.loop.duration_s, static_cast<double>(s.extrema_every_ticks) * s.loop.tick_s(), 4) {}

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
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    if (ticks_ % s_.extrema_every_ticks == 0) {
      alpha_extrema_.add(t1, plant_.alpha_rad());
      fit_.add(t1, plant_.alpha_rad());
      beta_extrema_.add(t1, plant_.beta_rad());
    }
    const double a_eq = book_alpha_eq(plant_.frame());
    CompassSegment& r = segments_.current();
    r.deviation_max = std::max(r.deviation_max, std::fabs(plant_.alpha_rad() - a_eq));
    r.alpha_sum += plant_.alpha_rad();
    r.alpha_eq_sum += a_eq;
    ++r.samples;
    segments_.advance(
        ticks_ * s_.loop.tick_ns, t1, [this](CompassSegment& e) { end_segment(e); }, [](CompassSegment&) {});
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    r.alpha_rad = plant_.alpha_rad();
    r.beta_rad = plant_.beta_rad();
    r.alpha_eq_rad = book_alpha_eq(plant_.frame());
    r.level_rad = plant_.level_rad(t);
    r.M1_Nm = last_.vertical_torquer_Nm;
    r.M2_Nm = last_.east_torquer_Nm;
    r.latitude_deg = plant_.motion().latitude / kDeg;
    r.heading_deg = plant_.motion().heading / kDeg;
    r.swing_rad = plant_.swing_rad();
    r.status_bits = static_cast<double>(last_.status);
  }

  bool at_rest() const {
    const motion::VehicleMotionParams& v = s_.plant.vehicle;
    if (v.start.speed != 0.0) return false;
    for (int k = 0; k < v.count; ++k) {
      const motion::ManoeuvreSegment& m = v.segments[static_cast<std::size_t>(k)];
      if (m.acceleration != 0.0 || m.turn_rate != 0.0) return false;
    }
    return true;
  }

  nlohmann::json figures() const {
    const models::GyrocompassParams& gyro = s_.plant.gyro;
    const motion::EarthParams& earth = s_.plant.vehicle.earth;
    const double H = gyro.gyro.H, c_total = gyro.c + s_.controller.law.c_e, f_law = s_.controller.law.f;
    const double we = earth.rotation_rate, g = earth.gravity, R = earth.radius;
    const motion::EarthVehicleSample& now = plant_.motion();
    const double lat = now.latitude;
    const double alpha = plant_.alpha_rad();
    const models::GyrocompassTheory th{H, c_total, f_law, we, lat};
    nlohmann::json f{{"ticks", ticks_},
                     {"omega_c_s", c_total / H},
                     {"omega_c_schuler_tuned_here_s", models::schuler_tuned_omega_c(lat, g, R, we)},
                     {"delta_s", f_law / H},
                     {"latitude_end_deg", lat / kDeg},
                     {"alpha_end_rad", alpha},
                     {"beta_end_rad", plant_.beta_rad()},
                     {"alpha0_book_13_11_rad", th.alpha0()},
                     {"beta0_book_13_11_rad", th.beta0()},
                     {"schuler_period_s", 2.0 * kPi * std::sqrt(R / g)}};
    if (std::isfinite(s_.tune_latitude)) f["tune_latitude_deg"] = s_.tune_latitude / kDeg;
    const bool periodic = th.omega_K_squared() > 0.0;
    f["period_book_13_12_s"] = periodic ? nlohmann::json(th.period()) : nlohmann::json(nullptr);
    f["decay_rate_book_13_12_s"] = th.decay_rate();
    // The compass mode of the model itself, linearised at its equilibrium (the inertia, d1, d2 kept), and of
    // the loop as it runs (hold, period, latency): gyrocompass_sampled.hpp, docs/sampled-data.md.
    // Only on a base at rest: a moving vehicle changes the loop as it goes.
    if (at_rest()) {
      const GyrocompassSampled lin = gyrocompass_sampled(s_);
      const auto finite_or_null = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
      f["decay_rate_per_s_predicted"] = finite_or_null(-lin.continuous.real());
      f["period_s_predicted"] = finite_or_null(2.0 * kPi / lin.continuous.imag());
      f["decay_rate_per_s_predicted_sampled"] = finite_or_null(-lin.sampled.real());
      f["period_s_predicted_sampled"] = finite_or_null(2.0 * kPi / lin.sampled.imag());
      f["sampled_loop_max_abs_z"] = lin.roots.max_abs_z;
      // The compass mode measured: the root of a recurrence fitted to α sampled every extrema_sample_s
      // (linear_prediction_fit.hpp), nearest the prediction.
      if (fit_.valid() && std::isfinite(lin.continuous.real())) {
        const std::complex<double> m = analysis::nearest_root(fit_.roots(), lin.continuous);
        f["decay_rate_per_s"] = -m.real();
        f["period_s"] = 2.0 * kPi / m.imag();
      } else {
        f["decay_rate_per_s"] = nullptr;
        f["period_s"] = nullptr;
      }
    } else {
      for (const char* k : {"decay_rate_per_s_predicted", "period_s_predicted", "decay_rate_per_s_predicted_sampled",
                            "period_s_predicted_sampled", "sampled_loop_max_abs_z"})
        f[k] = nullptr;
      f["linear_prediction"] = "not computed: the vehicle moves (the loop changes with latitude, speed and heading)";
    }
    if (gyro.fidelity == models::InstrumentFidelity::kFull && c_total > 0.0) {
      f["period_book_13_16_s"] =
          2.0 * kPi * std::sqrt((gyro.gyro.A + H * H / c_total) / (H * we * std::cos(lat)));
      f["nutation_frequency_rad_s"] = models::nutation_frequency(gyro.gyro);
    }
    const int n = alpha_extrema_.count();
    f["alpha_extrema"] = n;
    if (n >= 3) {
      f["period_measured_s"] = alpha_extrema_.period();
      f["alpha_eq_measured_rad"] = alpha_extrema_.equilibrium(n - 3);
      f["decay_rate_measured_s"] = alpha_extrema_.decay_rate(n - 3);
      f["decay_rate_measured_first_s"] = alpha_extrema_.decay_rate(0);
    } else {
      f["period_measured_s"] = nullptr;
      f["alpha_eq_measured_rad"] = nullptr;
      f["decay_rate_measured_s"] = nullptr;
      f["decay_rate_measured_first_s"] = nullptr;
    }
    const int nb = beta_extrema_.count();
    f["beta_eq_measured_rad"] =
        nb >= 3 ? nlohmann::json(beta_extrema_.equilibrium(nb - 3)) : nlohmann::json(nullptr);
    const double t_now = static_cast<double>(ticks_) * s_.loop.tick_s();
    f["segments"] = segments_json(segments_, t_now, [&](nlohmann::json& j, const CompassSegment& r) {
      const bool ended = r.ended;
      j["latitude_end_deg"] = (ended ? r.latitude_end : lat) / kDeg;
      j["heading_end_deg"] = (ended ? r.heading_end : now.heading) / kDeg;
      j["v_north_end_m_s"] = ended ? r.v_north_end : now.v_north;
      j["v_east_end_m_s"] = ended ? r.v_east_end : now.v_east;
      j["alpha_end_rad"] = ended ? r.alpha_end : alpha;
      j["alpha_eq_book_end_rad"] = ended ? r.alpha_eq_end : book_alpha_eq(plant_.frame());
      j["speed_deviation_book_13_23_rad"] = ended ? r.speed_dev_end : speed_dev(now);
      j["deviation_from_equilibrium_max_rad"] = r.deviation_max;
      j["alpha_mean_minus_eq_rad"] = (r.alpha_sum - r.alpha_eq_sum) / static_cast<double>(r.samples);
    });
    if (gyro.swing_inertia > 0.0) {
      // (13.38) with ψ of the final state.
      const models::ShipRoll& roll = gyro.roll;
      const double wg2 = gyro.c / gyro.swing_inertia, ws2 = roll.omega() * roll.omega(), b0 = roll.b0();
      const double gs = gyro.c, psi = now.heading, gg = gyro.gravity;
      const double num = -gs * b0 * b0 * wg2 * std::sin(2.0 * psi);
      const double den = 4.0 * gg * gg * H * we * std::cos(lat) * (wg2 - ws2) +
                         2.0 * gs * b0 * b0 * wg2 * std::cos(2.0 * psi);
      f["rolling_error_book_13_38_rad"] = num / den;
      f["swing_frequency_rad_s"] = std::sqrt(wg2);
      f["roll_acceleration_amplitude_m_s2"] = b0;
    }
    return f;
  }

  // report.json "error_estimate": 1000 ticks from the run's middle (the frame's motion is interpolated within
  // the tick exactly as in the run, so the re-integration at half the step sees the same forcing).
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Model& m, const Plant::Inputs& in) { m.inputs = in; };
    return error_estimate_json<6>(
        window_.estimate<dynamics::Rk4>(plant_.model(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s", "gamma_rad", "gamma_rate_rad_s"},
        "none watched: ship motion, damping torque and friction act");
  }

 private:
  // The book's equilibrium (13.22) with damping (level tilt neglected): α_eq = −(Ω2 + δ β0)/Ω3.
  double book_alpha_eq(const models::FrameSample& w) const {
    const double H = s_.plant.gyro.gyro.H;
    const double wc = (s_.plant.gyro.c + s_.controller.law.c_e) / H, delta = s_.controller.law.f / H;
    const double beta0 = w.Omega.x() / (wc + w.Omega.z());
    return -(w.Omega.y() + delta * beta0) / w.Omega.z();
  }
  double speed_dev(const motion::EarthVehicleSample& m) const {
    const motion::EarthParams& e = s_.plant.vehicle.earth;
    return models::speed_deviation(m.v_north, m.v_east, m.latitude, e.radius, e.rotation_rate);
  }
  void end_segment(CompassSegment& r) const {
    const motion::EarthVehicleSample& m = plant_.motion();
    r.alpha_end = plant_.alpha_rad();
    r.alpha_eq_end = book_alpha_eq(plant_.frame());
    r.speed_dev_end = speed_dev(m);
    r.latitude_end = m.latitude;
    r.heading_end = m.heading;
    r.v_north_end = m.v_north;
    r.v_east_end = m.v_east;
  }

  const GyrocompassScene& s_;
  Plant plant_;
  analysis::HalfStepWindow<Plant::Model, Plant::Inputs> window_;
  ActuatorFrame last_{};
  analysis::ExtremaMeter<64> alpha_extrema_, beta_extrema_;
  analysis::ManoeuvreSegmentLog<CompassSegment> segments_;
  analysis::LinearPredictionMeter fit_;
  std::int64_t ticks_{0};
};

struct GyrocompassTraits {
  using Scene = GyrocompassScene;
  using Binding = GyrocompassRun;
  using Controller = tools::Controller;
  static nlohmann::json limits(const Scene& s) {     return {{"torquer_limit_Nm", s.controller.law.torque_limit_Nm}}; }
};

}  // namespace

std::unique_ptr<DeviceScene> make_gyrocompass_scene(std::unique_ptr<GyrocompassScene> s) {
  return std::make_unique<DeviceSceneOf<GyrocompassTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
