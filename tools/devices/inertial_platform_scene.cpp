// Scene binding of the Schuler-tuned inertial platform (Magnus ch. 16, (16.1)-(16.50)): the single-axis
// platform of Fig. 16.9 on the book's great circle over a non-rotating Earth, or a three-axis local-level
// platform in the azimuth-free trihedron of a vehicle over the rotating Earth (sim/models/inertial_platform.hpp;
// motion sim/motion/earth_vehicle.hpp), each axis held by its rate-integrating gyro and analog servo, the
// horizontal channels commanded by the firmware Schuler loops (firmware/app/inertial_platform_controller.hpp).
// Sensors: integrating (Δv) accelerometers as the apparent tilt θ = specific force / g0 averaged over the
// previous tick (trapezoid between the tick's ends; seeded noise), the gyro pick-offs.
// Figures (measured beside the book's):
//   per channel — the period of the tilt e from its extrema against the loop's 2π/ω, ω² = (g/R_loop)(H_loop/H)
//   ((16.38)/(16.44): 84.4 min when tuned); max |e| against the tuned bound sqrt(e0² + (Δω0/ω_S)²) of
//   (16.46)/(16.49) (any vehicle motion); the velocity error of the loop v_err = R_loop ω_cmd − R Ω (ω_cmd
//   read from the torquer command, M = −H_loop ω_cmd) and the position error ∫v_err dt, with the book's
//   amplitudes e0 sqrt(gR) and 2 R e0 (16.47) (book: 2.2 km for 0.01°); the servo offset β0 = M^S/k (16.2).
// Keys: docs/scenes.md#inertial_platform.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "firmware/app/inertial_platform_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/inertial_platform.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/devices/scene_device.hpp"
#include "tools/devices/scene_run.hpp"
#include "tools/devices/vehicle_frame_feed.hpp"
#include "tools/devices/vehicle_motion_scene.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/run/run_device.hpp"

