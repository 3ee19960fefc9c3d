// Scene binding of the pendulous gyrocompass (Magnus ch. 13, (13.7)-(13.39)): the compass
// (sim/models/gyrocompass.hpp, full or precession form) in the geographic frame of a vehicle on the rotating
// Earth (sim/motion/earth_vehicle.hpp — at rest for the fixed-base compass, or a ship crossing latitudes),
// damped and electrically pendulous through the firmware (firmware/app/gyrocompass_controller.hpp), the
// electrical pendulosity optionally Schuler-tuned (13.26) for a design latitude. Sensors: the level sensor
// (elevation above the apparent horizon, seeded noise) and the follow-up pick-off.
// Figures (each measured value beside the book's):
//   fixed-base settling — period and decay rate of α from its extrema (analysis/extrema_meter.hpp) against
//   (13.12) T_K = 2π/ω^K and δ/2, and the strong-coupling period (13.16) for the full form; the equilibrium
//   (Aitken's Δ² on the last extrema, and the final state) against (13.11);
//   per manoeuvre segment — α at the segment's end against the steady equilibrium of (13.22) with damping,
//   α_eq = −(Ω2 + δ β0)/Ω3, β0 = Ω1/(ω^c + Ω3) (= (13.11) at rest, = the speed deviation (13.23) when
//   undamped), the speed deviation (13.23) itself, and the largest |α − α_eq(t)| during the segment — the
//   ballistic deviation, zero for a Schuler-tuned undamped compass (13.26)-(13.28);
//   rolling error — with the swing enabled, the mean α over the last segment minus α_eq against (13.38).
// Keys: docs/scenes.md#gyrocompass.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "firmware/app/gyrocompass_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyrocompass.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/devices/gyro_frame_scene.hpp"
#include "tools/devices/manoeuvre_segment_log.hpp"
#include "tools/devices/scene_device.hpp"
#include "tools/devices/scene_run.hpp"
#include "tools/devices/vehicle_frame_feed.hpp"
#include "tools/devices/vehicle_motion_scene.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/run/run_device.hpp"

namespace gyrostab::tools {
namespace {

using Controller = firmware::BasicGyrocompassController<firmware::posix::MonotonicClock>;
using Model = models::Gyrocompass;
constexpr double kPi = std::numbers::pi;

enum Stream : std::uint64_t { kLevelStream = 1 };

struct GcScene {
  LoopConfig loop;
  VehicleMotionConfig motion;
  models::GyrocompassParams gyro;
  double alpha0{0.0}, beta0{0.0};  // initial offsets from the equilibrium (or absolute, unsettled) [rad]
  bool start_settled{true};
  double level_noise_density{0.0};  // [rad/√Hz]
  double tune_latitude{0.0};        // [rad] (NaN: c_e given directly)
  firmware::GyrocompassConfig controller;
  int extrema_every_ticks{100};
  double extrema_hysteresis{1e-5};  // [rad]
};

struct CompassSegment : SegmentSpan {
  double alpha_end{0.0}, alpha_eq_end{0.0}, speed_dev_end{0.0}, latitude_end{0.0};
  double v_north_end{0.0}, v_east_end{0.0}, heading_end{0.0};
  double deviation_max{0.0};             // max |α − α_eq(t)| [rad]
  double alpha_sum{0.0}, alpha_eq_sum{0.0};  // for the rolling error
};

class GyrocompassDevice {
 public:
  explicit GyrocompassDevice(const GcScene& s)
      : s_(s),
        plant_(s.gyro),
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        feed_(s.motion, s.loop.tick_ns,
              PlumbFrame{&motion::EarthVehicleSample::geographic, frame_up_east_north, s.motion.earth.rotation_rate}),
        level_noise_({s.level_noise_density, 0.0, 0.0}, s.loop.tick_s()),
        rng_level_(s.loop.seed, kLevelStream),
        controller_(std::make_unique<Controller>(s.controller)),
        alpha_extrema_(s.extrema_hysteresis),
        beta_extrema_(s.extrema_hysteresis),
        segments_(s.motion) {
    plant_.inputs.frame.hold(feed_.frame());
    plant_.inputs.heading = feed_.motion().heading;
    x_ = Model::make_state(s.alpha0, s.beta0);
    if (s.start_settled) {
      double a, b;
      equilibrium(feed_.frame(), a, b);
      x_[0] += a;
      x_[1] += b;
    }
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    double a_rate, b_rate;
    plant_.rates(t, x_, a_rate, b_rate);
    f.gimbal_angle_rad[msg::kAxis2] = plant_.level_signal(t, x_) + level_noise_.sample(rng_level_);
    const double heading = feed_.motion().heading;
    f.gimbal_angle_rad[msg::kAxis1] = std::remainder(-(heading + x_[0]), 2.0 * kPi);
    f.gimbal_rate_rad_s[msg::kAxis1] = a_rate;
    f.gimbal_rate_rad_s[msg::kAxis2] = b_rate;
    f.carrier_angle_rad[msg::kYaw] = std::remainder(heading + x_[0], 2.0 * kPi);
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.inputs.M1 = cmd.gimbal_torque_Nm[msg::kAxis1];
    plant_.inputs.M2 = cmd.gimbal_torque_Nm[msg::kAxis2];
  }

