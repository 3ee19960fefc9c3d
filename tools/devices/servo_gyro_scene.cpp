// Scene binding of the servo gyro as a gyroscopic vibrator drive (Magnus §14.4, (14.41)-(14.44), Fig. 14.9):
// the gimballed rotor whose axis 2 is driven by a torque motor (sim/models/servo_gyro.hpp, torque-driven
// mode) and whose axis 1 carries the oscillator; the firmware rate loop
// (firmware/app/servo_gyro_controller.hpp: PI + the feed-forward of (14.43)) holds β' at Ω, so the gyroscopic
// torque M1^KR = −H cosβ β' (14.42) drives the oscillator. Sensors: an absolute encoder on axis 2 (β, single
// turn), a tachometer for β', the axis-1 pick-off (α, α'), with seeded noise. Figures, over the whole drive
// revolutions after settling: the oscillator amplitude α_A and phase φ (Fourier sums against the drive angle
// β), the torque peaks (M1^KR)max and (M2)max of the applied motor torque, their ratio — the torque
// amplification — beside the book's 1/α_A (14.44) and the general 2/(α_A(1 + |sin φ|)) of the model header;
// the same ratio from the harmonic content (noise-free estimate); the rate loop's tracking; motor power
// against the dissipation. Keys: docs/scenes.md#servo_gyro.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>

#include "firmware/app/servo_gyro_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/servo_gyro.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/devices/scene_device.hpp"
#include "hil/link/actuator_frame_check.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/run_device.hpp"
#include "tools/run/controller_report.hpp"

namespace gyrostab::tools {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicServoGyroController<firmware::posix::MonotonicClock>;

// Random streams of the scene seed, one per consumer (seeded_rng.hpp): adding a consumer never shifts
// another.
enum Stream : std::uint64_t { kDriveRateStream = 1, kAlphaRateStream };

struct SensorConfig {
  double drive_rate_noise_density{1e-5};  // tachometer of axis 2 (the rate loop's input) [rad/s/√Hz]
  double drive_rate_bias{0.0};            // [rad/s]
  double alpha_rate_noise_density{1e-5};  // axis-1 rate (the feed-forward's input) [rad/s/√Hz]
  std::int64_t drive_encoder_counts_per_rev{65536};  // absolute, single turn
  std::int64_t alpha_encoder_counts_per_rev{65536};
};

struct ServoScene {
  LoopConfig loop;
  models::ServoGyroParams gyro;  // torque-driven: the firmware rate loop drives axis 2
  double brake_full_Nms{10.0};   // brake on axis 2 at precession_brake = 1 (safe state) [N m s/rad]
  SensorConfig sensors;
  firmware::ServoGyroConfig controller;
  double settle_s{15.0};
};

// The servo gyro with the motor torque of the firmware and the brake on axis 2 as a viscous torque.
struct DrivenServoGyro {
  [[maybe_unused]] static constexpr int kStateSize = 4;  // the Rk4 model concept
  using State = models::ServoGyro::State;
  mutable models::ServoGyro gyro;
  double brake_Nms{0.0};
  double command_Nm{0.0};