namespace gyrostab::tools {
namespace {

using Controller = firmware::BasicInertialPlatformController<firmware::posix::MonotonicClock>;
constexpr double kPi = std::numbers::pi;

enum Stream : std::uint64_t { kAccel1Stream = 1, kAccel2Stream };

struct PlatformScene {
  LoopConfig loop;
  VehicleMotionConfig motion;
  int axes{3};
  models::PlatformAxisParams axis[3]{};
  double gravity_gradient{0.0};
  double tilt0[3]{0.0, 0.0, 0.0};            // initial tilt e(0) [rad]
  double velocity_error0[2]{0.0, 0.0};       // loop's initial velocity error per channel [m/s]
  double accel_noise_density{0.0};           // [m/s²/√Hz]
  firmware::InertialPlatformConfig controller;
  int extrema_every_ticks{1000};
  double extrema_hysteresis{1e-6};  // [rad]
};

struct ChannelStats {
  analysis::ExtremaMeter<64> extrema{};
  double tilt_max{0.0};
  double velocity_error_max{0.0};
  double position_error{0.0}, position_error_max{0.0};
};

// The two plant variants behind one interface: channel tilts, apparent tilts, gyro outputs.
template <class Model>
struct PlatformPlant;

template <>
struct PlatformPlant<models::SingleAxisPlatform> {
  static constexpr int kChannels = 1;
  static models::FrameSample frame(const motion::EarthVehicleSample& m) { return frame_as_is(m.track); }
  static void set_torquers(models::SingleAxisPlatform& p, const msg::ActuatorFrame& cmd) {
    p.inputs.torquer = cmd.gimbal_torque_Nm[msg::kAxis1];
  }
  static double tilt(const models::SingleAxisPlatform::State& x, int) { return x[0]; }
  static double frame_rate(const models::FrameSample& w, int) { return w.Omega.y(); }
  static void apparent(const models::SingleAxisPlatform& p, double t, const models::SingleAxisPlatform::State& x,
                       double (&theta)[2]) {
    theta[0] = p.apparent_tilt(t, x);
    theta[1] = 0.0;
  }
  static double gyro_angle(const models::SingleAxisPlatform::State& x, int) { return x[2]; }
  static double gyro_rate(const models::SingleAxisPlatform::State& x, int) { return x[3]; }
  static models::SingleAxisPlatform::State initial(const PlatformScene& s, const models::FrameSample& w) {
    models::SingleAxisPlatform::State x;
    x << s.tilt0[0], w.Omega.y(), s.axis[0].disturbance / s.axis[0].k, 0.0;
    return x;
  }
  static models::SingleAxisPlatform make(const PlatformScene& s) {
    return models::SingleAxisPlatform({s.axis[0], s.gravity_gradient});
  }
};

template <>
struct PlatformPlant<models::ThreeAxisPlatform> {
  static constexpr int kChannels = 2;
  static models::FrameSample frame(const motion::EarthVehicleSample& m) { return frame_as_is(m.azimuth_free); }
  static void set_torquers(models::ThreeAxisPlatform& p, const msg::ActuatorFrame& cmd) {
    p.inputs.torquer[0] = cmd.gimbal_torque_Nm[msg::kAxis1];
    p.inputs.torquer[1] = cmd.gimbal_torque_Nm[msg::kAxis2];
    p.inputs.torquer[2] = 0.0;  // azimuth: the frame has no vertical rate
  }
  static double tilt(const models::ThreeAxisPlatform::State& x, int i) { return x[i]; }
  static double frame_rate(const models::FrameSample& w, int i) { return w.Omega[i]; }
  static void apparent(const models::ThreeAxisPlatform& p, double t, const models::ThreeAxisPlatform::State& x,
                       double (&theta)[2]) {
    p.apparent_tilts(t, x, theta[0], theta[1]);
  }
  static double gyro_angle(const models::ThreeAxisPlatform::State& x, int i) { return x[6 + i]; }
  static double gyro_rate(const models::ThreeAxisPlatform::State& x, int i) { return x[9 + i]; }
  static models::ThreeAxisPlatform::State initial(const PlatformScene& s, const models::FrameSample& w) {
    models::ThreeAxisPlatform::State x = models::ThreeAxisPlatform::State::Zero();
    const dynamics::Vec3 e(s.tilt0[0], s.tilt0[1], s.tilt0[2]);
    x.segment<3>(0) = e;
    x.segment<3>(3) = w.Omega + w.Omega.cross(e);
    for (int i = 0; i < 3; ++i) x[6 + i] = s.axis[i].disturbance / s.axis[i].k;
    return x;
  }
  static models::ThreeAxisPlatform make(const PlatformScene& s) {
    models::ThreeAxisPlatformParams p;
    for (int i = 0; i < 3; ++i) p.axis[i] = s.axis[i];
    return models::ThreeAxisPlatform(p);
  }
};

template <class Model>
class PlatformDevice {
  using Plant = PlatformPlant<Model>;
  static constexpr int kChannels = Plant::kChannels;

 public:
  explicit PlatformDevice(const PlatformScene& s)
      : s_(s),
        plant_(Plant::make(s)),
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        feed_(s.motion, s.loop.tick_ns, &Plant::frame),
        noise_{sensors::SensorNoise({s.accel_noise_density, 0.0, 0.0}, s.loop.tick_s()),
               sensors::SensorNoise({s.accel_noise_density, 0.0, 0.0}, s.loop.tick_s())},
        rng_{random::SeededRng(s.loop.seed, kAccel1Stream), random::SeededRng(s.loop.seed, kAccel2Stream)},
        controller_(std::make_unique<Controller>(s.controller)) {
    plant_.inputs.frame.hold(feed_.frame());
    x_ = Plant::initial(s, feed_.frame());
    for (ChannelStats& c : stats_) c.extrema = analysis::ExtremaMeter<64>(s.extrema_hysteresis);
    Plant::apparent(plant_, 0.0, x_, theta_start_);
    theta_mean_[0] = theta_start_[0];
    theta_mean_[1] = theta_start_[1];
    remember_rates(0);
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    // Integrating (Δv) accelerometers: the mean apparent tilt over the previous tick (at tick 0 the
    // instantaneous value).
    f.carrier_angle_rad[msg::kRoll] = theta_mean_[0] + noise_[0].sample(rng_[0]) / models::kStandardGravity;
    if (kChannels > 1)
      f.carrier_angle_rad[msg::kPitch] = theta_mean_[1] + noise_[1].sample(rng_[1]) / models::kStandardGravity;
    for (int i = 0; i < kChannels; ++i) {
      f.gimbal_angle_rad[i] = Plant::gyro_angle(x_, i);
      f.gimbal_rate_rad_s[i] = Plant::gyro_rate(x_, i);
    }
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    Plant::set_torquers(plant_, cmd);
  }

