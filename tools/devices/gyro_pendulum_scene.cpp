// Scene binding of the Schuler-tuned gyro pendulum (or physical pendulum, H = 0) on a vehicle manoeuvring
// over the rotating Earth — Magnus §12.3.3 (12.52)-(12.68), Chelnokov §2. The pivot's motion comes from
// sim/motion/earth_vehicle.hpp ([earth], [vehicle], [segmentN]: tools/devices/vehicle_motion_scene.hpp), one
// sample per tick at each end (the end's LEFT limit, so a manoeuvre corner at a tick boundary is exact),
// linear in between (motion::SampledReference). The reference trihedron is the azimuth-free one (12.52).
// Plant, [pendulum] model =
//   "magnus"      small-angle (12.55)-(12.58), sim/models/gyro_pendulum_magnus.hpp; integrator
//                 "gyro-exponential" (nutation carried exactly: h ω^N up to 0.8·2π) or "rk4"
//   "rigid-body"  full 3-D Newton–Euler body spinning at H/C, sim/models/schuler_pendulum.hpp; integrator
//                 "strang" / "yoshida4" (exact free-body flow + pendulous/gravity-gradient kicks) or "rk4"
// Controller: firmware/app/gyro_pendulum_controller.hpp — monitor only, zero torque (the tuned instrument
// must not be corrected). Sensors: the case's tilt α, β from the geocentric vertical and their rates, with
// optional seeded white noise (an observer's pick-off, for the monitor and the log).
// Figures: the largest vertical error |z| beside the book's velocity-dependent error −Hw/(kR) (12.65); the
// deviation d = z − (−Hw/(kR)) split into its precession mode p = (ω^N d + i d')/(ω^N − ω^P) (the free
// Schuler swing: constant for a tuned instrument — unperturbability) and the nutation ripple d − p (excited
// at every manoeuvre corner, ~1e-6 rad); the period of p measured from zero crossings beside the book's
// (12.61)/(12.68) or (12.60); the tuned offset s of (12.66)/(12.59), k of (12.57), ω^N.
// Keys: docs/scenes.md#gyro_pendulum.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <numbers>

#include "firmware/app/gyro_pendulum_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/rotor_splitting.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyro_pendulum_magnus.hpp"
#include "sim/models/schuler_pendulum.hpp"
#include "sim/motion/suspension_reference.hpp"
#include "sim/oracles/schuler_tuning.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/devices/scene_device.hpp"
#include "tools/devices/scene_run.hpp"
#include "tools/devices/vehicle_motion_scene.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/run/run_device.hpp"

namespace gyrostab::tools {
namespace {

using Controller = firmware::BasicGyroPendulumController<firmware::posix::MonotonicClock>;
using Magnus = models::GyroPendulumMagnus<motion::SampledReference>;
using Body = models::SchulerPendulum<motion::SampledReference>;
using Cplx = std::complex<double>;

enum Stream : std::uint64_t { kTilt1Stream = 1, kTilt2Stream, kRate1Stream, kRate2Stream };
enum class PlantModel { kMagnus, kRigidBody };
enum class Integrator { kGyroExponential, kRk4, kStrang, kYoshida4 };

struct GpScene {
  LoopConfig loop;
  VehicleMotionConfig motion;
  PlantModel model{PlantModel::kMagnus};
  Integrator integrator{Integrator::kGyroExponential};
  models::GyroPendulumMagnusParams gyro;  // A, C, H, m, s, R, g, gravity gradient
  double s_tuned{0.0};                    // (12.66) for H > 0, (12.59) for H = 0 [m]
  bool start_on_equilibrium{true};        // z0 = −H w0/(kR)
  double alpha0{0.0}, beta0{0.0};         // added initial tilt [rad]
  double tilt_noise_density{0.0};         // [rad/√Hz]
  double rate_noise_density{0.0};         // [rad/s/√Hz]
  double period_threshold{1e-6};          // hysteresis of the period meter [rad]
  firmware::GyroPendulumConfig controller;
};

// Upward zero crossings with hysteresis: armed below −threshold, a crossing counted at the first sample ≥ 0
// after that (linear interpolation). The nutation ripple (≲ 2e-7 rad) stays inside the band.
class HysteresisCrossings {
 public:
  explicit HysteresisCrossings(double threshold) : thr_(threshold) {}
  void add(double t, double y) {
    if (y < -thr_) armed_ = true;
    if (has_prev_ && armed_ && prev_y_ < 0.0 && y >= 0.0) {
      const double tc = prev_t_ + (t - prev_t_) * (-prev_y_ / (y - prev_y_));
      if (n_ == 0) first_ = tc;
      last_ = tc;
      ++n_;
      armed_ = false;
    }
    prev_t_ = t;
    prev_y_ = y;
    has_prev_ = true;
  }
  int crossings() const { return n_; }
  double period() const { return n_ < 2 ? 0.0 : (last_ - first_) / (n_ - 1); }

