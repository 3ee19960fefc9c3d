// Scene binding of the gyro-stabilized monorail car (Magnus §14.1, (14.1)-(14.7)): the car with its
// top-heavy gyro case (sim/models/monorail.hpp, the plant's analog motor law k = 0), driven along a track
// that runs straight and then through a curve (curve running (14.6): the path turns at Ω3(t), with the
// centrifugal roll moment of the speed), hit by a side-wind gust, sensed with seeded noise, and held upright
// by the firmware motor law M2 = k φ − d β' (firmware/app/monorail_controller.hpp, gain window of (14.5)
// checked at start-up) at the controller's rate.
// Before running, the scene is refused if the loop of (14.6) with the firmware law is not Hurwitz at the
// curve's peak Ω3 (e.g. (14.7) c > HΩ3 > q: the car overturns in the curve), unless
// [track] allow_unstable_curve = true; and the plant step is checked against the car's fastest mode.
// Figures: tilt statistics after settling, case-angle peak, the gain window (k_lo, k_hi) on the straight and
// in the curve with the configured k, decay rates of (14.3)/(14.6), and the steady leans into the gust and
// into the curve, measured and predicted. Keys: docs/scenes.md#monorail.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>

#include "firmware/app/monorail_controller.hpp"
#include "firmware/control/hurwitz.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/monorail.hpp"
#include "sim/motion/wave_transfer.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/devices/running_stats.hpp"
#include "tools/devices/scene_device.hpp"
#include "hil/link/actuator_frame_check.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/run_device.hpp"
#include "tools/run/controller_report.hpp"

namespace gyrostab::tools {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kNever = std::numeric_limits<double>::infinity();
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicMonorailController<firmware::posix::MonotonicClock>;

// Random streams of the scene seed, one per consumer (seeded_rng.hpp): adding a consumer never shifts
// another.
enum Stream : std::uint64_t { kTiltStream = 1, kTiltRateStream, kCaseRateStream };

// Fraction in [0, 1] of a linear ramp that starts at t0 and lasts `ramp` seconds (a step when ramp = 0).
double ramp_fraction(double t, double t0, double ramp) {
  if (t < t0) return 0.0;
  return ramp > 0.0 ? std::min(1.0, (t - t0) / ramp) : 1.0;
}

// The path's turning rate Ω3(t) [rad/s]: straight until start_s, a transition of transition_s seconds in
// which Ω3 grows linearly (a clothoid at constant speed), the curve at Omega3, and from end_s the same
// transition back to straight.
struct CurveProfile {
  double Omega3{0.0};        // [rad/s], + in the rotor's spin sense
  double start_s{kNever};    // [s]
  double end_s{kNever};      // [s]
  double transition_s{0.0};  // [s]

  double operator()(double t) const {
    return Omega3 *
           std::min(ramp_fraction(t, start_s, transition_s), 1.0 - ramp_fraction(t, end_s, transition_s));
  }
};

// A side-wind gust: a roll moment on the car that rises linearly over rise_s from start_s, holds, and falls
// over rise_s from start_s + duration_s [N m].
struct Gust {
  double M1{0.0};          // [N m], + tilts the car to + φ
  double start_s{kNever};  // [s]
  double duration_s{0.0};  // [s]
  double rise_s{0.0};      // [s]