  void advance(std::int64_t tick) {
    feed_.begin_tick(tick, plant_.inputs.frame);
    window_.before_tick(tick, x_, plant_.inputs);
    driver_.advance_tick(tick, x_);
    window_.after_tick(tick, x_);
    // The tick's mean apparent tilt by the trapezoid between its start (right limit) and its end (left
    // limit): exact for the frame's linear motion within the tick, O(T²) in the platform's own.
    double theta_end[2];
    Plant::apparent(plant_, plant_.inputs.frame.t0 + plant_.inputs.frame.h, x_, theta_end);
    for (int i = 0; i < 2; ++i) theta_mean_[i] = 0.5 * (theta_start_[i] + theta_end[i]);
    if (feed_.end_tick(plant_.inputs.frame)) {  // a corner: the next tick starts from the right limit
      Plant::apparent(plant_, plant_.inputs.frame.t0, x_, theta_start_);
    } else {
      theta_start_[0] = theta_end[0];
      theta_start_[1] = theta_end[1];
    }
    remember_rates(tick + 1);
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    const double R = s_.motion.earth.radius, RL = s_.controller.law.radius, HL = s_.controller.law.H;
    for (int i = 0; i < kChannels; ++i) {
      ChannelStats& c = stats_[static_cast<std::size_t>(i)];
      const double e = Plant::tilt(x_, i);
      c.tilt_max = std::max(c.tilt_max, std::fabs(e));
      if (ticks_ % s_.extrema_every_ticks == 0) c.extrema.add(t1, e);
      // The loop's velocity estimate from its torquer command; the channel's true v = ±R Ω at the time
      // the command estimates (the end of the control step it came from, latency_ticks earlier).
      const double w_cmd = -last_.gimbal_torque_Nm[i] / HL;
      const double v_err = RL * w_cmd - R * rate_history(tick + 1 - s_.loop.latency_ticks, i);
      c.velocity_error_max = std::max(c.velocity_error_max, std::fabs(v_err));
      c.position_error += v_err * s_.loop.tick_s();
      c.position_error_max = std::max(c.position_error_max, std::fabs(c.position_error));
    }
  }

  bool finite() const { return x_.allFinite(); }

  // report.json "error_estimate": the half-step comparison (the frame's motion is interpolated within the tick
  // exactly as in the run, so the re-integration at half the step sees the same forcing).
  nlohmann::json error_estimate() const {
    const auto apply = [](auto& p, const auto& in) { p.inputs = in; };
    return window_.template estimate<dynamics::Rk4>(plant_, apply, s_.loop.tick_ns, s_.loop.substeps, 4, state_names(),
                                                    "none watched: vehicle motion, servo and Schuler-loop torques act");
  }
  static std::array<const char*, Model::kStateSize> state_names() {
    if constexpr (Model::kStateSize == 4) {
      return {"tilt_rad", "platform_rate_rad_s", "gyro_angle_rad", "gyro_rate_rad_s"};
    } else {
      return {"tilt1_rad",       "tilt2_rad",       "tilt3_rad",       "platform_rate1_rad_s",
              "platform_rate2_rad_s", "platform_rate3_rad_s", "gyro_angle1_rad", "gyro_angle2_rad",
              "gyro_angle3_rad", "gyro_rate1_rad_s", "gyro_rate2_rad_s", "gyro_rate3_rad_s"};
    }
  }

