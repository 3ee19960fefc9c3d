// Scene binding of the gyroscopic ship roll damper (Magnus §14.2, (14.8)): the plant
// (sim/models/ship_roll_damper.hpp) in a regular or irregular sea, its sensors, the firmware controller
// (firmware/app/ship_roll_damper_controller.hpp: passive brake or active precession control) and, in the
// same sea, the same ship with the gyro locked — the unstabilized reference for `roll_reduction`.
// Keys: docs/scenes.md#ship_roll_damper.
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <variant>

#include "firmware/app/ship_roll_damper_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/ship_roll_damper.hpp"
#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/regular_wave_moment.hpp"
#include "sim/motion/wave_spectrum.hpp"
#include "sim/motion/wave_transfer.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/accuracy/input_tap.hpp"
#include "tools/devices/running_stats.hpp"
#include "tools/devices/ship_in_sea.hpp"
#include "tools/devices/ship_roll_damper_study.hpp"
#include "tools/devices/scene_device.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/run_device.hpp"
#include "tools/run/controller_report.hpp"

namespace gyrostab::tools {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
using Sea = motion::IrregularSea<256>;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicShipRollDamperController<firmware::posix::MonotonicClock>;

// Random streams of the scene seed, one per consumer (seeded_rng.hpp): adding a consumer never shifts another.
enum Stream : std::uint64_t { kSeaStream = 1, kRollAngleStream, kRollRateStream, kPrecessionRateStream };

struct SeaConfig {
  bool regular{false};
  motion::RegularWaveMoment wave{};
  motion::WaveSpectrumParams spectrum{};
  motion::IrregularSeaParams irregular{};
  double kappa{1.0};
};

struct SensorConfig {
  double roll_angle_noise_rad{1e-4};          // white noise of the roll-angle (inclinometer/AHRS) output [rad]
  double roll_rate_noise_density{1e-4};       // rate gyro white noise [rad/s/√Hz]
  double roll_rate_bias{0.0};                 // [rad/s]
  double precession_rate_noise_density{1e-4}; // [rad/s/√Hz]
  std::int64_t encoder_counts_per_rev{65536};
};

struct ShipScene {
  LoopConfig loop;
  models::ShipRollDamperParams ship;
  double brake_full_Nms{1e7};  // plant brake at precession_brake = 1 (safe state locks the case) [N m s/rad]
  SeaConfig sea;
  SensorConfig sensors;
  firmware::ShipRollDamperConfig controller;
  double settle_s{60.0};
};

// The sea's roll moment E(t) [N m], regular (14.9) or irregular.
class SeaMoment {
 public:
  SeaMoment(const SeaConfig& c, double grid_period, std::uint64_t seed, double roll_stiffness) : regular_(c.regular),
      wave_(c.wave) {
    if (!regular_) {
      random::SeededRng rng(seed, kSeaStream);
      motion::IrregularSeaParams p = c.irregular;
      p.grid_period = grid_period;
      sea_ = std::make_unique<Sea>(motion::WaveSpectrum(c.spectrum), p, rng,
                                   motion::WaveRollMomentTransfer{roll_stiffness, c.kappa});
    }
  }
  // Both ships (stabilized and reference) evaluate E at the same RK4 stage times t, t + h/2 (twice), t + h,
  // so the last few values are kept: E is a pure function of t (irregular_sea.hpp), a hit is the same bits.
  double operator()(double t) const {
    for (const Memo& m : memo_) {
      if (m.t == t) return m.value;
    }
    const double value = regular_ ? wave_(t) : (*sea_)(t);
    memo_[next_memo_] = {t, value};
    next_memo_ = (next_memo_ + 1) % memo_.size();
    return value;
  }
  double rms() const { return regular_ ? wave_.E0 / std::sqrt(2.0) : std::sqrt(sea_->output_variance()); }

