// What a gimbal-error run reports: the plant of sim/plants/gimbal_error_plant.hpp with its meters — the
// largest gimbal errors Δα, Δβ (each gimbal angle against the vehicle angle it nominally reads) and where
// they occur; the simulated angles against the book's closed form of the mounting (12.11), (12.16)-(12.20)
// at the prescribed Euler angles; the integrated attitude against the analytic one; for the heading gyro
// "321" in a level turn the book's (12.14) and its extreme. The CSV columns, the half-step error estimate, and
// the scene's plant and controller for the run modes.
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/gimbal_error_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/oracles/gimbal_error_closed_forms.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/gimbal_error/gimbal_error_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::GimbalErrorPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = GimbalErrorController<firmware::posix::MonotonicClock>;

constexpr const char* kAngleNames[] = {"roll", "pitch", "yaw"};  // by vehicle axis 1^F, 2^F, 3^F

// The largest |error| and the vehicle's attitude where it first occurred.
struct ErrorPeak {
  double abs{-1.0}, value{0.0}, t{0.0}, yaw{0.0}, pitch{0.0}, roll{0.0};
  void add(double e, double t_s, double psi, double theta, double phi) {
    if (std::fabs(e) > abs) *this = {std::fabs(e), e, t_s, psi, theta, phi};
  }
  nlohmann::json json(const char* measures) const {
    return {{"measures", measures},     {"max_abs_rad", abs},   {"at_max_rad", value}, {"time_s", t},
            {"yaw_rad", yaw},           {"pitch_rad", pitch},   {"roll_rad", roll}};
  }
};

// The heading gyro in a level turn at constant bank: the case of (12.13)-(12.15).
bool level_turn_of_heading_gyro(const GimbalErrorScene& s) {
  // [motion] prescribed replaces the [yaw], [pitch], [roll] motion; a record is taken to hold it.
  if (s.plant.gyro.from_motion && s.plant.gyro.motion.kind == motion::BaseMotionKind::kPrescribed) return false;
  const auto still = [](const VehicleAngleKeys& k) { return k.rate == 0.0 && k.amplitude == 0.0; };
  return s.plant.gyro.mounting == models::GimbalMounting::k321 && still(s.pitch) && s.pitch.angle == 0.0 &&
         still(s.roll) && s.yaw.amplitude == 0.0 && s.yaw.rate != 0.0 && std::cos(s.roll.angle) > 0.0;
}

// (12.14) has period π in ψ and is odd about every multiple of 90°: the extremes sit at ±ψ* + nπ. The
// heading's distance from the nearest multiple of 180° (in [0, 90°]) compares with the book's ψ*.
double heading_from_nearest_axis(double psi) {
  return std::fabs(psi - std::numbers::pi * std::round(psi / std::numbers::pi));
}

class GimbalErrorRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::gimbal_error::Record;

  explicit GimbalErrorRun(const GimbalErrorScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        alpha_axis_(models::vehicle_axis_of(s.plant.gyro.mounting, 0)),
        beta_axis_(models::vehicle_axis_of(s.plant.gyro.mounting, 1)),
        level_turn_(level_turn_of_heading_gyro(s)),
        window_(s.loop.ticks() / 2, static_cast<std::int64_t>(1.0 / s.loop.tick_s())) {
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

  void record(Record& r) const {
    r.alpha_rad = plant_.alpha_rad();
    r.beta_rad = plant_.beta_rad();
    r.alpha_error_rad = alpha_error_;
    r.beta_error_rad = beta_error_;
    r.yaw_rad = euler_[2];
    r.pitch_rad = euler_[1];
    r.roll_rad = euler_[0];
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    nlohmann::json f{{"mounting", std::string(models::kGimbalMountingNames[static_cast<int>(s_.plant.gyro.mounting)])},
                     {"alpha_error", alpha_peak_.json(kAngleNames[alpha_axis_])},
                     {"beta_error", beta_peak_.json(kAngleNames[beta_axis_])},
                     {"closed_form_alpha_max_diff_rad", closed_alpha_},
                     {"closed_form_sin_beta_max_diff_rad", closed_sin_beta_},
                     {"closed_form_skipped_near_gimbal_lock", near_lock_},
                     {"attitude_error_max_rad", attitude_error_},
                     {"ticks", ticks_}};
    if (!level_turn_) {
      f["level_turn"] = nullptr;
      return f;
    }
    const oracles::TurnErrorExtreme book = oracles::heading_gyro_turn_error_extreme(s_.roll.angle);
    f["level_turn"] = {{"bank_rad", s_.roll.angle},
                       {"book_extreme_abs_rad", std::fabs(book.error)},
                       {"book_extreme_heading_rad", book.heading},
                       {"measured_extreme_abs_rad", alpha_peak_.abs},
                       {"measured_extreme_heading_rad", heading_from_nearest_axis(alpha_peak_.yaw)},
                       {"formula_12_14_max_diff_rad", turn_formula_diff_}};
    return f;
  }

  // report.json "error_estimate": 1 s of the motion from the run's middle.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics&, const Plant::HeldInputs&) {};
    return error_estimate_json<4>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"q_WF_x", "q_WF_y", "q_WF_z", "q_WF_w"}, "|q_WF| = 1, held by projection");
  }

 private:
  // The meters at the start of tick `tick` (the state just integrated up to it).
  void measure(std::int64_t tick) {
    const double t = plant_.time_s(tick);
    const auto& v = s_.plant.gyro;
    euler_ = v.euler(t);
    const double phi = euler_[0], theta = euler_[1], psi = euler_[2];
    const double alpha = plant_.alpha_rad(), beta = plant_.beta_rad();
    alpha_error_ = plants::wrap_angle(alpha - euler_[static_cast<std::size_t>(alpha_axis_)]);
    beta_error_ = plants::wrap_angle(beta - euler_[static_cast<std::size_t>(beta_axis_)]);
    alpha_peak_.add(alpha_error_, t, psi, theta, phi);
    beta_peak_.add(beta_error_, t, psi, theta, phi);

    const oracles::GimbalClosedForm cf = oracles::gimbal_closed_form(s_.plant.gyro.mounting, psi, theta, phi);
    // Near gimbal lock α is undefined and its closed form ill-conditioned (error ~ ε / cosβ).
    if (std::cos(beta) > 1e-3) {
      closed_alpha_ = std::fmax(closed_alpha_, std::fabs(plants::wrap_angle(alpha - cf.alpha())));
    } else {
      ++near_lock_;
    }
    closed_sin_beta_ = std::fmax(closed_sin_beta_, std::fabs(std::sin(beta) - cf.sin_beta));
    const Plant::State& x = plant_.state();
    const dynamics::Quat q(x[3], x[0], x[1], x[2]);
    attitude_error_ = std::fmax(attitude_error_, q.angularDistance(v.attitude(t)));
    if (level_turn_) {
      turn_formula_diff_ = std::fmax(
          turn_formula_diff_, std::fabs(alpha_error_ - oracles::heading_gyro_turn_error(psi, phi)));
    }
  }

  const GimbalErrorScene& s_;
  Plant plant_;
  int alpha_axis_, beta_axis_;
  bool level_turn_;
  ActuatorFrame last_{};
  std::array<double, 3> euler_{};  // φ, ϑ, ψ at the current state [rad]
  double alpha_error_{0.0}, beta_error_{0.0};
  ErrorPeak alpha_peak_{}, beta_peak_{};
  double closed_alpha_{0.0}, closed_sin_beta_{0.0}, attitude_error_{0.0}, turn_formula_diff_{0.0};
  std::int64_t near_lock_{0};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
};

struct GimbalErrorTraits {
  using Scene = GimbalErrorScene;
  using Binding = GimbalErrorRun;
  using Controller = tools::Controller;
  // What moves the vehicle (the [yaw], [pitch], [roll] generator or the scene's [motion]), for motion-record.
  static const motion::SceneBaseMotion* base_motion(const Scene& s) { return &s.plant.gyro.motion; }
};

}  // namespace

std::unique_ptr<DeviceScene> make_gimbal_error_scene(std::unique_ptr<GimbalErrorScene> s) {
  return std::make_unique<DeviceSceneOf<GimbalErrorTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