  double operator()(double t) const {
    return M1 *
           std::min(ramp_fraction(t, start_s, rise_s), 1.0 - ramp_fraction(t, start_s + duration_s, rise_s));
  }
};

struct Track {
  CurveProfile curve;
  Gust gust;
  double speed_m_s{0.0};  // v: the lateral acceleration in the curve is v Ω3 [m/s]
  bool allow_unstable_curve{false};
};

struct SensorConfig {
  double tilt_noise_rad{1e-4};           // car tilt (AHRS) white noise, standard deviation per sample [rad]
  double tilt_bias_rad{0.0};             // [rad]
  double tilt_rate_noise_density{1e-4};  // car roll-rate gyro [rad/s/√Hz]
  double case_rate_noise_density{1e-4};  // case rate gyro (the law's damper input) [rad/s/√Hz]
  double case_rate_bias{0.0};            // [rad/s]
  std::int64_t encoder_counts_per_rev{65536};
};

struct MonorailScene {
  LoopConfig loop;
  models::MonorailParams car;    // k = 0: the firmware is the motor law
  double brake_full_Nms{1e4};    // brake on axis 2 at precession_brake = 1 (safe state) [N m s/rad]
  double phi0{0.0}, beta0{0.0};  // initial car tilt and case angle [rad]
  Track track;
  SensorConfig sensors;
  firmware::MonorailConfig controller;
  double settle_s{10.0};
};

// The car on the track: the model with the path's Ω3(t), the gust and the centrifugal moments evaluated at
// every integrator stage, the brake on axis 2 as a viscous torque, and the ground (project()).
// Centrifugal terms, which the model neglects (the tilt of the apparent vertical by the lateral acceleration
// a = v Ω3): in the path frame car and case feel the uniform field m (0, −a, −g), i.e. the potential of
// sim/models/monorail.hpp plus (a/g)(−(c − q) sinφ − q sinφ cosβ), which adds
//   M1 += (a/g)(c cosφ − q cosφ (1 − cosβ)),     M2 += −(a/g) q sinφ sinβ
// (the large-angle counterpart of the gravity terms; to first order the moment c a/g on the car).
struct CarOnTrack {
  [[maybe_unused]] static constexpr int kStateSize = 4;  // the Rk4 model concept
  using State = models::Monorail::State;
  mutable models::Monorail car;
  const Track* track;
  double brake_Nms{0.0};
  double command_Nm{0.0};

  // The lateral acceleration of the path in units of g, a/g = v Ω3(t)/g [-].
  double lateral_g(double t) const { return track->speed_m_s * track->curve(t) / motion::kStandardGravity; }

  void derivative(double t, const State& x, State& dx) const {
    const models::MonorailParams& p = car.params();
    const double a_g = lateral_g(t);
    double M1 = track->gust(t), M2 = command_Nm - brake_Nms * x[3];
    if (a_g != 0.0) {
      const double cp = std::cos(x[0]), sp = std::sin(x[0]), cb = std::cos(x[1]), sb = std::sin(x[1]);
      M1 += a_g * (p.c * cp - p.q * cp * (1.0 - cb));
      M2 -= a_g * p.q * sp * sb;
    }
    car.inputs.Omega3 = track->curve(t);
    car.inputs.M1 = M1;
    car.inputs.M2 = M2;
    car.derivative(t, x, dx);
  }
  // The ground: a car that has overturned (|φ| reaches π/2, where the model stops applying) lies on its side
  // (inelastic contact: φ held at ±π/2, no tilt rate away from upright); the case moves on.
  void project(State& x) const {
    constexpr double kLying = 0.5 * std::numbers::pi;
    if (std::fabs(x[0]) >= kLying) {
      x[0] = std::copysign(kLying, x[0]);
      if (x[2] * x[0] > 0.0) x[2] = 0.0;
    }
  }
};

// Largest real part of the roots of (14.3) with c → c − HΩ3, q → q − HΩ3 (14.6), d the total damper [1/s].
double max_real_root(const models::MonorailParams& p, double k, double d, double Omega3) {
  const double c = p.c - p.H * Omega3, q = p.q - p.H * Omega3;
  const double a[5] = {p.A * p.B, p.A * d, p.H * p.H - q * p.A - c * p.B, k * p.H - c * d, c * q};
  Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 4; ++i) companion(0, i) = -a[i + 1] / a[0];
  for (int i = 1; i < 4; ++i) companion(i, i - 1) = 1.0;
  return Eigen::EigenSolver<Eigen::Matrix4d>(companion, false).eigenvalues().real().maxCoeff();
}

// The firmware law's view of the plant in a curve: (14.6) is (14.2) with c − HΩ3, q − HΩ3.
firmware::MonorailMotorParams law_in_curve(firmware::MonorailMotorParams l, double Omega3) {
  l.c -= l.H * Omega3;
  l.q -= l.H * Omega3;
  return l;
}