  void derivative(double t, const State& x, State& dx) const {
    gyro.inputs.M2 = command_Nm - brake_Nms * x[3];
    gyro.derivative(t, x, dx);
  }
  void project(State&) const {}
};

// Sums over the steady drive, against the drive angle β (the motor's, not the clock's, phase): with
// α = α_A cos(β − φ), M1^KR = −H cosβ β' and (14.43) M2^K = ½ H Ω α_A (sin(2β − φ) − sin φ), the Fourier sums
// over whole revolutions give α_A, φ, the amplitude of M1 and the mean and 2β-harmonic of M2 exactly for
// sinusoids sampled uniformly in β (to O(rate ripple) otherwise), while the noise averages out.
struct DriveSums {
  std::int64_t n{0};
  double alpha_cos{0.0}, alpha_sin{0.0};            // Σ α cosβ, Σ α sinβ [rad]
  double m1_cos{0.0}, m1_sin{0.0};                  // Σ M1 cosβ, Σ M1 sinβ [N m]
  double m2_mean{0.0}, m2_cos2{0.0}, m2_sin2{0.0};  // Σ M2, Σ M2 cos2β, Σ M2 sin2β [N m]
  double m1_peak{0.0}, m2_peak{0.0};                // max |M1^KR|, max |M2| [N m]
  double rate{0.0}, rate_error_peak{0.0};           // Σ β', max |β' − Ω| [rad/s]
  double motor_power{0.0}, dissipation{0.0};        // Σ M2 β', Σ (d1 α'² + d2 β'²) [W]
};

class ServoGyroDevice {
 public:
  explicit ServoGyroDevice(const ServoScene& s)
      : s_(s),
        plant_{models::ServoGyro(s.gyro), 0.0, 0.0},
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        drive_encoder_({s.sensors.drive_encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kAbsolute,
                        sensors::EncoderParams::Rounding::kNearest}),
        alpha_encoder_({s.sensors.alpha_encoder_counts_per_rev, 0.0,
                        sensors::EncoderParams::Mode::kIncremental,
                        sensors::EncoderParams::Rounding::kNearest}),
        drive_rate_noise_({s.sensors.drive_rate_noise_density, s.sensors.drive_rate_bias, 0.0},
                          s.loop.tick_s()),
        alpha_rate_noise_({s.sensors.alpha_rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
        rng_drive_rate_(s.loop.seed, kDriveRateStream),
        rng_alpha_rate_(s.loop.seed, kAlphaRateStream),
        controller_(std::make_unique<Controller>(s.controller)),
        settle_tick_(static_cast<std::int64_t>(std::llround(s.settle_s / s.loop.tick_s()))) {
    x_ = models::ServoGyro::make_state(0.0, 0.0, 0.0, 0.0);
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    // Axis 2 turns without end: a single-turn absolute encoder, read as β in [−π, π).
    const std::int64_t drive_counts = drive_encoder_.counts(x_[1]);
    double beta = drive_encoder_.angle_of(drive_counts);
    if (beta >= std::numbers::pi) beta -= kTwoPi;
    f.encoder_count[msg::kAxis2] = static_cast<std::int32_t>(drive_counts);
    f.gimbal_angle_rad[msg::kAxis2] = beta;
    f.gimbal_rate_rad_s[msg::kAxis2] = x_[3] + drive_rate_noise_.sample(rng_drive_rate_);
    const std::int64_t alpha_counts = alpha_encoder_.counts(x_[0]);
    f.encoder_count[msg::kAxis1] = static_cast<std::int32_t>(alpha_counts);
    f.gimbal_angle_rad[msg::kAxis1] = alpha_encoder_.angle_of(alpha_counts);
    f.gimbal_rate_rad_s[msg::kAxis1] = x_[2] + alpha_rate_noise_.sample(rng_alpha_rate_);
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.command_Nm = cmd.gimbal_torque_Nm[msg::kAxis2];
    plant_.brake_Nms = std::clamp(cmd.precession_brake, 0.0, 1.0) * s_.brake_full_Nms;
  }

  void advance(std::int64_t tick) {
    const double M2 = plant_.command_Nm - plant_.brake_Nms * x_[3];  // over this tick (zero-order hold)
    window_.before_tick(tick, x_, {plant_.command_Nm, plant_.brake_Nms});
    driver_.advance_tick(tick, x_);
    window_.after_tick(tick, x_);
    ticks_ = tick + 1;
    if (ticks_ < settle_tick_) return;
    if (!started_) {
      started_ = true;
      beta_start_ = x_[1];
    }
    // A completed revolution: the samples so far cover whole revolutions uniformly; keep them.
    const auto revs = static_cast<std::int64_t>(std::floor(std::fabs(x_[1] - beta_start_) / kTwoPi));
    if (revs > revolutions_) {
      revolutions_ = revs;
      done_ = run_;
    }
    add(M2);
  }

  bool finite() const { return x_.allFinite(); }

  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): 1 s of the steady drive from the end of
  // the settling time (the run's middle if that is later).
  nlohmann::json error_estimate() const {
    const auto apply = [](DrivenServoGyro& p, const TickInputs& in) {
      p.command_Nm = in.command_Nm;
      p.brake_Nms = in.brake_Nms;
    };
    return window_.estimate<dynamics::Rk4>(plant_, apply, s_.loop.tick_ns, s_.loop.substeps, 4,
                                           {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"},
                                           "none watched: the drive motor and friction act");
  }

  // The runtime guard's names for the plant state (tools/run/state_guard.hpp).
  static constexpr int kGuardedStates = 4;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

  static std::vector<std::string> columns() {
    return {"alpha_rad",  "alpha_rate_rad_s", "drive_rate_rad_s",
            "M1_gyro_Nm", "motor_torque_Nm",  "status_bits"};
  }
  void record(double* row) const {
    row[0] = x_[0];
    row[1] = x_[2];
    row[2] = x_[3];
    row[3] = plant_.gyro.gyro_torque_axis1(x_);
    row[4] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[5] = static_cast<double>(last_.status);
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
    const DriveSums& d = done_;
    nlohmann::json f{{"drive_rate_reference_rad_s", s_.controller.reference},
                     {"revolutions", revolutions_},
                     {"statistics_from_s", s_.settle_s},
                     {"ticks", ticks_}};
    const char* measured[] = {"alpha_A_rad",
                              "phase_rad",
                              "M1_max_Nm",
                              "M2_max_Nm",
                              "torque_gain",
                              "torque_gain_book",
                              "torque_gain_general",
                              "M1_amplitude_harmonic_Nm",
                              "M2_max_harmonic_Nm",
                              "torque_gain_harmonic",
                              "drive_rate_mean_rad_s",
                              "drive_rate_error_max_rad_s",
                              "motor_power_W",
                              "dissipation_W"};
    if (d.n == 0) {  // no whole revolution after settling (a short run)
      for (const char* key : measured) f[key] = nullptr;
      return f;
    }
    const double n = static_cast<double>(d.n);
    const double alpha_A = 2.0 / n * std::hypot(d.alpha_cos, d.alpha_sin);
    const double phase = std::atan2(d.alpha_sin, d.alpha_cos);
    const double m2_harmonic = std::fabs(d.m2_mean / n) + 2.0 / n * std::hypot(d.m2_cos2, d.m2_sin2);
    const double m1_harmonic = 2.0 / n * std::hypot(d.m1_cos, d.m1_sin);
    f["alpha_A_rad"] = alpha_A;
    f["phase_rad"] = phase;
    f["M1_max_Nm"] = d.m1_peak;
    f["M2_max_Nm"] = d.m2_peak;
    f["torque_gain"] = d.m1_peak / d.m2_peak;
    f["torque_gain_book"] = 1.0 / alpha_A;  // (14.44)
    f["torque_gain_general"] =
        2.0 / (alpha_A * (1.0 + std::fabs(std::sin(phase))));  // model header [derived]
    f["M1_amplitude_harmonic_Nm"] = m1_harmonic;
    f["M2_max_harmonic_Nm"] = m2_harmonic;
    f["torque_gain_harmonic"] = m1_harmonic / m2_harmonic;
    f["drive_rate_mean_rad_s"] = d.rate / n;
    f["drive_rate_error_max_rad_s"] = d.rate_error_peak;
    f["motor_power_W"] = d.motor_power / n;
    f["dissipation_W"] = d.dissipation / n;
    return f;
  }

 private:
  void add(double M2) {
    const double beta = x_[1], cb = std::cos(beta), sb = std::sin(beta);
    const double M1 = plant_.gyro.gyro_torque_axis1(x_);
    const double c2 = cb * cb - sb * sb, s2 = 2.0 * sb * cb;
    DriveSums& r = run_;
    ++r.n;
    r.alpha_cos += x_[0] * cb;
    r.alpha_sin += x_[0] * sb;
    r.m1_cos += M1 * cb;
    r.m1_sin += M1 * sb;
    r.m2_mean += M2;
    r.m2_cos2 += M2 * c2;
    r.m2_sin2 += M2 * s2;
    r.m1_peak = std::fmax(r.m1_peak, std::fabs(M1));
    r.m2_peak = std::fmax(r.m2_peak, std::fabs(M2));
    r.rate += x_[3];
    r.rate_error_peak = std::fmax(r.rate_error_peak, std::fabs(x_[3] - s_.controller.reference));
    r.motor_power += M2 * x_[3];
    r.dissipation += s_.gyro.d1 * x_[2] * x_[2] + s_.gyro.d2 * x_[3] * x_[3];
  }

  struct TickInputs {
    double command_Nm, brake_Nms;
  };

  const ServoScene& s_;
  DrivenServoGyro plant_;
  dynamics::Rk4<DrivenServoGyro> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<DrivenServoGyro>> driver_;
  DrivenServoGyro::State x_;
  sensors::Encoder drive_encoder_, alpha_encoder_;
  sensors::SensorNoise drive_rate_noise_, alpha_rate_noise_;
  random::SeededRng rng_drive_rate_, rng_alpha_rate_;
  std::unique_ptr<Controller> controller_;
  std::int64_t settle_tick_;
  msg::ActuatorFrame last_{};
  bool started_{false};
  double beta_start_{0.0};
  std::int64_t revolutions_{0};
  DriveSums run_{}, done_{};
  std::int64_t ticks_{0};
  accuracy::HalfStepWindow<DrivenServoGyro, TickInputs> window_{std::min(settle_tick_, s_.loop.ticks() / 2),
                                                                static_cast<std::int64_t>(1.0 / s_.loop.tick_s())};
};

bool read_scene(SceneReader& r, ServoScene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  auto& g = s.gyro;
  g.rate_driven = false;  // the firmware's rate loop is the drive
  g.A = r.required("gyro", "A", Range::positive(),
                   "axis-1 inertia: outer + inner gimbal + rotor + oscillator at beta = 0 [kg m²]");
  g.B = r.required("gyro", "B", Range::positive(), "inner gimbal + rotor about axis 2 [kg m²]");
  g.Q = r.number("gyro", "Q", 0.0, Range::any(), "A^R + A^J - C^J of (10.4) [kg m²]");
  g.H = r.required("gyro", "H", Range::positive(), "rotor spin momentum [N m s]");
  g.d2 = r.number("gyro", "d2", 0.0, Range::non_negative(), "viscous friction on axis 2 [N m s/rad]");
  s.brake_full_Nms = r.number("gyro", "brake_full_Nms", 10.0, Range::positive(),
                              "brake on axis 2 at precession_brake = 1 (safe state) [N m s/rad]");
  g.c1 = r.required("oscillator", "c1", Range::non_negative(), "oscillator stiffness on axis 1 [N m/rad]");
  g.d1 = r.required("oscillator", "d1", Range::non_negative(), "oscillator damping on axis 1 [N m s/rad]");
  if (const char* why = g.invalid_reason()) r.fail("gyro", "A", why);

  auto& n = s.sensors;
  n.drive_rate_noise_density = r.number("sensors", "drive_rate_noise_density", 1e-5, Range::non_negative(),
                                        "axis-2 tachometer noise density [rad/s/sqrt(Hz)]");
  n.drive_rate_bias =
      r.number("sensors", "drive_rate_bias", 0.0, Range::closed(-1.0, 1.0), "axis-2 tachometer bias [rad/s]");
  n.alpha_rate_noise_density = r.number("sensors", "alpha_rate_noise_density", 1e-5, Range::non_negative(),
                                        "axis-1 rate noise density [rad/s/sqrt(Hz)]");
  n.drive_encoder_counts_per_rev = r.integer("sensors", "drive_encoder_counts_per_rev", 65536, 16, 1 << 30,
                                             "axis-2 absolute encoder resolution [counts/rev]");
  n.alpha_encoder_counts_per_rev = r.integer("sensors", "alpha_encoder_counts_per_rev", 65536, 16, 1 << 30,
                                             "axis-1 encoder resolution [counts/rev]");

  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.reference_kind = firmware::ServoGyroReference::kRate;
  c.reference =
      r.required("controller", "Omega", Range::closed(-1e3, 1e3), "drive rate of axis 2, beta' [rad/s]");
  auto& l = c.law;
  l.B = g.B;
  l.H = g.H;
  // The tuning of firmware/control/servo_gyro_law.hpp on B β'' = M2: k_p = B ω_c gives the rate bandwidth ω_c
  // (default 200 rad/s), k_i = k_p ω_c / 4 = k_p² / (4B) a double closed-loop pole at −ω_c/2.
  const double B_law = std::isfinite(g.B) ? g.B : 1.0;  // (a missing B is already reported)
  l.rate_kp =
      r.number("controller", "rate_kp", 200.0 * B_law, Range::positive(), "rate loop k_p [N m s/rad]");
  l.rate_ki = r.number("controller", "rate_ki", l.rate_kp * l.rate_kp / (4.0 * B_law), Range::non_negative(),
                       "rate loop k_i [N m/rad]");
  l.feedforward =
      r.flag("controller", "feedforward", true, "add the feed-forward -H cos(beta) alpha' of (14.43)");
  l.torque_limit_Nm =
      r.required("controller", "torque_limit_Nm", Range::positive(), "motor torque limit [N m]");

  s.settle_s = r.number("report", "settle_s", std::min(15.0, 0.5 * s.loop.duration_s),
                        Range::closed(0.0, s.loop.duration_s), "statistics start after this time [s]");
  if (r.ok()) {
    const firmware::ConfigCheck check = Controller::check(c);
    if (!check.ok)
      r.fail("controller", "rate_kp", "refused by the controller's start-up check: " + describe(check));
    // The plant step against its fastest mode (oscillator or nutation), free and with the safe state's brake.
    const double h_sub = s.loop.tick_s() / s.loop.substeps;
    const models::ServoGyro::State x0 = models::ServoGyro::make_state(0.0, 0.0, 0.0, c.reference);
    const dynamics::StepCheck step = dynamics::check_step(
        dynamics::Method::kRk4, dynamics::fastest_mode(models::ServoGyro(g), 0.0, x0), h_sub);
    if (!step.ok) r.fail("loop", "plant_substeps", step.message);
    models::ServoGyroParams braked = g;
    braked.d2 += s.brake_full_Nms;
    const dynamics::StepCheck brake = dynamics::check_step(
        dynamics::Method::kRk4, dynamics::fastest_mode(models::ServoGyro(braked), 0.0, x0), h_sub);
    if (!brake.ok) r.fail("gyro", "brake_full_Nms", "too stiff for the plant step: " + brake.message);
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_servo_gyro(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<ServoScene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  auto device = std::make_unique<ServoGyroDevice>(*scene);
  return run_device(*device, scene->loop, req);
}

}  // namespace gyrostab::tools
