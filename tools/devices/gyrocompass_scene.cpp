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
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "firmware/app/gyrocompass_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyrocompass.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/devices/scene_device.hpp"
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

struct CompassSegment {
  bool started{false}, ended{false};
  double t_start{0.0}, t_end{0.0};
  double alpha_end{0.0}, alpha_eq_end{0.0}, speed_dev_end{0.0}, latitude_end{0.0};
  double v_north_end{0.0}, v_east_end{0.0}, heading_end{0.0};
  double deviation_max{0.0};             // max |α − α_eq(t)| [rad]
  double alpha_sum{0.0}, alpha_eq_sum{0.0};  // for the rolling error
  long samples{0};
};

class GyrocompassDevice {
 public:
  explicit GyrocompassDevice(const GcScene& s)
      : s_(s),
        plant_(s.gyro),
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        vehicle_(make_vehicle(s.motion)),
        corners_(s.motion),
        level_noise_({s.level_noise_density, 0.0, 0.0}, s.loop.tick_s()),
        rng_level_(s.loop.seed, kLevelStream),
        controller_(std::make_unique<Controller>(s.controller)),
        alpha_extrema_(s.extrema_hysteresis),
        beta_extrema_(s.extrema_hysteresis) {
    sample(0, current_, current_motion_);
    plant_.inputs.frame.hold(current_);
    plant_.inputs.heading = current_motion_.heading;
    x_ = Model::make_state(s.alpha0, s.beta0);
    if (s.start_settled) {
      double a, b;
      equilibrium(current_, a, b);
      x_[0] += a;
      x_[1] += b;
    }
    segment_ = segment_at(0);
    begin_segment(segment_, 0.0);
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    double a_rate, b_rate;
    plant_.rates(t, x_, a_rate, b_rate);
    f.gimbal_angle_rad[msg::kAxis2] = plant_.level_signal(t, x_) + level_noise_.sample(rng_level_);
    f.gimbal_angle_rad[msg::kAxis1] = std::remainder(-(current_motion_.heading + x_[0]), 2.0 * kPi);
    f.gimbal_rate_rad_s[msg::kAxis1] = a_rate;
    f.gimbal_rate_rad_s[msg::kAxis2] = b_rate;
    f.carrier_angle_rad[msg::kYaw] = std::remainder(current_motion_.heading + x_[0], 2.0 * kPi);
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.inputs.M1 = cmd.gimbal_torque_Nm[msg::kAxis1];
    plant_.inputs.M2 = cmd.gimbal_torque_Nm[msg::kAxis2];
  }

  void advance(std::int64_t tick) {
    const std::int64_t t1_ns = (tick + 1) * s_.loop.tick_ns;
    models::FrameSample next;
    motion::EarthVehicleSample next_motion = vehicle_.sample_left_ns(t1_ns);  // left limit at a corner
    frame_of(next_motion, next);
    plant_.inputs.frame.t0 = static_cast<double>(tick) * s_.loop.tick_s();
    plant_.inputs.frame.h = s_.loop.tick_s();
    plant_.inputs.frame.s0 = current_;
    plant_.inputs.frame.s1 = next;
    driver_.advance_tick(tick, x_);
    if (corners_.corner_at(t1_ns)) {
      sample(t1_ns, current_, current_motion_);
    } else {
      current_ = next;
      current_motion_ = next_motion;
    }
    plant_.inputs.frame.hold(current_);
    plant_.inputs.heading = current_motion_.heading;
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    if (ticks_ % s_.extrema_every_ticks == 0) {
      alpha_extrema_.add(t1, x_[0]);
      beta_extrema_.add(t1, x_[1]);
    }
    const double a_eq = book_alpha_eq(current_);
    CompassSegment& r = segments_[static_cast<std::size_t>(segment_)];
    r.deviation_max = std::max(r.deviation_max, std::fabs(x_[0] - a_eq));
    r.alpha_sum += x_[0];
    r.alpha_eq_sum += a_eq;
    ++r.samples;
    const int seg = segment_at(t1_ns);
    if (seg != segment_) {
      end_segment(segment_, t1);
      segment_ = seg;
      begin_segment(seg, t1);
    }
  }

