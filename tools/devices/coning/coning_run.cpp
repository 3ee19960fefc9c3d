// What a coning run reports: the plant of sim/plants/coning_plant.hpp with its meter — after the settling
// time, over whole vibration periods (rounded to ticks), the platform's drift relative to the base (the slope
// between its azimuth averaged over the first and over the last period), its mean absolute rate about axis
// 3 and the gyro's mean reading (nulled by the loop), beside the open-loop coning rate of the book, the
// first-order rate through the gyro's response, and the closed-loop prediction (sim/oracles/
// coning_closed_forms.hpp). The CSV columns, the half-step error estimate, and the scene's plant and
// controller for the run modes.
#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/coning_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/oracles/coning_closed_forms.hpp"
#include "tools/devices/coning/coning_scene.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::ConingPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicConingController<firmware::posix::MonotonicClock>;

// Sums over one block of samples (a vibration period in ticks).
struct BlockSums {
  double phi{0.0}, theta{0.0};
};

// A base whose axis 3 runs round a cone about the world's axis 3 at a constant rate: `prescribed` with a
// constant pitch, a yaw rate and no harmonic, roll or vibration (the Goodman–Robinson setting).
struct Cone {
  bool applies{false};
  double half_angle{0.0}, yaw_rate{0.0}, period_s{0.0};
};
Cone cone_of(const motion::SceneBaseMotion& b) {
  const auto& p = b.prescribed;
  if (b.kind != motion::BaseMotionKind::kPrescribed || b.vibration.count > 0 || p.yaw.count > 0 ||
      p.pitch.count > 0 || p.roll.count > 0 || p.roll.offset != 0.0 || p.roll.rate != 0.0 || p.pitch.rate != 0.0 ||
      p.yaw.rate == 0.0)
    return {};
  return {true, p.pitch.offset, p.yaw.rate, 2.0 * std::numbers::pi / std::fabs(p.yaw.rate)};
}

class ConingRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::coning::Record;

  explicit ConingRun(const ConingScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        settle_tick_(static_cast<std::int64_t>(std::llround(s.settle_s / s.loop.tick_s()))),
        per_(std::max<std::int64_t>(
            1, std::llround(2.0 * std::numbers::pi / (s.plant.platform.frequency * s.loop.tick_s())))),
        cone_(cone_of(s.plant.base)),
        circuit_ticks_(cone_.applies ? std::llround(cone_.period_s / s.loop.tick_s()) : 0),
        window_(std::min(settle_tick_, s.loop.ticks() / 2), per_) {}

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
    if (ticks_ == settle_tick_) phi_at_settle_ = plant_.phi_rad();
    if (cone_.applies && ticks_ == settle_tick_ + circuit_ticks_) phi_after_circuit_ = plant_.phi_rad();
    if (ticks_ < settle_tick_) return;
    const double phi = plant_.phi_rad();
    const double g = s_.plant.platform.gyro.gyro.d2 / s_.plant.platform.gyro.gyro.H;
    block_.phi += phi;
    block_.theta += g * plant_.beta_rad();  // the I-gyro's angle reading (unused for a P-gyro)
    run_cos_ += std::cos(phi);
    run_rate_ += plant_.platform_rate_rad_s(plant_.tick_time(ticks_))[2];
    run_reading_ += plant_.indicated();
    max_beta_ = std::max(max_beta_, std::fabs(plant_.beta_rad()));
    if (++in_block_ == per_) {
      if (blocks_ == 0) first_ = block_;
      last_block_ = block_;
      ++blocks_;
      done_cos_ = run_cos_;
      done_rate_ = run_rate_;
      done_reading_ = run_reading_;
      block_ = {};
      in_block_ = 0;
    }
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.phi_rad = plant_.phi_rad();
    r.phi_rate_rad_s = plant_.phi_rate_rad_s();
    r.platform_rate_rad_s = plant_.platform_rate_rad_s(plant_.tick_time(ticks_))[2];
    r.beta_rad = plant_.beta_rad();
    r.reading = plant_.indicated();
    r.drive_voltage_V = plant_.held_inputs().voltage;
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const models::ConingPlatformParams& m = s_.plant.platform;
    const sensors::SingleAxisGyroParams& g = m.gyro.gyro;
    const bool p_gyro = g.c2 > 0.0;
    const double O1 = m.Omega10(), O3 = m.Omega30(), nu = m.frequency, eps = m.phase;
    const double book = p_gyro ? oracles::coning_rate_p_book(g.H, g.c2, O1, O3) * std::cos(eps)
                               : oracles::coning_rate_i_ideal(g.H, g.d2, O1, O3, nu, eps);
    const double first = oracles::coning_rate_first_order(m.gyro, O1, O3, nu, eps);
    const firmware::ConingNullParams& law = s_.controller.law;
    const double T = s_.loop.tick_s();
    const std::complex<double> S = oracles::coning_loop_sensitivity(
        m.gyro, law.kp, law.ki, m.drive_time_constant, (s_.loop.latency_ticks + 0.5) * T, nu);
    nlohmann::json f{{"gyro_kind", p_gyro ? "P" : "I"},
                     {"Omega10_input_rad_s", O1},
                     {"Omega30_spin_rad_s", O3},
                     {"coning_rate_book_rad_s", book},
                     {"coning_rate_first_order_rad_s", first},
                     {"loop_sensitivity_abs", std::abs(S)},
                     {"vibration_period_s", 2.0 * std::numbers::pi / nu},
                     {"periods", blocks_},
                     {"statistics_from_s", s_.settle_s},
                     {"ticks", ticks_}};
    goodman_robinson_figures(f);
    const char* measured[] = {"drift_rate_rad_s",      "drift_predicted_rad_s", "drift_predicted_sampled_rad_s",
                              "drift_rel_error_vs_prediction_sampled", "loop_sensitivity_sampled_abs",
                              "drift_rel_error_vs_book",
                              "drift_rel_error_vs_prediction", "platform_mean_rate_rad_s",
                              "gyro_mean_reading_rad_s", "mean_cos_phi",        "max_abs_beta_rad"};
    if (blocks_ < 2) {  // fewer than two whole periods after settling (a short run)
      for (const char* key : measured) f[key] = nullptr;
      return f;
    }
    const double n = static_cast<double>(blocks_ * per_), span = static_cast<double>((blocks_ - 1) * per_) * T;
    const double drift = (last_block_.phi - first_.phi) / static_cast<double>(per_) / span;
    const std::complex<double> S_sampled = oracles::coning_loop_sensitivity_sampled(
        m.gyro, law.kp, law.ki, m.drive_time_constant, s_.controller.runtime.control_period_s(),
        static_cast<double>(s_.loop.latency_ticks) * T / s_.controller.runtime.control_period_s(), nu);
    const double mean_cos = done_cos_ / n;
    const double predicted = -oracles::coning_rate_first_order(m.gyro, O1, O3 * mean_cos, nu, eps, S);
    // A relative error whose reference is 0 (no vibration, or none the book's form sees) has no value: null.
    const auto rel = [drift](double ref) { return ref != 0.0 ? nlohmann::json(drift / ref - 1.0) : nlohmann::json(); };
    f["drift_rate_rad_s"] = drift;
    f["drift_predicted_rad_s"] = predicted;
    f["drift_rel_error_vs_book"] = rel(-book);
    f["drift_rel_error_vs_prediction"] = rel(predicted);
    const double predicted_sampled = -oracles::coning_rate_first_order(m.gyro, O1, O3 * mean_cos, nu, eps, S_sampled);
    f["drift_predicted_sampled_rad_s"] = predicted_sampled;
    f["drift_rel_error_vs_prediction_sampled"] = rel(predicted_sampled);
    f["loop_sensitivity_sampled_abs"] = std::abs(S_sampled);
    f["platform_mean_rate_rad_s"] = done_rate_ / n;
    f["gyro_mean_reading_rad_s"] =
        p_gyro ? done_reading_ / n : (last_block_.theta - first_.theta) / static_cast<double>(per_) / span;
    f["mean_cos_phi"] = mean_cos;
    f["max_abs_beta_rad"] = max_beta_;
    return f;
  }

  // The Goodman–Robinson theorem, Magnus (15.30)-(15.35): a base whose axis 3 runs round a cone of half-angle
  // ϑ about the world's axis 3 (prescribed: constant pitch ϑ, constant yaw rate ψ', nothing else) carries the
  // platform slaved to zero rate about that axis; over one circuit T = 2π/|ψ'| the platform turns relative to
  // the base by A − 2πn, A = ∮(1 − cos ϑ)dψ = sgn(ψ') 2π(1 − cos ϑ), n = sgn(ψ'): −sgn(ψ') 2π cos ϑ (15.35:
  // a level platform on the Earth at latitude λ = 90° − ϑ, a sidereal day, −2π sin λ). Measured: φ after
  // settle_s and one circuit later (the ticks nearest T), against the theorem over the same span.
  void goodman_robinson_figures(nlohmann::json& f) const {
    if (!cone_.applies) return;
    const double span = static_cast<double>(circuit_ticks_) * s_.loop.tick_s();
    const double per_circuit = -std::copysign(2.0 * std::numbers::pi, cone_.yaw_rate) * std::cos(cone_.half_angle);
    const double predicted = per_circuit * span / cone_.period_s;
    const bool measured = settle_tick_ + circuit_ticks_ <= ticks_;
    const double turn = phi_after_circuit_ - phi_at_settle_;
    f["goodman_robinson"] = {
        {"cone_half_angle_rad", cone_.half_angle},
        {"latitude_rad", std::numbers::pi / 2 - cone_.half_angle},
        {"circuit_s", cone_.period_s},
        {"enclosed_area_sr", std::copysign(2.0 * std::numbers::pi, cone_.yaw_rate) * (1.0 - std::cos(cone_.half_angle))},
        {"turn_per_circuit_book_rad", per_circuit},
        {"span_s", span},
        {"from_s", static_cast<double>(settle_tick_) * s_.loop.tick_s()},
        {"turn_rad_predicted", predicted},
        {"turn_rad", measured ? nlohmann::json(turn) : nlohmann::json()},
        {"turn_rel_error", measured && predicted != 0.0 ? nlohmann::json(turn / predicted - 1.0) : nlohmann::json()},
        {"turn_error_rad", measured ? nlohmann::json(turn - predicted) : nlohmann::json()}};
  }

  // report.json "error_estimate": one vibration period from the end of settling.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics& m, const Plant::HeldInputs& in) { m.inputs.voltage = in.voltage; };
    return error_estimate_json<4>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"phi_rad", "phi_rate_rad_s", "beta_rad", "beta_rate_rad_s"},
        "none watched: the drive and the gyro's damper act");
  }

 private:
  const ConingScene& s_;
  Plant plant_;
  std::int64_t settle_tick_;
  std::int64_t per_;
  ActuatorFrame last_{};
  BlockSums block_{}, first_{}, last_block_{};
  std::int64_t in_block_{0}, blocks_{0};
  double run_cos_{0.0}, run_rate_{0.0}, run_reading_{0.0};     // over all samples so far
  double done_cos_{0.0}, done_rate_{0.0}, done_reading_{0.0};  // at the last completed period
  double max_beta_{0.0};
  Cone cone_;
  std::int64_t circuit_ticks_{0};
  double phi_at_settle_{0.0}, phi_after_circuit_{0.0};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
};

struct ConingTraits {
  using Scene = ConingScene;
  using Binding = ConingRun;
  using Controller = tools::Controller;
  // What moves the base (the vibration generator or the scene's [motion]): `gyrostab motion-record` writes it.
  static const motion::SceneBaseMotion* base_motion(const Scene& s) { return &s.plant.base; }
  // The drive's supply (the only command).
  static hil::ActuatorLimits actuator_limits(const Scene& s) {
    msg::coning::ActuatorFrame l = hil::ActuatorLimits::unlimited<msg::coning::ActuatorFrame>();
    l.drive_voltage_V = s.plant.voltage_limit;
    return hil::ActuatorLimits::of(l);
  }
  static nlohmann::json limits(const Scene& s) { return {{"drive_voltage_limit_V", s.plant.voltage_limit}}; }
};

}  // namespace

std::unique_ptr<DeviceScene> make_coning_scene(std::unique_ptr<ConingScene> s) {
  return std::make_unique<DeviceSceneOf<ConingTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