  static std::vector<std::string> columns() {
    return {"tilt1_rad", "tilt2_rad", "theta1_rad", "theta2_rad", "torquer1_Nm", "torquer2_Nm", "gyro1_rad",
            "velocity_error1_m_s", "status_bits"};
  }
  void record(double* row) const {
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    double theta[2];
    Plant::apparent(plant_, t, x_, theta);
    row[0] = Plant::tilt(x_, 0);
    row[1] = kChannels > 1 ? Plant::tilt(x_, 1) : 0.0;
    row[2] = theta[0];
    row[3] = theta[1];
    row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
    row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[6] = Plant::gyro_angle(x_, 0);
    row[7] = s_.controller.law.radius * (-last_.gimbal_torque_Nm[0] / s_.controller.law.H) -
             s_.motion.earth.radius * rate_history(ticks_ - s_.loop.latency_ticks, 0);
    row[8] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const {
    msg::ActuatorFrame a{};  // the loop's initial torque: the level frame's rate at t = 0 (no start transient)
    for (int i = 0; i < kChannels; ++i) a.gimbal_torque_Nm[i] = -s_.controller.law.H * s_.controller.law.initial_rate[i];
    return a;
  }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const double g = s_.motion.earth.gravity, R = s_.motion.earth.radius;
    const double RL = s_.controller.law.radius, HL = s_.controller.law.H, wS = std::sqrt(g / R);
    nlohmann::json f{{"ticks", ticks_},
                     {"axes", s_.axes},
                     {"schuler_period_s", 2.0 * kPi / wS}};
    nlohmann::json ch = nlohmann::json::array();
    for (int i = 0; i < kChannels; ++i) {
      const ChannelStats& c = stats_[static_cast<std::size_t>(i)];
      const models::PlatformAxisParams& a = s_.axis[i];
      const double w_loop = std::sqrt(g / RL * HL / a.H);
      const double dw0 = s_.velocity_error0[i] / RL;
      const double e0 = s_.tilt0[i];
      nlohmann::json j{{"channel", i + 1},
                       {"period_loop_book_s", 2.0 * kPi / w_loop},
                       {"tilt_max_rad", c.tilt_max},
                       {"tilt_bound_tuned_rad", std::hypot(e0, dw0 / wS)},
                       {"tilt_end_rad", Plant::tilt(x_, i)},
                       {"velocity_error_max_m_s", c.velocity_error_max},
                       {"velocity_error_amplitude_book_16_47_m_s", std::fabs(e0) * std::sqrt(g * R)},
                       {"position_error_max_m", c.position_error_max},
                       {"position_error_max_book_16_47_m", 2.0 * R * std::fabs(e0)},
                       {"servo_offset_book_16_2_rad", a.disturbance / a.k},
                       {"gyro_angle_end_rad", Plant::gyro_angle(x_, i)},
                       {"servo_gain_limit_16_5", a.k_max()},
                       {"drift_position_rate_book_16_50_m_s", -a.drift * R},
                       {"extrema", c.extrema.count()}};
      j["period_measured_s"] = c.extrema.count() >= 2 ? nlohmann::json(c.extrema.period()) : nlohmann::json(nullptr);
      ch.push_back(j);
    }
    f["channels"] = ch;
    return f;
  }

 private:
  static constexpr std::int64_t kHistory = kMaxLatencyTicks + 2;
  // The level frame's rate about channel i at the start of tick k (k ≥ 0, within the last kHistory ticks).
  void remember_rates(std::int64_t k) {
    for (int i = 0; i < kChannels; ++i)
      rate_hist_[static_cast<std::size_t>(k % kHistory)][static_cast<std::size_t>(i)] =
          Plant::frame_rate(feed_.frame(), i);
  }
  double rate_history(std::int64_t k, int i) const {
    k = k < 0 ? 0 : k;
    return rate_hist_[static_cast<std::size_t>(k % kHistory)][static_cast<std::size_t>(i)];
  }