 private:
  double thr_;
  bool armed_{false}, has_prev_{false};
  double prev_t_{0.0}, prev_y_{0.0}, first_{0.0}, last_{0.0};
  int n_{0};
};

class GyroPendulumDevice {
 public:
  explicit GyroPendulumDevice(const GpScene& s)
      : s_(s),
        vehicle_(make_vehicle(s.motion)),
        magnus_(s.gyro, motion::SampledReference{}),
        body_(body_params(s.gyro), motion::SampledReference{}),
        gx_(magnus_),
        rk_magnus_(magnus_),
        strang_(body_),
        yoshida_(body_),
        rk_body_(body_),
        d_gx_(gx_, s.loop.tick_ns, s.loop.substeps),
        d_rk_magnus_(rk_magnus_, s.loop.tick_ns, s.loop.substeps),
        d_strang_(strang_, s.loop.tick_ns, s.loop.substeps),
        d_yoshida_(yoshida_, s.loop.tick_ns, s.loop.substeps),
        d_rk_body_(rk_body_, s.loop.tick_ns, s.loop.substeps),
        k_(s.gyro.k()),
        roots_(s.gyro.H > 0.0 ? oracles::gyro_pendulum_roots(s.gyro.A, s.gyro.H, s.gyro.k())
                              : oracles::GyroPendulumRoots{0.0, 0.0}),
        corners_(s.motion),
        noise_{sensors::SensorNoise({s.tilt_noise_density, 0.0, 0.0}, s.loop.tick_s()),
               sensors::SensorNoise({s.tilt_noise_density, 0.0, 0.0}, s.loop.tick_s()),
               sensors::SensorNoise({s.rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
               sensors::SensorNoise({s.rate_noise_density, 0.0, 0.0}, s.loop.tick_s())},
        rng_{random::SeededRng(s.loop.seed, kTilt1Stream), random::SeededRng(s.loop.seed, kTilt2Stream),
             random::SeededRng(s.loop.seed, kRate1Stream), random::SeededRng(s.loop.seed, kRate2Stream)},
        crossings_(s.period_threshold),
        controller_(std::make_unique<Controller>(s.controller)) {
    current_ = sample(vehicle_.sample_ns(0));
    // Start: on the book's steady error (12.65) (z0 = −Hw0/(kR), z0' = −Hw0'/(kR)) or on the vertical.
    Cplx z0(s.alpha0, s.beta0), dz0(0.0, 0.0);
    if (s.start_on_equilibrium) {
      z0 += book_error(current_);
      dz0 = oracles::velocity_error(s.gyro.H, k_, s.gyro.R, {current_.a_Z.x(), current_.a_Z.y()});
    }
    xm_ = Magnus::make_state(z0.real(), z0.imag(), dz0.real(), dz0.imag());
    const dynamics::Quat tilt = dynamics::Quat(Eigen::AngleAxisd(z0.real(), dynamics::Vec3::UnitX())) *
                                dynamics::Quat(Eigen::AngleAxisd(z0.imag(), dynamics::Vec3::UnitY()));
    xb_ = models::make_rigid_body_state(
        tilt.conjugate() * (current_.w_Z + dynamics::Vec3(dz0.real(), dz0.imag(), 0.0)) +
            dynamics::Vec3(0.0, 0.0, s.gyro.C > 0.0 ? s.gyro.H / s.gyro.C : 0.0),
        current_.q_IZ * tilt);
    observe(0.0);
    mode_start_ = std::abs(p_);
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    f.gimbal_angle_rad[msg::kAxis1] = z_.real() + noise_[0].sample(rng_[0]);
    f.gimbal_angle_rad[msg::kAxis2] = z_.imag() + noise_[1].sample(rng_[1]);
    f.gimbal_rate_rad_s[msg::kAxis1] = dz_.real() + noise_[2].sample(rng_[2]);
    f.gimbal_rate_rad_s[msg::kAxis2] = dz_.imag() + noise_[3].sample(rng_[3]);
    f.rotor_speed_rad_s = s_.gyro.C > 0.0 ? s_.gyro.H / s_.gyro.C : 0.0;
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    magnus_.M1 = cmd.gimbal_torque_Nm[msg::kAxis1];
    magnus_.M2 = cmd.gimbal_torque_Nm[msg::kAxis2];
    body_.torque_ext_B = dynamics::Vec3(magnus_.M1, magnus_.M2, 0.0);  // small tilt: case ≈ F axes
  }

  void advance(std::int64_t tick) {
    const std::int64_t t1_ns = (tick + 1) * s_.loop.tick_ns;
    motion::SampledReference ref;
    ref.t0 = 1e-9 * static_cast<double>(tick * s_.loop.tick_ns);  // = SubstepDriver's t0
    ref.h = s_.loop.tick_s();
    ref.s0 = current_;
    ref.s1 = sample(vehicle_.sample_left_ns(t1_ns));  // left limit: the accelerations jump at corners
    if (s_.model == PlantModel::kMagnus) {
      magnus_.reference() = ref;
      window_.before_tick(tick, xm_, {ref, magnus_.M1, magnus_.M2});
      if (s_.integrator == Integrator::kRk4) d_rk_magnus_.advance_tick(tick, xm_);
      else d_gx_.advance_tick(tick, xm_);
      window_.after_tick(tick, xm_);
    } else {
      body_.reference() = ref;
      if (s_.integrator == Integrator::kRk4) d_rk_body_.advance_tick(tick, xb_);
      else if (s_.integrator == Integrator::kYoshida4) d_yoshida_.advance_tick(tick, xb_);
      else d_strang_.advance_tick(tick, xb_);
    }
    current_ = corners_.corner_at(t1_ns) ? sample(vehicle_.sample_ns(t1_ns)) : ref.s1;
    ticks_ = tick + 1;
    observe(1e-9 * static_cast<double>(t1_ns));
  }

  bool finite() const { return s_.model == PlantModel::kMagnus ? xm_.allFinite() : xb_.allFinite(); }

  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): 1000 ticks from the run's middle, the
  // Magnus model with the scene's integrator (the reference trihedron's samples are interpolated within the
  // tick exactly as in the run). Not (yet) for the rigid-body variant.
  nlohmann::json error_estimate() const {
    if (s_.model != PlantModel::kMagnus) {
      return {{"available", false}, {"why", "not estimated for the rigid-body (Chelnokov) variant of the scene"}};
    }
    const auto apply = [](Magnus& m, const MagnusTickInputs& in) {
      m.reference() = in.ref;
      m.M1 = in.M1;
      m.M2 = in.M2;
    };
    const std::array<const char*, 4> names{"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"};
    const char* inv = "none watched: the vehicle's accelerations and the Earth's rotation act";
    if (s_.integrator == Integrator::kRk4) {
      return window_.estimate<dynamics::Rk4>(magnus_, apply, s_.loop.tick_ns, s_.loop.substeps, 4, names, inv);
    }
    return window_.estimate<dynamics::GyroscopicExponential>(magnus_, apply, s_.loop.tick_ns, s_.loop.substeps, 2,
                                                             names, inv);
  }

  static std::vector<std::string> columns() {
    return {"alpha_rad",  "beta_rad",  "tilt_rad",     "alpha_book_rad", "beta_book_rad",
            "precession_mode_rad", "speed_m_s", "heading_deg", "latitude_deg", "status_bits"};
  }
  void record(double* row) const {
    constexpr double deg = 180.0 / std::numbers::pi;
    row[0] = z_.real();
    row[1] = z_.imag();
    row[2] = tilt_;
    row[3] = zb_.real();
    row[4] = zb_.imag();
    row[5] = std::abs(p_);
    row[6] = speed_;
    row[7] = heading_ * deg;
    row[8] = latitude_ * deg;
    row[9] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const auto& g = s_.gyro;
    nlohmann::json f{{"ticks", ticks_},
                     {"model", s_.model == PlantModel::kMagnus ? "magnus" : "rigid-body"},
                     {"step_s", s_.loop.tick_s() / s_.loop.substeps},
                     {"s_m", g.s},
                     {"s_tuned_m", s_.s_tuned},
                     {"k_Nm_per_rad", k_},
                     {"vertical_error_max_rad", vertical_error_max_},
                     {"book_velocity_error_max_rad", book_error_max_},
                     {"deviation_from_book_max_rad", deviation_max_},
                     {"precession_mode_start_rad", mode_start_},
                     {"precession_mode_min_rad", mode_min_},
                     {"precession_mode_max_rad", mode_max_},
                     {"precession_mode_end_rad", std::abs(p_)},
                     {"nutation_ripple_max_rad", ripple_max_},
                     {"schuler_period_book_min", oracles::schuler_period(g.g, g.R) / 60.0},
                     {"period_crossings", crossings_.crossings()}};
    f["period_measured_min"] = crossings_.crossings() >= 2 ? nlohmann::json(crossings_.period() / 60.0) : nlohmann::json(nullptr);
    if (g.H > 0.0) {
      const oracles::GyroPendulumRoots& r = roots_;
      f["nutation_frequency_rad_s"] = r.nutation;
      f["precession_rate_rad_s"] = r.precession;
      f["period_book_min"] = 2.0 * std::numbers::pi / std::abs(r.precession) / 60.0;  // (12.61), (12.68)
      f["nutation_over_precession"] = r.nutation / std::abs(r.precession);
    } else {
      const double T = oracles::pendulum_period(g.A, k_);  // (12.60)
      f["period_book_min"] = std::isfinite(T) ? nlohmann::json(T / 60.0) : nlohmann::json(nullptr);
    }
    return f;
  }

 private:
  static models::SchulerPendulumParams body_params(const models::GyroPendulumMagnusParams& g) {
    models::SchulerPendulumParams p;
    p.inertia = dynamics::Vec3(g.A, g.A, g.C > 0.0 ? g.C : g.A * 1e-9);
    p.ml = g.m * g.s;
    p.gravity_gradient = g.gravity_gradient;
    p.gradient_inertia = dynamics::Vec3(g.A, g.A, g.C);
    return p;
  }
  motion::SuspensionSample sample(const motion::EarthVehicleSample& v) {
    speed_ = v.speed;
    heading_ = v.heading;
    latitude_ = v.latitude;
    const motion::EarthParams& e = vehicle_.earth();
    return motion::suspension_from(v.azimuth_free, e.gravity / e.radius);
  }
  // The book's steady error −H w/(kR) (12.65); 0 for the physical pendulum.
  Cplx book_error(const motion::SuspensionSample& r) const {
    return oracles::velocity_error(s_.gyro.H, k_, s_.gyro.R, {r.v_Z.x(), r.v_Z.y()});
  }
  void observe(double t) {
    if (s_.model == PlantModel::kMagnus) {
      z_ = Cplx(xm_[0], xm_[1]);
      dz_ = Cplx(xm_[2], xm_[3]);
      tilt_ = std::abs(z_);
    } else {
      double a, b;
      Body::magnus_angles(current_, xb_, a, b);
      z_ = Cplx(a, b);
      const Eigen::Map<const dynamics::Quat> q_IB(xb_.data() + 3);
      const dynamics::Vec3 w_rel =
          current_.q_IZ.conjugate() * (q_IB * dynamics::Vec3(xb_[0], xb_[1], 0.0)) - current_.w_Z;
      dz_ = Cplx(w_rel.x(), w_rel.y());
      tilt_ = Body::tilt(current_, xb_);
    }
    zb_ = book_error(current_);
    const Cplx d = z_ - zb_;
    const Cplx dd = dz_ - oracles::velocity_error(s_.gyro.H, k_, s_.gyro.R, {current_.a_Z.x(), current_.a_Z.y()});
    // Precession-mode part of the deviation (homogeneous (12.58): z = Z1 e^(iω^N t) + Z2 e^(iω^P t)).
    p_ = s_.gyro.H > 0.0 ? (roots_.nutation * d + Cplx(0.0, 1.0) * dd) / (roots_.nutation - roots_.precession) : d;
    vertical_error_max_ = std::max(vertical_error_max_, tilt_);
    book_error_max_ = std::max(book_error_max_, std::abs(zb_));
    deviation_max_ = std::max(deviation_max_, std::abs(d));
    mode_max_ = std::max(mode_max_, std::abs(p_));
    mode_min_ = std::min(mode_min_, std::abs(p_));
    ripple_max_ = std::max(ripple_max_, std::abs(d - p_));
    crossings_.add(t, p_.real());
  }

  struct MagnusTickInputs {
    motion::SampledReference ref;
    double M1, M2;
  };

  const GpScene& s_;
  VehicleGenerator vehicle_;
  Magnus magnus_;
  Body body_;
  dynamics::GyroscopicExponential<Magnus> gx_;
  dynamics::Rk4<Magnus> rk_magnus_;
  dynamics::RotorStrang<Body> strang_;
  dynamics::RotorYoshida4<Body> yoshida_;
  dynamics::Rk4<Body> rk_body_;
  dynamics::SubstepDriver<dynamics::GyroscopicExponential<Magnus>> d_gx_;
  dynamics::SubstepDriver<dynamics::Rk4<Magnus>> d_rk_magnus_;
  dynamics::SubstepDriver<dynamics::RotorStrang<Body>> d_strang_;
  dynamics::SubstepDriver<dynamics::RotorYoshida4<Body>> d_yoshida_;
  dynamics::SubstepDriver<dynamics::Rk4<Body>> d_rk_body_;
  double k_;
  oracles::GyroPendulumRoots roots_;
  Magnus::State xm_{Magnus::State::Zero()};
  accuracy::HalfStepWindow<Magnus, MagnusTickInputs> window_{s_.loop.ticks() / 2, 1000};
  Body::State xb_{Body::State::Zero()};
  motion::SuspensionSample current_{};
  CornerClock corners_;
  std::array<sensors::SensorNoise, 4> noise_;
  std::array<random::SeededRng, 4> rng_;
  HysteresisCrossings crossings_;
  std::unique_ptr<Controller> controller_;
  msg::ActuatorFrame last_{};
  Cplx z_{0.0, 0.0}, dz_{0.0, 0.0}, zb_{0.0, 0.0}, p_{0.0, 0.0};
  double tilt_{0.0}, speed_{0.0}, heading_{0.0}, latitude_{0.0};
  double vertical_error_max_{0.0}, book_error_max_{0.0}, deviation_max_{0.0};
  double mode_start_{0.0}, mode_min_{1e300}, mode_max_{0.0}, ripple_max_{0.0};
  std::int64_t ticks_{0};
};

bool read_scene(SceneReader& r, GpScene& s) {
  const std::string model = r.choice("pendulum", "model", "magnus", {"magnus", "rigid-body"},
                                     "small-angle (12.58) or full 3-D rigid body");
  s.model = model == "rigid-body" ? PlantModel::kRigidBody : PlantModel::kMagnus;
  if (s.model == PlantModel::kMagnus) {
    s.loop = read_loop_config(r, "gyro-exponential", {"gyro-exponential", "rk4"});
  } else {
    s.loop = read_loop_config(r, "strang", {"strang", "yoshida4", "rk4"});
  }
  const std::string& in = s.loop.integrator;
  s.integrator = in == "rk4"        ? Integrator::kRk4
                 : in == "strang"   ? Integrator::kStrang
                 : in == "yoshida4" ? Integrator::kYoshida4
                                    : Integrator::kGyroExponential;
  s.motion = read_vehicle_motion(r, 50.0);
  // The per-tick sampling is exact at corners only when they fall on tick boundaries.
  if (r.ok()) {
    if (const char* why = corners_on_ticks(s.motion, s.loop.tick_ns)) r.fail("segment1", "duration_s", why);
  }
  auto& g = s.gyro;
  g.R = s.motion.earth.radius;
  g.g = s.motion.earth.gravity;
  g.A = r.required("pendulum", "A", Range::positive(), "transverse moment of rotor + case about the pivot [kg m²]");
  g.C = r.required("pendulum", "C", Range::non_negative(), "axial moment of rotor + case about the pivot [kg m²]");
  g.m = r.required("pendulum", "m", Range::positive(), "mass [kg]");
  g.H = r.number("pendulum", "H", 0.0, Range::non_negative(), "spin momentum [N m s] (0: physical pendulum)");
  g.gravity_gradient = r.flag("pendulum", "gravity_gradient", true, "include the −(3g/R)(C − A) of (12.57)");
  if (std::isfinite(g.A) && std::isfinite(g.C) && std::isfinite(g.m) && std::isfinite(g.H) && g.m > 0.0) {
    s.s_tuned = g.H > 0.0 ? oracles::tuned_gyro_pendulum_offset(g.m, g.A, g.C, g.H, g.g, g.R)  // (12.66)
                          : g.A / (g.m * g.R);                                                  // (12.59)
  }
  const double s_given = r.number("pendulum", "s_m", 0.0, Range::closed(-10.0, 10.0),
                                  "centre of mass below the pivot [m]; 0 or absent: the tuned value");
  const double detune = r.number("pendulum", "detuning", 1.0, Range::closed(0.0, 100.0),
                                 "factor on s (1: as tuned or given)");
  g.s = (s_given != 0.0 ? s_given : s.s_tuned) * detune;
  s.start_on_equilibrium =
      r.choice("pendulum", "start", "equilibrium", {"equilibrium", "vertical"},
               "initial tilt: the book's steady error -Hw/(kR) (12.65), or the geocentric vertical") == "equilibrium";
  s.alpha0 = kDeg * r.number("pendulum", "alpha0_deg", 0.0, Range::closed(-10.0, 10.0), "added initial tilt about F1 [deg]");
  s.beta0 = kDeg * r.number("pendulum", "beta0_deg", 0.0, Range::closed(-10.0, 10.0), "added initial tilt about F2 [deg]");
  if (const char* why = g.invalid_reason()) r.fail("pendulum", "A", why);
  if (r.ok() && s.model == PlantModel::kRigidBody && !(g.C > 0.0) && g.H > 0.0)
    r.fail("pendulum", "C", "a spinning rigid body needs C > 0 (its spin is H/C)");
  if (r.ok() && s.model == PlantModel::kRigidBody && 2.0 * g.A < g.C)
    r.fail("pendulum", "C", "C > 2A violates the triangle inequality of a rigid body's moments");

  s.tilt_noise_density = r.number("sensors", "tilt_noise_density", 0.0, Range::non_negative(),
                                  "tilt pick-off noise [rad/sqrt(Hz)]");
  s.rate_noise_density = r.number("sensors", "rate_noise_density", 0.0, Range::non_negative(),
                                  "tilt-rate pick-off noise [rad/s/sqrt(Hz)]");
  s.period_threshold = r.number("report", "period_threshold_rad", 1e-6, Range::positive(),
                                "hysteresis of the zero-crossing period meter [rad]");
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;

  if (r.ok()) {
    const firmware::ConfigCheck check = Controller::check(s.controller);
    if (!check.ok) r.fail("loop", "tick_us", "refused by the controller's start-up check: " + describe(check));
    // The plant step against the fastest mode: the nutation ω^N (12.61) with spin, else the pendulum's own.
    const double h_sub = s.loop.tick_s() / s.loop.substeps;
    dynamics::Mode mode;
    if (g.H > 0.0) {
      mode.name = "nutation";
      mode.lambda = {0.0, oracles::gyro_pendulum_roots(g.A, g.H, g.k()).nutation};
    } else {
      const double k = g.k();
      mode.name = k > 0.0 ? "pendulum" : "divergence";
      mode.lambda = k > 0.0 ? std::complex<double>(0.0, std::sqrt(k / g.A)) : std::complex<double>(std::sqrt(-k / g.A), 0.0);
    }
    const dynamics::Method m = s.integrator == Integrator::kRk4        ? dynamics::Method::kRk4
                               : s.integrator == Integrator::kStrang   ? dynamics::Method::kStrang
                               : s.integrator == Integrator::kYoshida4 ? dynamics::Method::kYoshida4
                                                                       : dynamics::Method::kGyroExponential;
    if (g.H > 0.0 || g.k() > 0.0) {
      const dynamics::StepCheck step = dynamics::check_step(m, mode, h_sub);
      if (!step.ok) r.fail("loop", "plant_substeps", step.message);
    }
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_gyro_pendulum(SceneReader& reader, const RunRequest& req) {
  return run_scene<GyroPendulumDevice>(reader, req, read_scene);
}

}  // namespace gyrostab::tools