// Mean of a signal over the ticks [from, to) (allocation-free).
struct WindowMean {
  std::int64_t from{0}, to{0};
  double sum{0.0};
  std::int64_t n{0};
  void add(std::int64_t tick, double v) {
    if (tick >= from && tick < to) {
      sum += v;
      ++n;
    }
  }
  nlohmann::json json() const {
    return n > 0 ? nlohmann::json(sum / static_cast<double>(n)) : nlohmann::json();
  }
};

// A measurement window of the steady lean: the last second of a constant load (the gust's plateau, the
// curve's constant part), clipped to the scene's duration; empty if there is no such plateau.
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

class MonorailDevice {
 public:
  explicit MonorailDevice(const MonorailScene& s)
      : s_(s),
        plant_{models::Monorail(s.car), &s.track, 0.0, 0.0},
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        encoder_({s.sensors.encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kIncremental,
                  sensors::EncoderParams::Rounding::kNearest}),
        tilt_noise_({s.sensors.tilt_noise_rad * std::sqrt(s.loop.tick_s()), s.sensors.tilt_bias_rad, 0.0},
                    s.loop.tick_s()),
        tilt_rate_noise_({s.sensors.tilt_rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
        case_rate_noise_({s.sensors.case_rate_noise_density, s.sensors.case_rate_bias, 0.0}, s.loop.tick_s()),
        rng_tilt_(s.loop.seed, kTiltStream),
        rng_tilt_rate_(s.loop.seed, kTiltRateStream),
        rng_case_rate_(s.loop.seed, kCaseRateStream),
        controller_(std::make_unique<Controller>(s.controller)),
        settle_tick_(tick_at(s.settle_s)) {
    x_ = models::Monorail::make_state(s.phi0, s.beta0, 0.0, 0.0);
    const Gust& g = s.track.gust;
    const CurveProfile& c = s.track.curve;
    gust_window_ = g.M1 != 0.0
                       ? plateau_window(g.start_s + g.rise_s, g.start_s + g.duration_s, s.loop.duration_s)
                       : LeanWindow{};
    curve_window_ = c.Omega3 != 0.0 ? plateau_window(c.start_s + c.transition_s, c.end_s, s.loop.duration_s)
                                    : LeanWindow{};
    set_window(gust_window_, gust_tilt_, gust_case_);
    set_window(curve_window_, curve_tilt_, curve_case_);
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    f.carrier_angle_rad[msg::kRoll] = x_[0] + tilt_noise_.sample(rng_tilt_);
    f.carrier_rate_rad_s[msg::kRoll] = x_[2] + tilt_rate_noise_.sample(rng_tilt_rate_);
    const std::int64_t counts = encoder_.counts(x_[1]);
    f.encoder_count[msg::kAxis2] = static_cast<std::int32_t>(counts);
    f.gimbal_angle_rad[msg::kAxis2] = encoder_.angle_of(counts);
    f.gimbal_rate_rad_s[msg::kAxis2] = x_[3] + case_rate_noise_.sample(rng_case_rate_);
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.command_Nm = cmd.gimbal_torque_Nm[msg::kAxis2];
    plant_.brake_Nms = std::clamp(cmd.precession_brake, 0.0, 1.0) * s_.brake_full_Nms;
  }

  void advance(std::int64_t tick) {
    window_.before_tick(tick, x_, {plant_.command_Nm, plant_.brake_Nms});
    driver_.advance_tick(tick, x_);
    window_.after_tick(tick, x_);
    const std::int64_t now = tick + 1;  // the state is at the start of tick + 1
    if (now >= settle_tick_) tilt_.add(x_[0]);
    case_peak_ = std::fmax(case_peak_, std::fabs(x_[1]));
    torque_peak_ = std::fmax(torque_peak_, std::fabs(plant_.command_Nm));
    gust_tilt_.add(now, x_[0]);
    gust_case_.add(now, x_[1]);
    curve_tilt_.add(now, x_[0]);
    curve_case_.add(now, x_[1]);
    if (overturned_tick_ < 0 && std::fabs(x_[0]) >= 0.5 * std::numbers::pi) overturned_tick_ = now;
    ticks_ = now;
  }

  bool finite() const { return x_.allFinite(); }

  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): 1 s from the first load (the gust's or
  // the curve's start, else t = 0; the run's middle if that is later), where the car and the case move most.
  nlohmann::json error_estimate() const {
    const auto apply = [](CarOnTrack& p, const TickInputs& in) {
      p.command_Nm = in.command_Nm;
      p.brake_Nms = in.brake_Nms;
    };
    return window_.estimate<dynamics::Rk4>(plant_, apply, s_.loop.tick_ns, s_.loop.substeps, 4,
                                           {"tilt_rad", "case_angle_rad", "tilt_rate_rad_s", "case_rate_rad_s"},
                                           "none watched: gust, curve, motor and brake act");
  }

  // The runtime guard's names for the plant state (tools/run/state_guard.hpp).
  static constexpr int kGuardedStates = 4;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"tilt_rad", "case_angle_rad", "tilt_rate_rad_s", "case_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

  static std::vector<std::string> columns() {
    return {"tilt_rad",       "case_angle_rad",        "tilt_rate_rad_s", "case_rate_rad_s", "Omega3_rad_s",
            "gust_moment_Nm", "centrifugal_moment_Nm", "motor_torque_Nm", "status_bits"};
  }
  void record(double* row) const {
    const double t =
        1e-9 * static_cast<double>((static_cast<std::int64_t>(last_.tick) + 1) * s_.loop.tick_ns);
    row[0] = x_[0];
    row[1] = x_[1];
    row[2] = x_[2];
    row[3] = x_[3];
    row[4] = s_.track.curve(t);
    row[5] = s_.track.gust(t);
    row[6] = plant_.lateral_g(t) * s_.car.c * std::cos(x_[0]);
    row[7] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[8] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  // What the plant accepts over a link (hil/link/actuator_frame_check.hpp): the law's torque limit on both
  // axes; no voltage limit (torque-mode drive, the voltages are unused).
  hil::ActuatorLimits actuator_limits() const {
    hil::ActuatorLimits l;
    l.torque_Nm[0] = l.torque_Nm[1] = s_.controller.law.torque_limit_Nm;
    return l;
  }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const firmware::MonorailMotorParams& law = s_.controller.law;
    const double d_total = law.d + law.d_mechanical;
    const double W = s_.track.curve.Omega3;
    const firmware::MonorailGainWindow straight = firmware::monorail_gain_window(law);
    const firmware::MonorailGainWindow curve = firmware::monorail_gain_window(law_in_curve(law, W));
    const double tick_s = s_.loop.tick_s();
    nlohmann::json f{
        {"tilt_rms_rad", tilt_.rms()},
        {"tilt_max_rad", tilt_.peak},
        {"case_angle_max_rad", case_peak_},
        {"motor_torque_max_Nm", torque_peak_},
        {"k_Nm_per_rad", law.k},
        {"k_lo_Nm_per_rad", straight.k_min},
        {"k_hi_Nm_per_rad", straight.k_max},
        {"omega_P_rad_s", straight.omega_P},
        {"omega_N_rad_s", straight.omega_N},
        {"decay_rate_per_s_predicted", -max_real_root(s_.car, law.k, d_total, 0.0)},
        {"curve_Omega3_rad_s", W},
        {"curve_H_Omega3_Nm_per_rad", s_.car.H * W},
        {"curve_radius_m", W != 0.0 && s_.track.speed_m_s > 0.0
                               ? nlohmann::json(s_.track.speed_m_s / std::fabs(W))
                               : nlohmann::json()},
        // (14.6)'s necessary condition; violated by (14.7) c > HΩ3 > q.
        {"curve_condition_14_7_holds", (s_.car.c - s_.car.H * W) * (s_.car.q - s_.car.H * W) > 0.0},
        {"curve_k_lo_Nm_per_rad", curve.gyro_strong_enough ? nlohmann::json(curve.k_min) : nlohmann::json()},
        {"curve_k_hi_Nm_per_rad", curve.gyro_strong_enough ? nlohmann::json(curve.k_max) : nlohmann::json()},
        {"curve_decay_rate_per_s_predicted", -max_real_root(s_.car, law.k, d_total, W)},
        {"gust_lean_rad", gust_tilt_.json()},
        {"gust_lean_rad_predicted", predicted_lean(gust_window_)},
        {"gust_case_angle_rad", gust_case_.json()},
        {"gust_case_angle_rad_predicted", predicted_case_angle(gust_window_)},
        {"curve_lean_rad", curve_tilt_.json()},
        {"curve_lean_rad_predicted", predicted_lean(curve_window_)},
        {"curve_case_angle_rad", curve_case_.json()},
        {"curve_case_angle_rad_predicted", predicted_case_angle(curve_window_)},
        {"overturned", overturned_tick_ >= 0},
        {"overturned_at_s", overturned_tick_ >= 0
                                ? nlohmann::json(static_cast<double>(overturned_tick_) * tick_s)
                                : nlohmann::json()},
        {"statistics_from_s", s_.settle_s},
        {"ticks", ticks_}};
    return f;
  }

 private:
  std::int64_t tick_at(double t_s) const {
    if (!std::isfinite(t_s)) return std::numeric_limits<std::int64_t>::max();
    return static_cast<std::int64_t>(std::llround(t_s / s_.loop.tick_s()));
  }
  void set_window(const LeanWindow& w, WindowMean& tilt, WindowMean& case_angle) const {
    tilt.from = case_angle.from = w.active ? tick_at(w.from_s) : 0;
    tilt.to = case_angle.to = w.active ? tick_at(w.to_s) : 0;
  }
  // Small-angle steady state of (14.6) with the law M2 = k (φ + tilt bias) − d β' under the window's constant
  // roll moment M1 (gust + c v Ω3 / g): A φ'' + Hβ' + (HΩ3 − c) φ = M1 gives φ = −M1 / (c − HΩ3) — the car
  // leans against the moment, whatever the gains — and B β'' + ... + (HΩ3 − q) β − k φ_measured = 0 gives
  // β = −k (φ + bias) / (q − HΩ3).
  double window_time(const LeanWindow& w) const { return 0.5 * (w.from_s + w.to_s); }
  nlohmann::json predicted_lean(const LeanWindow& w) const {
    if (!w.active) return nlohmann::json();
    const double t = window_time(w), W = s_.track.curve(t);
    const double M1 = s_.track.gust(t) + s_.car.c * plant_.lateral_g(t);
    return -M1 / (s_.car.c - s_.car.H * W);
  }
  nlohmann::json predicted_case_angle(const LeanWindow& w) const {
    if (!w.active) return nlohmann::json();
    const double t = window_time(w), W = s_.track.curve(t);
    const double phi = predicted_lean(w).get<double>();
    return -s_.controller.law.k * (phi + s_.sensors.tilt_bias_rad) / (s_.car.q - s_.car.H * W);
  }

  struct TickInputs {
    double command_Nm, brake_Nms;
  };
  std::int64_t first_load_tick() const {
    const Gust& g = s_.track.gust;
    const CurveProfile& c = s_.track.curve;
    double t = std::numeric_limits<double>::infinity();
    if (g.M1 != 0.0) t = std::min(t, g.start_s);
    if (c.Omega3 != 0.0) t = std::min(t, c.start_s);
    if (!std::isfinite(t)) t = 0.0;
    return std::min(tick_at(t), s_.loop.ticks() / 2);
  }

  const MonorailScene& s_;
  CarOnTrack plant_;
  dynamics::Rk4<CarOnTrack> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<CarOnTrack>> driver_;
  CarOnTrack::State x_;
  sensors::Encoder encoder_;
  sensors::SensorNoise tilt_noise_, tilt_rate_noise_, case_rate_noise_;
  random::SeededRng rng_tilt_, rng_tilt_rate_, rng_case_rate_;
  std::unique_ptr<Controller> controller_;
  std::int64_t settle_tick_;
  LeanWindow gust_window_, curve_window_;
  WindowMean gust_tilt_, gust_case_, curve_tilt_, curve_case_;
  msg::ActuatorFrame last_{};
  RunningStats tilt_;
  double case_peak_{0.0}, torque_peak_{0.0};
  std::int64_t overturned_tick_{-1};
  std::int64_t ticks_{0};
  accuracy::HalfStepWindow<CarOnTrack, TickInputs> window_{first_load_tick(),
                                                           static_cast<std::int64_t>(1.0 / s_.loop.tick_s())};
};

bool read_scene(SceneReader& r, MonorailScene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  auto& p = s.car;
  p.A = r.required("car", "A", Range::positive(), "car inertia about the rail, case upright [kg m²]");
  p.c = r.required("car", "c", Range::positive(), "overturning stiffness of the car m g h [N m/rad]");
  p.B = r.required("gyro", "B", Range::positive(), "case + rotor inertia about the case axis 2 [kg m²]");
  p.Q = r.number("gyro", "Q", 0.0, Range::any(), "A^R + A^J - C^J of (10.4) [kg m²]");
  p.q = r.required("gyro", "q", Range::positive(), "overturning stiffness of the case G s [N m/rad]");
  p.H = r.required("gyro", "H", Range::positive(), "rotor spin momentum [N m s]");
  p.d = r.number("gyro", "d_mechanical", 0.0, Range::non_negative(),
                 "passive damper on axis 2 (the motor realises the law's d) [N m s/rad]");
  p.k = 0.0;  // the firmware is the motor law
  s.brake_full_Nms = r.number("gyro", "brake_full_Nms", 1e4, Range::positive(),
                              "brake on axis 2 at precession_brake = 1 (safe state) [N m s/rad]");
  if (const char* why = p.invalid_reason()) r.fail("car", "A", why);

  s.phi0 = kDeg * r.number("initial", "phi0_deg", 0.0, Range::closed(-30.0, 30.0), "initial car tilt [deg]");
  s.beta0 =
      kDeg * r.number("initial", "beta0_deg", 0.0, Range::closed(-60.0, 60.0), "initial case angle [deg]");

  auto& t = s.track;
  t.speed_m_s =
      r.number("track", "speed_m_s", 0.0, Range::closed(0.0, 150.0), "car speed along the track [m/s]");
  t.curve.Omega3 = r.number("track", "Omega3", 0.0, Range::closed(-2.0, 2.0),
                            "turning rate of the path in the curve, + in the rotor's spin sense [rad/s]");
  t.curve.start_s = r.number("track", "curve_start_s", kNever, Range::non_negative(), "curve entry [s]");
  t.curve.end_s = r.number("track", "curve_end_s", kNever, Range::non_negative(), "curve exit [s]");
  t.curve.transition_s = r.number("track", "transition_s", 2.0, Range::non_negative(),
                                  "transition (clothoid) at entry and exit: Omega3 ramps linearly [s]");
  t.allow_unstable_curve = r.flag("track", "allow_unstable_curve", false,
                                  "run even if the loop of (14.6) is unstable in the curve");
  if (t.curve.end_s < t.curve.start_s + t.curve.transition_s) {
    r.fail("track", "curve_end_s",
           "must be >= curve_start_s + transition_s (the exit starts after the entry)");
  }
  t.gust.M1 = r.number("gust", "M1", 0.0, Range::closed(-1e7, 1e7), "side-wind roll moment on the car [N m]");
  t.gust.start_s = r.number("gust", "start_s", kNever, Range::non_negative(), "gust onset [s]");
  t.gust.duration_s = r.number("gust", "duration_s", 10.0, Range::non_negative(), "from onset to decay [s]");
  t.gust.rise_s = r.number("gust", "rise_s", 0.5, Range::non_negative(), "rise and decay time [s]");
  if (t.gust.rise_s > t.gust.duration_s) r.fail("gust", "rise_s", "must be <= duration_s");

  auto& n = s.sensors;
  n.tilt_noise_rad = r.number("sensors", "tilt_noise_rad", 1e-4, Range::non_negative(),
                              "car tilt noise, standard deviation per sample [rad]");
  n.tilt_bias_rad =
      r.number("sensors", "tilt_bias_rad", 0.0, Range::closed(-0.05, 0.05), "car tilt bias [rad]");
  n.tilt_rate_noise_density = r.number("sensors", "tilt_rate_noise_density", 1e-4, Range::non_negative(),
                                       "car roll-rate gyro noise density [rad/s/sqrt(Hz)]");
  n.case_rate_noise_density = r.number("sensors", "case_rate_noise_density", 1e-4, Range::non_negative(),
                                       "case rate gyro noise density [rad/s/sqrt(Hz)]");
  n.case_rate_bias =
      r.number("sensors", "case_rate_bias", 0.0, Range::closed(-0.1, 0.1), "case rate gyro bias [rad/s]");
  n.encoder_counts_per_rev = r.integer("sensors", "encoder_counts_per_rev", 65536, 16, 1 << 30,
                                       "case-angle encoder resolution [counts/rev]");

  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  auto& l = c.law;
  l.A = p.A;
  l.B = p.B;
  l.c = p.c;
  l.q = p.q;
  l.H = p.H;
  l.d_mechanical = p.d;
  l.k = r.required("controller", "k", Range::any(),
                   "motor gain on the car tilt, M2 = k phi - d beta' [N m/rad]");
  l.d = r.required("controller", "d", Range::non_negative(), "damper realised by the motor [N m s/rad]");
  l.torque_limit_Nm =
      r.number("controller", "torque_limit_Nm", 2000.0, Range::positive(), "motor torque limit [N m]");

  s.settle_s = r.number("report", "settle_s", std::min(10.0, 0.2 * s.loop.duration_s),
                        Range::closed(0.0, s.loop.duration_s), "tilt statistics start after this time [s]");
  if (r.ok()) {
    const firmware::ConfigCheck check = Controller::check(c);
    if (!check.ok)
      r.fail("controller", "k", "refused by the controller's start-up check: " + describe(check));
    // The loop of (14.6) at the curve's Ω3, with the firmware law: Hurwitz, or the car leaves the curve lying
    // down (the continuous loop; the sampled one at 1 kHz differs by O(ω_N T)).
    const double W = t.curve.Omega3, cW = p.c - p.H * W, qW = p.q - p.H * W, dt = l.d + p.d;
    const firmware::HurwitzResult h = firmware::hurwitz_quartic(
        p.A * p.B, p.A * dt, p.H * p.H - qW * p.A - cW * p.B, l.k * p.H - cW * dt, cW * qW);
    if (check.ok && std::isfinite(t.curve.start_s) && W != 0.0 && !h.stable && !t.allow_unstable_curve) {
      char msg[400];
      if (p.c > p.H * W && p.H * W > p.q) {
        std::snprintf(
            msg, sizeof msg,
            "= %g: H Omega3 = %g lies between q = %g and c = %g, (14.7): the car overturns in the curve "
            "for every gain; keep |Omega3| < q/H = %g (or set allow_unstable_curve = true to watch it)",
            W, p.H * W, p.q, p.c, p.q / p.H);
      } else {
        const firmware::MonorailGainWindow w = firmware::monorail_gain_window(law_in_curve(l, W));
        std::snprintf(
            msg, sizeof msg,
            "= %g: the loop of (14.6) with k = %g is unstable in the curve (window there %g < k < %g); "
            "set allow_unstable_curve = true to run it anyway",
            W, l.k, w.k_min, w.k_max);
      }
      r.fail("track", "Omega3", msg);
    }
    // The plant step against the car's fastest mode, with the law's gains in the linearisation (as a passive
    // k and d; the firmware's are sampled) and, separately, with the safe state's brake.
    models::MonorailParams closed = p;
    closed.k = l.k;
    closed.d = dt;
    const double h_sub = s.loop.tick_s() / s.loop.substeps;
    const models::Monorail::State x0 = models::Monorail::make_state(s.phi0, s.beta0, 0.0, 0.0);
    const dynamics::StepCheck step = dynamics::check_step(
        dynamics::Method::kRk4, dynamics::fastest_mode(models::Monorail(closed), 0.0, x0), h_sub);
    if (!step.ok) r.fail("loop", "plant_substeps", step.message);
    models::MonorailParams braked = p;
    braked.d += s.brake_full_Nms;
    const dynamics::StepCheck brake = dynamics::check_step(
        dynamics::Method::kRk4, dynamics::fastest_mode(models::Monorail(braked), 0.0, x0), h_sub);
    if (!brake.ok) r.fail("gyro", "brake_full_Nms", "too stiff for the plant step: " + brake.message);
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_monorail(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<MonorailScene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  auto device = std::make_unique<MonorailDevice>(*scene);
  return run_device(*device, scene->loop, req);
}

}  // namespace gyrostab::tools