  bool finite() const { return x_.allFinite(); }

  static std::vector<std::string> columns() {
    return {"alpha_rad", "beta_rad", "alpha_eq_rad", "level_rad", "M1_Nm", "M2_Nm",
            "latitude_deg", "heading_deg", "swing_rad", "status_bits"};
  }
  void record(double* row) const {
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    row[0] = x_[0];
    row[1] = x_[1];
    row[2] = book_alpha_eq(current_);
    row[3] = plant_.level_signal(t, x_);
    row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
    row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[6] = current_motion_.latitude / kDeg;
    row[7] = current_motion_.heading / kDeg;
    row[8] = x_[4];
    row[9] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const double H = s_.gyro.gyro.H, c_total = s_.gyro.c + s_.controller.law.c_e, f_law = s_.controller.law.f;
    const double we = s_.motion.earth.rotation_rate, g = s_.motion.earth.gravity, R = s_.motion.earth.radius;
    const double lat = current_motion_.latitude;
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
    nlohmann::json segs = nlohmann::json::array();
    for (int i = 0; i <= s_.motion.count; ++i) {
      const CompassSegment& r = segments_[static_cast<std::size_t>(i)];
      if (!r.started || r.samples == 0) continue;
      const bool ended = r.ended;
      segs.push_back({{"segment", i + 1 <= s_.motion.count ? i + 1 : 0},
                      {"t_start_s", r.t_start},
                      {"t_end_s", ended ? r.t_end : static_cast<double>(ticks_) * s_.loop.tick_s()},
                      {"latitude_end_deg", (ended ? r.latitude_end : lat) / kDeg},
                      {"heading_end_deg", (ended ? r.heading_end : current_motion_.heading) / kDeg},
                      {"v_north_end_m_s", ended ? r.v_north_end : current_motion_.v_north},
                      {"v_east_end_m_s", ended ? r.v_east_end : current_motion_.v_east},
                      {"alpha_end_rad", ended ? r.alpha_end : x_[0]},
                      {"alpha_eq_book_end_rad", ended ? r.alpha_eq_end : book_alpha_eq(current_)},
                      {"speed_deviation_book_13_23_rad", ended ? r.speed_dev_end : speed_dev(current_motion_)},
                      {"deviation_from_equilibrium_max_rad", r.deviation_max},
                      {"alpha_mean_minus_eq_rad", (r.alpha_sum - r.alpha_eq_sum) / static_cast<double>(r.samples)}});
    }
    f["segments"] = segs;
    if (s_.gyro.swing_inertia > 0.0) {
      // (13.38) with ψ of the final state.
      const models::ShipRoll& roll = s_.gyro.roll;
      const double wg2 = s_.gyro.c / s_.gyro.swing_inertia, ws2 = roll.omega() * roll.omega(), b0 = roll.b0();
      const double gs = s_.gyro.c, psi = current_motion_.heading, gg = s_.gyro.gravity;
      const double num = -gs * b0 * b0 * wg2 * std::sin(2.0 * psi);
      const double den = 4.0 * gg * gg * H * we * std::cos(lat) * (wg2 - ws2) + 2.0 * gs * b0 * b0 * wg2 * std::cos(2.0 * psi);
      f["rolling_error_book_13_38_rad"] = num / den;
      f["swing_frequency_rad_s"] = std::sqrt(wg2);
      f["roll_acceleration_amplitude_m_s2"] = b0;
    }
    return f;
  }