 private:
  struct Memo {
    double t{std::numeric_limits<double>::quiet_NaN()};  // NaN: never equal, an empty slot
    double value{0.0};
  };
  bool regular_;
  motion::RegularWaveMoment wave_;
  std::unique_ptr<Sea> sea_;
  mutable std::array<Memo, 4> memo_{};
  mutable std::size_t next_memo_{0};
};

using ShipInSea = ShipInSeaOf<SeaMoment>;

class ShipRollDamperDevice {
 public:
  // The runtime guard's names (tools/run/state_guard.hpp): the stabilized ship, then the locked reference.
  static constexpr int kGuardedStates = 8;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"roll_rad",           "precession_rad",           "roll_rate_rad_s",
                                 "precession_rate_rad_s", "reference_roll_rad",     "reference_precession_rad",
                                 "reference_roll_rate_rad_s", "reference_precession_rate_rad_s"};
    return n[i];
  }
  double state_value(int i) const { return i < 4 ? x_[i] : x_ref_[i - 4]; }

  explicit ShipRollDamperDevice(const ShipScene& s)
      : s_(s),
        sea_(s.sea, s.loop.tick_s() / s.loop.substeps, s.loop.seed, s.ship.c),
        plant_{models::ShipRollDamper(s.ship), &sea_, 0.0, 0.0},
        reference_{models::ShipRollDamper(locked(s.ship)), &sea_, 0.0, 0.0},
        integ_(plant_),
        ref_integ_(reference_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        ref_driver_(ref_integ_, s.loop.tick_ns, s.loop.substeps),
        encoder_({s.sensors.encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kIncremental,
                  sensors::EncoderParams::Rounding::kNearest}),
        roll_angle_noise_({s.sensors.roll_angle_noise_rad * std::sqrt(s.loop.tick_s()), 0.0, 0.0}, s.loop.tick_s()),
        roll_rate_noise_({s.sensors.roll_rate_noise_density, s.sensors.roll_rate_bias, 0.0}, s.loop.tick_s()),
        precession_rate_noise_({s.sensors.precession_rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
        rng_angle_(s.loop.seed, kRollAngleStream),
        rng_rate_(s.loop.seed, kRollRateStream),
        rng_precession_(s.loop.seed, kPrecessionRateStream),
        controller_(std::make_unique<Controller>(s.controller)),
        settle_tick_(static_cast<std::int64_t>(s.settle_s / s.loop.tick_s())) {
    x_.setZero();
    x_ref_.setZero();
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    f.carrier_angle_rad[msg::kRoll] = x_[0] + roll_angle_noise_.sample(rng_angle_);
    f.carrier_rate_rad_s[msg::kRoll] = x_[2] + roll_rate_noise_.sample(rng_rate_);
    const std::int64_t counts = encoder_.counts(x_[1]);
    f.encoder_count[msg::kAxis2] = static_cast<std::int32_t>(counts);
    f.gimbal_angle_rad[msg::kAxis2] = encoder_.angle_of(counts);
    f.gimbal_rate_rad_s[msg::kAxis2] = x_[3] + precession_rate_noise_.sample(rng_precession_);
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.command_Nm = cmd.gimbal_torque_Nm[msg::kAxis2];
    // The bearing's own d2 is in the model (ShipRollDamper applies −d2 β'); only the controller's brake here.
    plant_.brake_Nms = std::clamp(cmd.precession_brake, 0.0, 1.0) * s_.brake_full_Nms;
  }

  void advance(std::int64_t tick) {
    window_.before_tick(tick, x_, {plant_.command_Nm, plant_.brake_Nms});
    driver_.advance_tick(tick, x_);
    window_.after_tick(tick, x_);
    ref_driver_.advance_tick(tick, x_ref_);
    if (tick + 1 >= settle_tick_) {
      roll_.add(x_[0]);
      roll_ref_.add(x_ref_[0]);
    }
    precession_peak_ = std::fmax(precession_peak_, std::fabs(x_[1]));
    torque_peak_ = std::fmax(torque_peak_, std::fabs(plant_.command_Nm));
    roll_rate_peak_ = std::fmax(roll_rate_peak_, std::fabs(x_[2]));
    precession_rate_peak_ = std::fmax(precession_rate_peak_, std::fabs(x_[3]));
    penetration_peak_ = std::fmax(penetration_peak_, std::fabs(x_[1]) - s_.ship.beta_stop);
  }

  bool finite() const { return x_.allFinite() && x_ref_.allFinite(); }
  const ShipInSea& plant() const { return plant_; }  // the accuracy study's input tap
  const ShipInSea::State& state() const { return x_; }

  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): the stabilized ship over 10 s from
  // the start of the statistics (or the run's middle, if shorter).
  nlohmann::json error_estimate() const {
    const auto apply = [](ShipInSea& p, const ShipRollDamperStudySetup::TickInputs& in) {
      p.command_Nm = in.command_Nm;
      p.brake_Nms = in.brake_Nms;
    };
    return window_.estimate<dynamics::Rk4>(plant_, apply, s_.loop.tick_ns, s_.loop.substeps, 4,
                                           {"roll_rad", "precession_rad", "roll_rate_rad_s", "precession_rate_rad_s"},
                                           "none watched: sea, brake, control and roll damping act");
  }

  static std::vector<std::string> columns() {
    return {"roll_rad", "roll_unstabilized_rad", "precession_rad", "roll_rate_rad_s", "precession_rate_rad_s",
            "wave_moment_Nm", "precession_torque_Nm", "status_bits"};
  }
  void record(double* row) const {
    const double t = 1e-9 * static_cast<double>((static_cast<std::int64_t>(last_.tick) + 1) * s_.loop.tick_ns);
    row[0] = x_[0];
    row[1] = x_ref_[0];
    row[2] = x_[1];
    row[3] = x_[2];
    row[4] = x_[3];
    row[5] = sea_(t);
    row[6] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[7] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const double reduction = roll_ref_.rms() > 0 ? roll_.rms() / roll_ref_.rms() : 0.0;
    return {{"roll_rms_rad", roll_.rms()},
            {"roll_rms_unstabilized_rad", roll_ref_.rms()},
            {"roll_reduction", reduction},
            {"roll_max_rad", roll_.peak},
            {"roll_max_unstabilized_rad", roll_ref_.peak},
            {"precession_max_rad", precession_peak_},
            {"precession_torque_max_Nm", torque_peak_},
            {"wave_moment_rms_Nm", sea_.rms()},
            {"statistics_from_s", s_.settle_s},
            {"stop_penetration_max_rad", std::fmax(penetration_peak_, 0.0)},
            {"stop_penetration_bound_rad", stop_penetration_bound()}};
  }

  // report.json "plant": what the loop assembled. The gyro is (14.8) with its large-angle terms — both
  // inertias (roll A, case B), so nutation and precession; no reduced model is offered: for a ship gyro
  // the two are not separated (ω_N = H/sqrt(AB) = 1.5 rad/s against the roll's 0.6 rad/s for the digest's
  // ship, ε = O(1)), the condition under which precession theory P0 holds (digest §8) fails.
  nlohmann::json report_extra() const {
    nlohmann::json parts = nlohmann::json::array({"ship roll + gyro case precession (14.8), large-angle terms",
                                                  "precession end stops (spring-damper)",
                                                  "locked reference ship in the same sea"});
    if (s_.ship.H == 0.0) parts[0] = "ship roll + gyro case (14.8) with H = 0: no gyroscopic coupling";
    if (s_.ship.w > 0.0) parts.push_back("wall-sided righting arm");
    if (s_.ship.d1 > 0.0 || s_.ship.d2 > 0.0) parts.push_back("viscous roll / precession damping");
    parts.push_back(s_.sea.regular ? "regular sea (14.9)" : "irregular sea");
    if (s_.sensors.roll_angle_noise_rad > 0.0 || s_.sensors.roll_rate_noise_density > 0.0 ||
        s_.sensors.precession_rate_noise_density > 0.0 || s_.sensors.roll_rate_bias != 0.0) {
      parts.push_back("sensor noise");
    }
    return {{"plant",
             {{"model", models::ShipRollDamper::kName},
              {"fidelity", "full (14.8): no reduced model (epsilon = O(1) for a ship gyro)"},
              {"components", parts},
              {"mechanical_states", 4},
              {"reference_ship_states", 4},
              {"state_size", 8},
              {"device_bytes", sizeof(ShipRollDamperDevice)},
              {"integrator", "rk4"},
              {"plant_substeps", s_.loop.substeps}}}};
  }
  // Largest penetration of the end stops the run's peaks allow (models/ship_roll_damper.hpp: k_s = B ω_s²,
  // ζ_s): the quasi-static push into the stop, (H |φ'|max + |M2|max + |Q| φ'²max/2)/k_s, plus the impact at |β'|max, whose
  // largest excursion in a spring-damper is |β'|/ω_s, or |β'|/(e ω_s) for ζ_s ≥ 1 (the force is clipped at
  // zero, which can only shorten the excursion; the pendulum moment q pushes out of the stop and is left out).
  double stop_penetration_bound() const {
    const auto& p = s_.ship;
    const double ks = p.B * p.stop_frequency * p.stop_frequency;
    const double impact = precession_rate_peak_ / p.stop_frequency * (p.stop_damping_ratio >= 1.0 ? std::exp(-1.0) : 1.0);
    const double inertial = 0.5 * std::abs(p.Q) * roll_rate_peak_ * roll_rate_peak_;  // |Q sinβ cosβ φ'²|
    return (p.H * roll_rate_peak_ + torque_peak_ + inertial) / ks + impact;
  }

 private:
  static models::ShipRollDamperParams locked(models::ShipRollDamperParams p) {
    p.locked = true;
    return p;
  }

  const ShipScene& s_;
  SeaMoment sea_;
  ShipInSea plant_, reference_;
  dynamics::Rk4<ShipInSea> integ_, ref_integ_;
  dynamics::SubstepDriver<dynamics::Rk4<ShipInSea>> driver_, ref_driver_;
  ShipInSea::State x_, x_ref_;
  sensors::Encoder encoder_;
  sensors::SensorNoise roll_angle_noise_, roll_rate_noise_, precession_rate_noise_;
  random::SeededRng rng_angle_, rng_rate_, rng_precession_;
  std::unique_ptr<Controller> controller_;
  std::int64_t settle_tick_;
  msg::ActuatorFrame last_{};
  RunningStats roll_, roll_ref_;
  double precession_peak_{0.0}, torque_peak_{0.0};
  double roll_rate_peak_{0.0}, precession_rate_peak_{0.0}, penetration_peak_{-1e300};
  accuracy::HalfStepWindow<ShipInSea, ShipRollDamperStudySetup::TickInputs> window_{
      std::min(settle_tick_, s_.loop.ticks() / 2), static_cast<std::int64_t>(10.0 / s_.loop.tick_s())};
};

bool read_scene(SceneReader& r, ShipScene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  auto& p = s.ship;
  p.A = r.required("ship", "A", Range::positive(), "roll inertia of ship + installation [kg m²]");
  p.c = r.required("ship", "c", Range::positive(), "roll stiffness m g GM [N m/rad]");
  p.d1 = r.number("ship", "d1", 0.0, Range::non_negative(), "roll damping [N m s/rad]");
  p.w = r.number("ship", "w", 0.0, Range::non_negative(), "wall-sided coefficient BM/(2 GM) [-]");
  p.B = r.required("gyro", "B", Range::positive(), "case + rotor inertia about the precession axis [kg m²]");
  p.Q = r.number("gyro", "Q", 0.0, Range::any(), "A^R + A^J - C^J of (10.4) [kg m²]");
  p.q = r.required("gyro", "q", Range::non_negative(), "pendulous stiffness of the case G s [N m/rad]");
  p.d2 = r.number("gyro", "d2", 0.0, Range::non_negative(),
                  "viscous friction of the precession bearing (the brake is the controller's) [N m s/rad]");
  // H = 0 is a gyro without spin (zero-spin case, docs/extreme.md): the case is a pendulum, no damping.
  p.H = r.required("gyro", "H", Range::non_negative(), "rotor spin momentum [N m s]");
  p.beta_stop = kDeg * r.number("gyro", "beta_stop_deg", 70.0, Range::open_closed(0.0, 89.0),
                                "hard end stops of the precession angle [deg]");
  p.stop_frequency = r.number("gyro", "stop_frequency", 100.0, Range::positive(), "end-stop stiffness sqrt(k/B) [rad/s]");
  p.stop_damping_ratio = r.number("gyro", "stop_damping_ratio", 1.0, Range::non_negative(), "end-stop damping [-]");
  s.brake_full_Nms = r.number("gyro", "brake_full_Nms", 1e7, Range::positive(),
                              "brake at precession_brake = 1 (safe state) [N m s/rad]");
  // Relations between keys only once each key is valid (a missing key reads as NaN and would trip them too).
  if (r.ok()) {
    if (const char* why = p.invalid_reason()) r.fail("ship", "A", why);
  }

  const std::string kind = r.choice("sea", "kind", "jonswap", {"regular", "pierson_moskowitz", "jonswap"}, "wave model");
  s.sea.regular = kind == "regular";
  if (s.sea.regular) {
    s.sea.wave.E0 = r.required("sea", "E0", Range::non_negative(), "wave moment amplitude (14.9) [N m]");
    s.sea.wave.omega = r.required("sea", "omega", Range::positive(), "wave frequency [rad/s]");
  } else {
    s.sea.spectrum.kind = kind == "jonswap" ? motion::WaveSpectrumParams::Kind::kJonswap
                                            : motion::WaveSpectrumParams::Kind::kPiersonMoskowitz;
    s.sea.spectrum.Hs = r.required("sea", "Hs", Range::positive(), "significant wave height [m]");
    s.sea.spectrum.Tp = r.required("sea", "Tp", Range::positive(), "peak period [s]");
    if (kind == "jonswap") {
      s.sea.spectrum.gamma = r.number("sea", "gamma", 3.3, Range::closed(1.0, 10.0), "JONSWAP peak enhancement [-]");
    }
    s.sea.irregular.components = static_cast<int>(r.integer("sea", "components", 64, 1, 256, "harmonic components"));
    s.sea.kappa = r.number("sea", "kappa", 1.0, Range::open_closed(0.0, 2.0), "effective wave-slope coefficient [-]");
    if (const char* why = motion::WaveSpectrum::check(s.sea.spectrum)) r.fail("sea", "Hs", why);
  }

  s.sensors.roll_angle_noise_rad = r.number("sensors", "roll_angle_noise_rad", 1e-4, Range::non_negative(),
                                            "roll angle noise, standard deviation per sample [rad]");
  s.sensors.roll_rate_noise_density = r.number("sensors", "roll_rate_noise_density", 1e-4, Range::non_negative(),
                                               "roll rate gyro noise density [rad/s/sqrt(Hz)]");
  s.sensors.roll_rate_bias = r.number("sensors", "roll_rate_bias", 0.0, Range::closed(-0.1, 0.1),
                                      "roll rate gyro bias [rad/s]");
  s.sensors.precession_rate_noise_density = r.number("sensors", "precession_rate_noise_density", 1e-4,
                                                     Range::non_negative(), "precession rate noise [rad/s/sqrt(Hz)]");
  s.sensors.encoder_counts_per_rev = r.integer("sensors", "encoder_counts_per_rev", 65536, 16, 1 << 30,
                                               "precession encoder resolution [counts/rev]");

  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  const std::string law = r.choice("controller", "law", "active", {"passive", "active"}, "control law");
  c.mode = law == "passive" ? firmware::ShipRollDamperMode::kPassiveBrake : firmware::ShipRollDamperMode::kActive;
  const double torque_limit = r.number("controller", "torque_limit_Nm", 2e5, Range::positive(), "precession torque limit [N m]");
  if (c.mode == firmware::ShipRollDamperMode::kPassiveBrake) {
    c.brake.d2 = r.number("controller", "brake_d2", 4.53e4, Range::non_negative(), "brake coefficient [N m s/rad]");
    c.brake.torque_limit_Nm = torque_limit;
    c.brake.B = p.B;
  } else {
    auto& a = c.active;
    a.B = p.B;
    a.H = p.H;
    a.torque_limit_Nm = torque_limit;
    a.roll_rate_gain = r.number("controller", "roll_rate_gain", p.H, Range::non_negative(),
                                "M2 per rad/s of roll rate [N m s/rad]");
    a.precession_damping = r.number("controller", "precession_damping", 8.36e4, Range::positive(),
                                    "M2 per rad/s of precession rate [N m s/rad]");
    a.centring_stiffness = r.number("controller", "centring_stiffness", 0.0, Range::non_negative(),
                                    "M2 per rad of precession angle [N m/rad]");
    a.beta_soft = kDeg * r.number("controller", "soft_limit_deg", 60.0, Range::open_closed(0.0, 89.0),
                                  "soft limit of the precession angle [deg]");
    a.soft_stiffness = r.number("controller", "soft_stiffness", 5e5, Range::non_negative(), "beyond the soft limit [N m/rad]");
    a.beta_stop = p.beta_stop;
    a.brake_deceleration = r.number("controller", "brake_deceleration", 2.0, Range::positive(),
                                    "end-stop braking deceleration [rad/s²]");
  }
  s.settle_s = r.number("report", "settle_s", std::min(60.0, 0.2 * s.loop.duration_s),
                        Range::closed(0.0, s.loop.duration_s), "statistics start after this time [s]");
  const firmware::ConfigCheck check = Controller::check(c);
  if (!check.ok) r.fail("controller", "law", "refused by the controller's start-up check: " + describe(check));
  r.finish();
  return r.ok();
}

}  // namespace

