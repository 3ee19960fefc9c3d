// Scene binding of the two-axis power gyro stabilizer (Magnus §14.3, (14.19)-(14.25)): the full nonlinear
// gimbal gyro with torque motors on both axes (sim/models/power_stabilizer.hpp) on a rolling base, disturbance
// torque steps, encoders and rate gyros, and the firmware's stabilization loops with rate damping
// (firmware/app/power_stabilizer_controller.hpp, gains checked against (14.25) at start-up). The plant step is
// checked against the nutation before running (sim/dynamics/step_validation.hpp).
// Figures: the closed loop's nutation frequency and decay rate measured from α'(t) after the first
// disturbance step, beside the roots of the characteristic equation (14.23) (`_predicted`); the steady
// deflections under the constant disturbances beside (14.21). Keys: docs/scenes.md#power_stabilizer.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>

#include "firmware/app/power_stabilizer_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/power_stabilizer.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/devices/running_stats.hpp"
#include "tools/devices/scene_device.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/run/nutation_meter.hpp"

namespace gyrostab::tools {
namespace {

using Plant = models::PowerStabilizer<models::HarmonicBaseRotation>;
using Controller = firmware::BasicPowerStabilizerController<firmware::posix::MonotonicClock>;
enum Stream : std::uint64_t { kRateStream1 = 1, kRateStream2 };

struct Disturbance {
  double M1{0.0}, M2{0.0};    // step heights on axis 1 / axis 2 [N m]
  double t1{1.0}, t2{1.0};    // step times [s]
};

struct PowerScene {
  LoopConfig loop;
  models::GimbalGyroParams gyro;
  double H{200.0};
  models::HarmonicBaseRotation base{};
  Disturbance disturbance;
  double rate_noise_density{1e-4};
  std::int64_t encoder_counts_per_rev{1 << 18};
  firmware::PowerStabilizerControllerConfig controller;
  double measure_window_s{1.5};
};

// Roots of (14.23) with the total damping (commanded + bearings): AB λ⁴ + (A d2 + B d1) λ³ + (H² + d1 d2) λ²
// + H (k1 + k2) λ + k1 k2 = 0. Returns the pair with the largest |Im| (the nutation).
std::complex<double> nutation_root(const PowerScene& s) {
  const double A = s.gyro.A(), B = s.gyro.B(), H = s.H;
  const auto& l = s.controller.loops;
  const double d1 = l.d1 + s.gyro.d1, d2 = l.d2 + s.gyro.d2;
  const double c[5] = {A * B, A * d2 + B * d1, H * H + d1 * d2, H * (l.k1 + l.k2), l.k1 * l.k2};
  Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 4; ++i) companion(0, i) = -c[i + 1] / c[0];
  for (int i = 1; i < 4; ++i) companion(i, i - 1) = 1.0;
  Eigen::EigenSolver<Eigen::Matrix4d> es(companion, false);
  std::complex<double> best{0.0, 0.0};
  for (int i = 0; i < 4; ++i) {
    if (std::abs(es.eigenvalues()[i].imag()) > std::abs(best.imag())) best = es.eigenvalues()[i];
  }
  return {best.real(), std::abs(best.imag())};
}

template <template <class> class Integrator>
class PowerStabilizerDevice {
 public:
  explicit PowerStabilizerDevice(const PowerScene& s)
      : s_(s),
        plant_(s.gyro, models::TorqueMotors{}, models::RigidStructure{}, s.base),
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        encoder_({s.encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kIncremental,
                  sensors::EncoderParams::Rounding::kNearest}),
        noise1_({s.rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
        noise2_({s.rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
        rng1_(s.loop.seed, kRateStream1),
        rng2_(s.loop.seed, kRateStream2),
        controller_(std::make_unique<Controller>(s.controller)),
        meter_(std::min(s.disturbance.t1, s.disturbance.t2) + 0.02,
               std::min(s.disturbance.t1, s.disturbance.t2) + s.measure_window_s) {
    x_ = Plant::make_state(0.0, 0.0, 0.0, 0.0, s.H);
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    f = msg::SensorFrame{};
    f.tick = static_cast<std::uint64_t>(tick);
    f.time_ns = tick * s_.loop.tick_ns;
    f.sample_time_ns = f.time_ns;
    f.sequence = static_cast<std::uint32_t>(tick);
    const std::int64_t c1 = encoder_.counts(x_[0]), c2 = encoder_.counts(x_[1]);
    f.encoder_count[msg::kAxis1] = static_cast<std::int32_t>(c1);
    f.encoder_count[msg::kAxis2] = static_cast<std::int32_t>(c2);
    f.gimbal_angle_rad[msg::kAxis1] = encoder_.angle_of(c1);
    f.gimbal_angle_rad[msg::kAxis2] = encoder_.angle_of(c2);
    f.gimbal_rate_rad_s[msg::kAxis1] = x_[2] + noise1_.sample(rng1_);
    f.gimbal_rate_rad_s[msg::kAxis2] = x_[3] + noise2_.sample(rng2_);
    f.rotor_speed_rad_s = x_[4] / s_.gyro.CR;
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.inputs.M1K = cmd.gimbal_torque_Nm[msg::kAxis1];
    plant_.inputs.M2K = cmd.gimbal_torque_Nm[msg::kAxis2];
  }

  void advance(std::int64_t tick) {
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    plant_.inputs.M1S = t >= s_.disturbance.t1 ? s_.disturbance.M1 : 0.0;
    plant_.inputs.M2S = t >= s_.disturbance.t2 ? s_.disturbance.M2 : 0.0;
    driver_.advance_tick(tick, x_);
    meter_.add(t + s_.loop.tick_s(), x_[2]);
    alpha_.add(x_[0]);
    beta_.add(x_[1]);
  }

  bool finite() const { return x_.allFinite(); }

  static std::vector<std::string> columns() {
    return {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s", "M1_motor_Nm", "M2_motor_Nm",
            "M1_disturbance_Nm", "M2_disturbance_Nm", "status_bits"};
  }
  void record(double* row) const {
    row[0] = x_[0];
    row[1] = x_[1];
    row[2] = x_[2];
    row[3] = x_[3];
    row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
    row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[6] = plant_.inputs.M1S;
    row[7] = plant_.inputs.M2S;
    row[8] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const std::complex<double> root = nutation_root(s_);
    const auto& l = s_.controller.loops;
    const firmware::GainCheck g = firmware::check_power_stabilizer_gains(l);
    nlohmann::json f{{"nutation_frequency_rad_s_predicted", root.imag()},
                     {"nutation_decay_rate_per_s_predicted", -root.real()},
                     // (14.21) holds on a base at rest; on a rolling base the gimbal angles (relative to the
                     // base) also carry the base motion.
                     {"steady_alpha_rad_predicted", l.k2 != 0.0 ? -s_.disturbance.M2 / l.k2 : 0.0},
                     {"steady_beta_rad_predicted", l.k1 != 0.0 ? s_.disturbance.M1 / l.k1 : 0.0},
                     {"steady_alpha_rad", x_[0]},
                     {"steady_beta_rad", x_[1]},
                     {"alpha_max_rad", alpha_.peak},
                     {"beta_max_rad", beta_.peak},
                     {"gain_margin", g.gain_scale_max},
                     {"k_max_equal_Nm_per_rad", g.k_max_equal},
                     {"open_loop_nutation_rad_s", s_.H / std::sqrt(s_.gyro.A() * s_.gyro.B())}};
    if (meter_.valid()) {
      f["nutation_frequency_rad_s"] = meter_.angular_frequency();
      f["nutation_decay_rate_per_s"] = -meter_.growth_rate();
    } else {
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_decay_rate_per_s"] = nullptr;
    }
    return f;
  }

 private:
  const PowerScene& s_;
  Plant plant_;
  Integrator<Plant> integ_;
  dynamics::SubstepDriver<Integrator<Plant>> driver_;
  Plant::State x_;
  sensors::Encoder encoder_;
  sensors::SensorNoise noise1_, noise2_;
  random::SeededRng rng1_, rng2_;
  std::unique_ptr<Controller> controller_;
  NutationMeter meter_;
  msg::ActuatorFrame last_{};
  RunningStats alpha_, beta_;
};

bool read_scene(SceneReader& r, PowerScene& s) {
  s.loop = read_loop_config(r, "gyro-exponential", {"gyro-exponential", "rk4"});
  auto& g = s.gyro;
  g.CR = r.required("gyro", "CR", Range::positive(), "rotor axial moment C^R [kg m²]");
  g.AR = r.required("gyro", "AR", Range::positive(), "rotor transverse moment A^R [kg m²]");
  g.AJ = r.number("gyro", "AJ", 0.0, Range::non_negative(), "inner gimbal A^J [kg m²]");
  g.BJ = r.number("gyro", "BJ", 0.0, Range::non_negative(), "inner gimbal B^J [kg m²]");
  g.CJ = r.number("gyro", "CJ", 0.0, Range::non_negative(), "inner gimbal C^J [kg m²]");
  g.AA = r.number("gyro", "AA", 0.0, Range::non_negative(), "outer gimbal / platform about axis 1 [kg m²]");
  g.d1 = r.number("gyro", "d1", 0.0, Range::non_negative(), "outer bearing viscous friction [N m s/rad]");
  g.d2 = r.number("gyro", "d2", 0.0, Range::non_negative(), "inner bearing viscous friction [N m s/rad]");
  const double rpm = r.required("gyro", "rpm", Range::positive(), "rotor speed [rpm]");
  s.H = g.CR * rpm * 2.0 * std::numbers::pi / 60.0;
  // Inertia triangle (1.10) for the rotor: 2 A^R >= C^R for a body of revolution.
  if (!(2.0 * g.AR >= g.CR)) r.fail("gyro", "AR", "rotor inertia triangle violated: need 2 A^R >= C^R (Magnus (1.10))");

  const double roll = r.number("base", "roll_amplitude_rad", 0.0, Range::closed(0.0, 0.5), "base roll amplitude [rad]");
  const double freq = r.number("base", "roll_frequency_rad_s", 0.6, Range::positive(), "base roll frequency [rad/s]");
  const std::int64_t axis = r.integer("base", "roll_axis", 1, 1, 2, "base axis the roll is about");
  s.base = models::HarmonicBaseRotation{axis == 1 ? dynamics::Vec3::UnitX() : dynamics::Vec3::UnitY(), roll, freq,
                                        dynamics::Vec3::UnitZ()};

  s.disturbance.M1 = r.number("disturbance", "M1_Nm", 0.0, Range::closed(-1e6, 1e6), "torque step on axis 1 [N m]");
  s.disturbance.t1 = r.number("disturbance", "M1_time_s", 1.0, Range::non_negative(), "time of the axis-1 step [s]");
  s.disturbance.M2 = r.number("disturbance", "M2_Nm", 0.0, Range::closed(-1e6, 1e6), "torque step on axis 2 [N m]");
  s.disturbance.t2 = r.number("disturbance", "M2_time_s", 1.0, Range::non_negative(), "time of the axis-2 step [s]");

  s.rate_noise_density = r.number("sensors", "rate_noise_density", 1e-4, Range::non_negative(),
                                  "gimbal rate gyro noise density [rad/s/sqrt(Hz)]");
  s.encoder_counts_per_rev = r.integer("sensors", "encoder_counts_per_rev", 1 << 18, 16, 1 << 30,
                                       "gimbal encoder resolution [counts/rev]");

  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  auto& l = c.loops;
  l.A = g.A();
  l.B = g.B();
  l.H = s.H;
  l.bearing_d1 = g.d1;
  l.bearing_d2 = g.d2;
  l.k1 = r.required("controller", "k1", Range::any(), "M1 per rad of beta (14.19) [N m/rad]");
  l.k2 = r.required("controller", "k2", Range::any(), "M2 per rad of alpha (14.19) [N m/rad]");
  l.d1 = r.number("controller", "d1", 0.0, Range::non_negative(), "commanded rate damping, axis 1 [N m s/rad]");
  l.d2 = r.number("controller", "d2", 0.0, Range::non_negative(), "commanded rate damping, axis 2 [N m s/rad]");
  const double limit = r.number("controller", "torque_limit_Nm", 100.0, Range::positive(), "motor torque limit [N m]");
  l.torque_limit_Nm[0] = l.torque_limit_Nm[1] = limit;
  s.measure_window_s = r.number("report", "nutation_window_s", 1.5, Range::positive(),
                                "window after the first disturbance step for the nutation measurement [s]");
  if (r.ok()) {
    const firmware::ConfigCheck check = Controller::check(c);
    if (!check.ok) r.fail("controller", "k1", "refused by the controller's start-up check: " + describe(check));
    // The plant step against the nutation (foundation step validation).
    const Plant plant(g, models::TorqueMotors{}, models::RigidStructure{}, s.base);
    const dynamics::Mode mode = dynamics::fastest_mode(plant, 0.0, Plant::make_state(0, 0, 0, 0, s.H));
    const auto method = s.loop.integrator == "rk4" ? dynamics::Method::kRk4 : dynamics::Method::kGyroExponential;
    const dynamics::StepCheck step = dynamics::check_step(method, mode, s.loop.tick_s() / s.loop.substeps);
    if (!step.ok) r.fail("loop", "plant_substeps", step.message);
  }
  r.finish();
  return r.ok();
}

template <template <class> class Integrator>
int run_with(const PowerScene& scene, const RunRequest& req) {
  auto device = std::make_unique<PowerStabilizerDevice<Integrator>>(scene);
  Recorder rec(PowerStabilizerDevice<Integrator>::columns(), scene.loop.ticks(), scene.loop.record_every);
  const LoopOutcome outcome = run_requested(*device, scene.loop, rec, req);
  nlohmann::json report{{"scene", scene_summary(scene.loop, req.scene_path)},
                        {"figures", device->figures()},
                        {"timing", timing_summary(scene.loop, outcome)}};
  report["timing"]["controller"] = controller_report(device->controller());
  std::string error;
  if (!write_run_outputs(req, scene.loop, rec, report, error)) {
    std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
    return 3;
  }
  if (outcome.diverged) {
    std::fprintf(stderr, "gyrostab: %s: the plant state became non-finite at tick %lld; outputs up to it are written\n",
                 scene.loop.name.c_str(), static_cast<long long>(outcome.diverged_tick));
    return 3;
  }
  return 0;
}

}  // namespace

int run_power_stabilizer(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<PowerScene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  if (scene->loop.integrator == "rk4") return run_with<dynamics::Rk4>(*scene, req);
  return run_with<dynamics::GyroscopicExponential>(*scene, req);
}

}  // namespace gyrostab::tools