 private:
  void sample(std::int64_t t_ns, models::FrameSample& frame, motion::EarthVehicleSample& m) const {
    m = vehicle_.sample_ns(t_ns);
    frame_of(m, frame);
  }
  void frame_of(const motion::EarthVehicleSample& m, models::FrameSample& frame) const {
    motion::Trihedron G = m.geographic;
    remove_centrifugal_tilt(m, s_.motion.earth.rotation_rate, G);
    frame = frame_up_east_north(G);
  }
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
  int segment_at(std::int64_t t_ns) const {
    int k = 0;
    while (k < s_.motion.count && t_ns >= segment_start_ns(s_.motion, k + 1)) ++k;
    return k;
  }
  void begin_segment(int i, double t) {
    CompassSegment& r = segments_[static_cast<std::size_t>(i)];
    r.started = true;
    r.t_start = t;
  }
  void end_segment(int i, double t) {
    CompassSegment& r = segments_[static_cast<std::size_t>(i)];
    r.ended = true;
    r.t_end = t;
    r.alpha_end = x_[0];
    r.alpha_eq_end = book_alpha_eq(current_);
    r.speed_dev_end = speed_dev(current_motion_);
    r.latitude_end = current_motion_.latitude;
    r.heading_end = current_motion_.heading;
    r.v_north_end = current_motion_.v_north;
    r.v_east_end = current_motion_.v_east;
  }

  const GcScene& s_;
  Model plant_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  Model::State x_;
  VehicleGenerator vehicle_;
  CornerClock corners_;
  models::FrameSample current_{};
  motion::EarthVehicleSample current_motion_{};
  sensors::SensorNoise level_noise_;
  random::SeededRng rng_level_;
  std::unique_ptr<Controller> controller_;
  msg::ActuatorFrame last_{};
  analysis::ExtremaMeter<64> alpha_extrema_, beta_extrema_;
  std::array<CompassSegment, kMaxVehicleSegments + 1> segments_{};
  int segment_{0};
  std::int64_t ticks_{0};
};

bool read_scene(SceneReader& r, GcScene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  s.motion = read_vehicle_motion(r, 50.0);
  auto& g = s.gyro;
  g.fidelity = r.choice("gyro", "fidelity", "full", {"full", "precession"}, "full (13.7) or precession (13.10) form") ==
                       "precession"
                   ? models::InstrumentFidelity::kPrecession
                   : models::InstrumentFidelity::kFull;
  g.gyro.H = r.required("gyro", "H", Range::positive(), "spin momentum [N m s]");
  g.gyro.A = r.number("gyro", "A", 0.05, Range::positive(), "inertia about the vertical axis 1 [kg m²]");
  g.gyro.B = r.number("gyro", "B", 0.05, Range::positive(), "inertia about the east axis 2 [kg m²]");
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
      const double A = g.gyro.A, B = g.gyro.B, H = g.gyro.H, wh = we * std::cos(s.motion.start.latitude);
      Eigen::Matrix4d J;
      J << 0, 0, 1, 0,  //
          0, 0, 0, 1,   //
          -H * wh / A, -l.f / A, -g.d1 / A, -H / A,  //
          0.0, -(H * wh + g.c + l.c_e) / B, H / B, -g.d2 / B;
      const Eigen::EigenSolver<Eigen::Matrix4d> es(J, false);
      double growth = -1e300;
      for (int i = 0; i < 4; ++i) growth = std::max(growth, es.eigenvalues()[i].real());
      if (growth > 0.0) {
        char msg[256];
        std::snprintf(msg, sizeof msg,
                      "the damping torque makes the nutation grow at %.3g /s (a circulatory force, model "
                      "header): give the sphere viscous damping d1, d2 (d/A well above f/H = %.3g /s)",
                      growth, l.f / H);
        r.fail("gyro", "d1", msg);
      }
    }
    const double h_sub = s.loop.tick_s() / s.loop.substeps;
    Model m(g);
    m.inputs.frame.hold({dynamics::Vec3(we * std::sin(design_lat), 0.0, we * std::cos(design_lat)),
                         dynamics::Vec3::Zero(), dynamics::Vec3(s.motion.earth.gravity, 0.0, 0.0)});
    const dynamics::StepCheck step =
        dynamics::check_step(dynamics::Method::kRk4, dynamics::fastest_mode(m, 0.0, Model::make_state(0, 0)), h_sub);
    if (!step.ok) r.fail("loop", "plant_substeps", step.message);
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_gyrocompass(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<GcScene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  auto device = std::make_unique<GyrocompassDevice>(*scene);
  return run_device(*device, scene->loop, req);
}

}  // namespace gyrostab::tools