int run_ship_roll_damper(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<ShipScene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  auto device = std::make_unique<ShipRollDamperDevice>(*scene);
  return run_device(*device, scene->loop, req);
}

}  // namespace gyrostab::tools

// The accuracy study's view of a scene (ship_roll_damper_study.hpp).
namespace gyrostab::tools {

int ship_roll_damper_study_setup(SceneReader& reader, std::int64_t ticks, ShipRollDamperStudySetup& out) {
  auto scene = std::make_unique<ShipScene>();
  if (!read_scene(reader, *scene)) return 2;
  out.loop = scene->loop;
  out.scene_duration_s = scene->loop.duration_s;
  if (ticks >= 0) out.loop.duration_s = static_cast<double>(ticks) * out.loop.tick_s();
  out.ship = scene->ship;
  out.regular_sea = scene->sea.regular;
  out.wave = scene->sea.wave;
  out.spectrum = scene->sea.spectrum;
  out.irregular = scene->sea.irregular;
  out.irregular.grid_period = scene->loop.tick_s() / scene->loop.substeps;  // as SeaMoment sets it
  out.kappa = scene->sea.kappa;
  out.sea_stream = kSeaStream;
  auto device = std::make_unique<ShipRollDamperDevice>(*scene);
  const std::int64_t n = out.loop.ticks();
  out.inputs.reserve(static_cast<std::size_t>(n));
  out.states.reserve(static_cast<std::size_t>(n));
  auto tap = accuracy::make_input_tap(*device, [&out](const ShipRollDamperDevice& d, std::int64_t) {
    out.inputs.push_back({d.plant().command_Nm, d.plant().brake_Nms});
    out.states.push_back(d.state());
  });
  const LoopOutcome o = run_closed_loop(tap, out.loop, nullptr);
  out.closed_loop_wall_s = o.wall_s;
  return o.diverged ? 3 : 0;
}

}  // namespace gyrostab::tools