  void advance(std::int64_t tick) {
    feed_.begin_tick(tick, plant_.inputs.frame);
    window_.before_tick(tick, x_, plant_.inputs);
    driver_.advance_tick(tick, x_);
    window_.after_tick(tick, x_);
    feed_.end_tick(plant_.inputs.frame);
    plant_.inputs.heading = feed_.motion().heading;
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    if (ticks_ % s_.extrema_every_ticks == 0) {
      alpha_extrema_.add(t1, x_[0]);
      beta_extrema_.add(t1, x_[1]);
    }
    const double a_eq = book_alpha_eq(feed_.frame());
    CompassSegment& r = segments_.current();
    r.deviation_max = std::max(r.deviation_max, std::fabs(x_[0] - a_eq));
    r.alpha_sum += x_[0];
    r.alpha_eq_sum += a_eq;
    ++r.samples;
    segments_.advance(ticks_ * s_.loop.tick_ns, t1, [this](CompassSegment& e) { end_segment(e); },
                      [](CompassSegment&) {});
  }

  bool finite() const { return x_.allFinite(); }

  // report.json "error_estimate": the half-step comparison (the frame's motion is interpolated within the tick
  // exactly as in the run, so the re-integration at half the step sees the same forcing).
  nlohmann::json error_estimate() const {
    const auto apply = [](auto& p, const auto& in) { p.inputs = in; };
    return window_.template estimate<dynamics::Rk4>(plant_, apply, s_.loop.tick_ns, s_.loop.substeps, 4, {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s", "gamma_rad", "gamma_rate_rad_s"},
                                                    "none watched: ship motion, damping torque and friction act");
  }

  static std::vector<std::string> columns() {
    return {"alpha_rad", "beta_rad", "alpha_eq_rad", "level_rad", "M1_Nm", "M2_Nm",
            "latitude_deg", "heading_deg", "swing_rad", "status_bits"};
  }
  void record(double* row) const {
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    row[0] = x_[0];
    row[1] = x_[1];
    row[2] = book_alpha_eq(feed_.frame());
    row[3] = plant_.level_signal(t, x_);
    row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
    row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[6] = feed_.motion().latitude / kDeg;
    row[7] = feed_.motion().heading / kDeg;
    row[8] = x_[4];
    row[9] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const double H = s_.gyro.gyro.H, c_total = s_.gyro.c + s_.controller.law.c_e, f_law = s_.controller.law.f;
    const double we = s_.motion.earth.rotation_rate, g = s_.motion.earth.gravity, R = s_.motion.earth.radius;
    const motion::EarthVehicleSample& now = feed_.motion();
    const double lat = now.latitude;
    models::GyrocompassTheory th{H, c_total, f_law, we, lat};
    nlohmann::json f{{"ticks", ticks_},
                     {"omega_c_s", c_total / H},
                     {"omega_c_schuler_tuned_here_s", models::schuler_tuned_omega_c(lat, g, R, we)},
                     {"delta_s", f_law / H},
                     {"latitude_end_deg", lat / kDeg},
                     {"alpha_end_rad", x_[0]},
                     {"beta_end_rad", x_[1]},
                     {"alpha0_book_13_11_rad", th.alpha0()},
                     {"beta0_book_13_11_rad", th.beta0()},
                     {"schuler_period_s", 2.0 * kPi * std::sqrt(R / g)}};
    if (std::isfinite(s_.tune_latitude)) f["tune_latitude_deg"] = s_.tune_latitude / kDeg;
    const bool periodic = th.omega_K_squared() > 0.0;
    f["period_book_13_12_s"] = periodic ? nlohmann::json(th.period()) : nlohmann::json(nullptr);
    f["decay_rate_book_13_12_s"] = th.decay_rate();
    if (s_.gyro.fidelity == models::InstrumentFidelity::kFull && c_total > 0.0) {
      f["period_book_13_16_s"] =
          2.0 * kPi * std::sqrt((s_.gyro.gyro.A + H * H / c_total) / (H * we * std::cos(lat)));  // (13.16)
      f["nutation_frequency_rad_s"] = models::nutation_frequency(s_.gyro.gyro);
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
    f["beta_eq_measured_rad"] = nb >= 3 ? nlohmann::json(beta_extrema_.equilibrium(nb - 3)) : nlohmann::json(nullptr);
    const double t_now = static_cast<double>(ticks_) * s_.loop.tick_s();
    f["segments"] = segments_.to_json(t_now, [&](nlohmann::json& j, const CompassSegment& r) {
      const bool ended = r.ended;
      j["latitude_end_deg"] = (ended ? r.latitude_end : lat) / kDeg;
      j["heading_end_deg"] = (ended ? r.heading_end : now.heading) / kDeg;
      j["v_north_end_m_s"] = ended ? r.v_north_end : now.v_north;
      j["v_east_end_m_s"] = ended ? r.v_east_end : now.v_east;
      j["alpha_end_rad"] = ended ? r.alpha_end : x_[0];
      j["alpha_eq_book_end_rad"] = ended ? r.alpha_eq_end : book_alpha_eq(feed_.frame());
      j["speed_deviation_book_13_23_rad"] = ended ? r.speed_dev_end : speed_dev(now);
      j["deviation_from_equilibrium_max_rad"] = r.deviation_max;
      j["alpha_mean_minus_eq_rad"] = (r.alpha_sum - r.alpha_eq_sum) / static_cast<double>(r.samples);
    });
    if (s_.gyro.swing_inertia > 0.0) {
      // (13.38) with ψ of the final state.
      const models::ShipRoll& roll = s_.gyro.roll;
      const double wg2 = s_.gyro.c / s_.gyro.swing_inertia, ws2 = roll.omega() * roll.omega(), b0 = roll.b0();
      const double gs = s_.gyro.c, psi = now.heading, gg = s_.gyro.gravity;
      const double num = -gs * b0 * b0 * wg2 * std::sin(2.0 * psi);
      const double den = 4.0 * gg * gg * H * we * std::cos(lat) * (wg2 - ws2) + 2.0 * gs * b0 * b0 * wg2 * std::cos(2.0 * psi);
      f["rolling_error_book_13_38_rad"] = num / den;
      f["swing_frequency_rad_s"] = std::sqrt(wg2);
      f["roll_acceleration_amplitude_m_s2"] = b0;
    }
    return f;
  }

 private:
  // The model's steady state for constant frame rates and level (precession form, M1 = −f β_lvl,
  // M2 = −c_total β_lvl): β0 = (HΩ1 + c β_L)/(HΩ3 + c), α0 = −(HΩ2 + f(β0 − β_L))/(HΩ3).
  void equilibrium(const models::FrameSample& w, double& alpha, double& beta) const {
    const double H = s_.gyro.gyro.H, c = s_.gyro.c + s_.controller.law.c_e, fd = s_.controller.law.f;
    const double bL = models::apparent_horizon_tilt(w.f);
    beta = (H * w.Omega.x() + c * bL) / (H * w.Omega.z() + c);
    alpha = -(H * w.Omega.y() + fd * (beta - bL)) / (H * w.Omega.z());
  }
  // The book's equilibrium (13.22) with damping (level tilt neglected): α_eq = −(Ω2 + δ β0)/Ω3.
  double book_alpha_eq(const models::FrameSample& w) const {
    const double H = s_.gyro.gyro.H;
    const double wc = (s_.gyro.c + s_.controller.law.c_e) / H, delta = s_.controller.law.f / H;
    const double beta0 = w.Omega.x() / (wc + w.Omega.z());
    return -(w.Omega.y() + delta * beta0) / w.Omega.z();
  }
  double speed_dev(const motion::EarthVehicleSample& m) const {
    return models::speed_deviation(m.v_north, m.v_east, m.latitude, s_.motion.earth.radius,
                                   s_.motion.earth.rotation_rate);
  }
  void end_segment(CompassSegment& r) const {
    const motion::EarthVehicleSample& m = feed_.motion();
    r.alpha_end = x_[0];
    r.alpha_eq_end = book_alpha_eq(feed_.frame());
    r.speed_dev_end = speed_dev(m);
    r.latitude_end = m.latitude;
    r.heading_end = m.heading;
    r.v_north_end = m.v_north;
    r.v_east_end = m.v_east;
  }

  const GcScene& s_;
  Model plant_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  Model::State x_;
  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): 1000 ticks from the run's middle.
  accuracy::HalfStepWindow<Model, std::remove_cvref_t<decltype(std::declval<Model&>().inputs)>> window_{s_.loop.ticks() / 2, 1000};
  VehicleFrameFeed<PlumbFrame> feed_;  // the geographic frame
  sensors::SensorNoise level_noise_;
  random::SeededRng rng_level_;
  std::unique_ptr<Controller> controller_;
  msg::ActuatorFrame last_{};
  analysis::ExtremaMeter<64> alpha_extrema_, beta_extrema_;
  ManoeuvreSegmentLog<CompassSegment> segments_;
  std::int64_t ticks_{0};
};

bool read_scene(SceneReader& r, GcScene& s) {
  read_gyro_frame_scene_head(r,
                             {0.05, "full (13.7) or precession (13.10) form",
                              "inertia about the vertical axis 1 [kg m²]",
                              "inertia about the east axis 2 [kg m²]"},
                             s);
  auto& g = s.gyro;
  g.c = r.number("gyro", "c", 0.0, Range::non_negative(), "mechanical pendulous moment G s [N m/rad]");
  g.d1 = r.number("gyro", "d1", 0.0, Range::non_negative(), "viscous damping about the vertical [N m s/rad]");
  g.d2 = r.number("gyro", "d2", g.d1, Range::non_negative(), "viscous damping about the east axis [N m s/rad]");
  g.gravity = s.motion.earth.gravity;
  g.swing_inertia = r.number("gyro", "swing_inertia", 0.0, Range::non_negative(),
                             "inertia about the rotor axis for the swing of (13.31); 0: no swing [kg m²]");
  s.alpha0 = kDeg * r.number("gyro", "alpha0_deg", 0.0, Range::closed(-30.0, 30.0),
                             "initial azimuth offset (from the equilibrium if start_settled) [deg]");
  s.beta0 = kDeg * r.number("gyro", "beta0_deg", 0.0, Range::closed(-30.0, 30.0), "initial elevation offset [deg]");
  s.start_settled = r.flag("gyro", "start_settled", true, "start at the steady state of the initial motion");
  g.roll.amplitude = kDeg * r.number("roll", "amplitude_deg", 0.0, Range::closed(0.0, 45.0), "ship roll Φ [deg]");
  g.roll.period = r.number("roll", "period_s", 10.0, Range::closed(1.0, 100.0), "roll period [s]");
  g.roll.height = r.number("roll", "height_m", 0.0, Range::closed(0.0, 100.0), "compass above the roll axis [m]");
  if (const char* why = g.invalid_reason()) r.fail("gyro", "H", why);

  s.level_noise_density =
      r.number("sensors", "level_noise_density", 0.0, Range::non_negative(), "level sensor noise [rad/sqrt(Hz)]");

  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  auto& l = c.law;
  l.H = g.gyro.H;
  const double we = s.motion.earth.rotation_rate;
  s.tune_latitude = std::numeric_limits<double>::quiet_NaN();
  if (r.has("controller", "tune_latitude_deg")) {
    s.tune_latitude = kDeg * r.number("controller", "tune_latitude_deg", 50.0, Range::closed(-80.0, 80.0),
                                      "Schuler-tune the total pendulosity for this latitude (13.26) [deg]");
    if (r.has("controller", "c_e")) r.fail("controller", "c_e", "give either c_e or tune_latitude_deg, not both");
    l.c_e = firmware::schuler_tuned_pendulosity(l.H, s.tune_latitude, s.motion.earth.gravity, s.motion.earth.radius,
                                                we) -
            g.c;
    if (!(l.c_e >= 0.0))
      r.fail("controller", "tune_latitude_deg", "the mechanical pendulosity c already exceeds the tuned value");
  } else {
    l.c_e = r.number("controller", "c_e", 0.0, Range::non_negative(), "electrical pendulosity [N m/rad]");
  }
  const double design_lat = std::isfinite(s.tune_latitude) ? s.tune_latitude : s.motion.start.latitude;
  if (r.has("controller", "damping_ratio")) {
    const double zeta = r.number("controller", "damping_ratio", 0.0, Range::closed(0.0, 2.0),
                                 "damping ratio of (13.12) at the design latitude [-]");
    if (r.has("controller", "f")) r.fail("controller", "f", "give either f or damping_ratio, not both");
    l.f = firmware::gyrocompass_damping_for_ratio(l.H, g.c + l.c_e, design_lat, zeta, we);
  } else {
    l.f = r.number("controller", "f", 0.0, Range::non_negative(), "damping M1 = -f beta_level [N m/rad]");
  }
  l.torque_limit_Nm = r.number("controller", "torque_limit_Nm", 0.1, Range::positive(), "torquer limit [N m]");
  if (!(g.c + l.c_e > 0.0)) r.fail("gyro", "c", "the compass needs a pendulous moment: c + c_e > 0");
  const double every_s =
      r.number("report", "extrema_sample_s", 1.0, Range::positive(), "sampling of alpha for the extrema [s]");
  s.extrema_every_ticks = std::max<int>(1, static_cast<int>(std::llround(every_s / s.loop.tick_s())));
  s.extrema_hysteresis = r.number("report", "extrema_hysteresis_rad", 1e-5, Range::non_negative(),
                                  "an extremum counts once the signal has moved back this much [rad]");

  if (r.ok()) {
    if (const char* why = corners_on_ticks(s.motion, s.loop.tick_ns)) r.fail("segment1", "duration_s", why);
    const firmware::ConfigCheck check = Controller::check(c);
    if (!check.ok) r.fail("controller", "f", "refused by the controller's start-up check: " + describe(check));
    if (std::fabs(s.motion.start.latitude) > 85.0 * kDeg)
      r.fail("vehicle", "latitude_deg", "a gyrocompass has no directive torque near the poles (13.6): |latitude| <= 85");
    if (g.fidelity == models::InstrumentFidelity::kFull) {
      // Closed-loop linearization at the start latitude at rest: the damping torque −f β is circulatory
      // and can make the nutation grow (model header).
      const double H = g.gyro.H, wh = we * std::cos(s.motion.start.latitude);
      refuse_growing_nutation(r, g.gyro, {H * wh, l.f, 0.0, H * wh + g.c + l.c_e}, g.d1, g.d2, "the damping torque",
                              "give the sphere viscous damping d1, d2 (d/A well above f/H = " + format_3g(l.f / H) +
                                  " /s)");
    }
    Model m(g);
    m.inputs.frame.hold({dynamics::Vec3(we * std::sin(design_lat), 0.0, we * std::cos(design_lat)),
                         dynamics::Vec3::Zero(), dynamics::Vec3(s.motion.earth.gravity, 0.0, 0.0)});
    refuse_long_rk4_substep(r, s.loop, m);
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_gyrocompass(SceneReader& reader, const RunRequest& req) {
  return run_scene<GyrocompassDevice>(reader, req, read_scene);
}

}  // namespace gyrostab::tools