  const PlatformScene& s_;
  Model plant_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  typename Model::State x_;
  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): 1000 ticks from the run's middle.
  accuracy::HalfStepWindow<Model, typename Model::Inputs> window_{s_.loop.ticks() / 2, 1000};
  VehicleFrameFeed<models::FrameSample (*)(const motion::EarthVehicleSample&)> feed_;
  std::array<sensors::SensorNoise, 2> noise_;
  std::array<random::SeededRng, 2> rng_;
  std::unique_ptr<Controller> controller_;
  msg::ActuatorFrame last_{};
  std::array<ChannelStats, 2> stats_{};
  std::array<std::array<double, 2>, static_cast<std::size_t>(kHistory)> rate_hist_{};
  double theta_start_[2]{0.0, 0.0};  // apparent tilt at the current tick's start (right limit) [rad]
  double theta_mean_[2]{0.0, 0.0};   // mean over the last completed tick (what the accelerometers report) [rad]
  std::int64_t ticks_{0};
};

void read_axis(SceneReader& r, const std::string& sec, models::PlatformAxisParams& a) {
  a.J = r.number(sec, "J", a.J, Range::positive(), "platform + gimbal inertia about the axis [kg m²]");
  a.k = r.number(sec, "k", a.k, Range::positive(), "stabilization servo gain M = -k beta [N m/rad]");
  a.H = r.number(sec, "H", a.H, Range::positive(), "gyro spin momentum [N m s]");
  a.B = r.number(sec, "B", a.B, Range::positive(), "gyro output-axis inertia [kg m²]");
  a.d = r.number(sec, "d", a.d, Range::positive(), "gyro output-axis damping [N m s/rad]");
  a.c = r.number(sec, "c", a.c, Range::non_negative(), "gyro output-axis spring [N m/rad]");
  a.disturbance = r.number(sec, "disturbance_Nm", 0.0, Range::closed(-10.0, 10.0), "constant torque M^S [N m]");
  a.drift = r.number(sec, "drift_deg_h", 0.0, Range::closed(-100.0, 100.0), "gyro drift [deg/h]") * kDeg / 3600.0;
  a.accel_bias =
      r.number(sec, "accel_bias_m_s2", 0.0, Range::closed(-1.0, 1.0), "bias of the accelerometer across the axis [m/s²]");
  if (const char* why = a.invalid_reason()) r.fail(sec, "k", why);
}

bool read_scene(SceneReader& r, PlatformScene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  s.axes = static_cast<int>(r.integer("platform", "axes", 3, 1, 3, "1: single-axis (Fig. 16.9), 3: three-axis"));
  if (s.axes == 2) r.fail("platform", "axes", "must be 1 or 3");
  s.motion = read_vehicle_motion(r, 45.0, s.axes == 1 ? 0.0 : 7.292115e-5);
  if (s.axes == 1 && r.ok()) {
    if (s.motion.earth.rotation_rate != 0.0)
      r.fail("earth", "rotation_rate_rad_s", "the single-axis platform is the book's non-rotating case: must be 0");
    for (int k = 0; k < s.motion.count; ++k)
      if (s.motion.segments[static_cast<std::size_t>(k)].turn_rate != 0.0)
        r.fail("segment" + std::to_string(k + 1), "turn_rate_deg_s",
               "the single-axis platform follows a great circle (16.4.1): turn rates must be 0");
  }
  const char* names[3] = {"axis1", "axis2", "axis3"};
  for (int i = 0; i < (s.axes == 1 ? 1 : 3); ++i) {
    read_axis(r, names[i], s.axis[i]);
    s.tilt0[i] = kDeg * r.number(names[i], "tilt0_deg", 0.0, Range::closed(-5.0, 5.0), "initial tilt e(0) [deg]");
  }
  if (s.axes == 1) {
    s.gravity_gradient = r.number("axis1", "gravity_gradient_Nm_rad", 0.0, Range::any(),
                                  "(3g/R)(B_p - C_p) of (16.30) [N m/rad]");
  }
  s.accel_noise_density =
      r.number("sensors", "accel_noise_density", 0.0, Range::non_negative(), "accelerometer noise [m/s²/sqrt(Hz)]");

  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  auto& l = c.law;
  l.radius = r.number("controller", "radius_m", s.motion.earth.radius, Range::positive(),
                      "R the Schuler loop is tuned to [m]");
  l.H = r.number("controller", "H", s.axis[0].H, Range::positive(), "gyro momentum the torquer scale assumes [N m s]");
  l.torque_limit_Nm = r.number("controller", "torque_limit_Nm", 1.0, Range::positive(), "torquer limit [N m]");
  const int channels = s.axes == 1 ? 1 : 2;
  l.enabled[1] = channels > 1;
  for (int i = 0; i < channels; ++i) {
    const std::string key = "velocity_error" + std::to_string(i + 1) + "_m_s";
    s.velocity_error0[i] = r.number("controller", key, 0.0, Range::closed(-1e3, 1e3),
                                    "initial velocity error of the channel's integrator [m/s]");
  }
  const double every_s = r.number("report", "extrema_sample_s", 10.0, Range::positive(), "tilt sampling for the extrema [s]");
  s.extrema_every_ticks = std::max<int>(1, static_cast<int>(std::llround(every_s / s.loop.tick_s())));
  s.extrema_hysteresis = r.number("report", "extrema_hysteresis_rad", 1e-6, Range::non_negative(),
                                  "an extremum counts once the tilt has moved back this much [rad]");

  if (r.ok()) {
    if (const char* why = corners_on_ticks(s.motion, s.loop.tick_ns)) r.fail("segment1", "duration_s", why);
    // The loop starts on the level frame's rate at t = 0 (an ideal alignment), plus the scene's error.
    const VehicleGenerator v = make_vehicle(s.motion);
    const motion::EarthVehicleSample m0 = v.sample_ns(0);
    if (s.axes == 1) {
      l.initial_rate[0] = m0.track.w_IZ_Z.y() + s.velocity_error0[0] / l.radius;
    } else {
      for (int i = 0; i < 2; ++i) l.initial_rate[i] = m0.azimuth_free.w_IZ_Z[i] + s.velocity_error0[i] / l.radius;
    }
    const firmware::ConfigCheck check = Controller::check(c);
    if (!check.ok) r.fail("controller", "radius_m", "refused by the controller's start-up check: " + describe(check));
    const double h_sub = s.loop.tick_s() / s.loop.substeps;
    dynamics::StepCheck step;
    if (s.axes == 1) {
      models::SingleAxisPlatform m({s.axis[0], s.gravity_gradient});
      step = dynamics::check_step(dynamics::Method::kRk4,
                                  dynamics::fastest_mode(m, 0.0, models::SingleAxisPlatform::State::Zero(), "servo"), h_sub);
    } else {
      models::ThreeAxisPlatformParams p;
      for (int i = 0; i < 3; ++i) p.axis[i] = s.axis[i];
      models::ThreeAxisPlatform m(p);
      step = dynamics::check_step(dynamics::Method::kRk4,
                                  dynamics::fastest_mode(m, 0.0, models::ThreeAxisPlatform::State::Zero(), "servo"), h_sub);
    }
    if (!step.ok) r.fail("loop", "plant_substeps", step.message);
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_inertial_platform(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<PlatformScene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  return scene->axes == 1 ? run_on_scene<PlatformDevice<models::SingleAxisPlatform>>(*scene, req)
                          : run_on_scene<PlatformDevice<models::ThreeAxisPlatform>>(*scene, req);
}

}  // namespace gyrostab::tools
