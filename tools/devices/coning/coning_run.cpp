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
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/oracles/coning_closed_forms.hpp"
#include "tools/devices/coning/coning_scene.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/run/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::ConingPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicConingController<firmware::posix::MonotonicClock>;

const std::vector<std::string>& columns() {
  static const std::vector<std::string> c{"phi_rad",   "phi_rate_rad_s", "platform_rate_rad_s", "beta_rad",
                                          "reading",   "drive_voltage_V", "status_bits"};
  return c;
}

// Sums over one block of samples (a vibration period in ticks).
struct BlockSums {
  double phi{0.0}, theta{0.0};
};

class ConingRun {
 public:
  explicit ConingRun(const ConingScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        settle_tick_(static_cast<std::int64_t>(std::llround(s.settle_s / s.loop.tick_s()))),
        per_(std::max<std::int64_t>(
            1, std::llround(2.0 * std::numbers::pi / (s.plant.platform.frequency * s.loop.tick_s())))),
        window_(std::min(settle_tick_, s.loop.ticks() / 2), per_) {}

  void sense(std::int64_t tick, msg::SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    window_.before_tick(tick, plant_.state(), plant_.held_inputs());
    plant_.advance(tick);
    window_.after_tick(tick, plant_.state());
    ticks_ = tick + 1;
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

  void record(double* row) const {
    row[0] = plant_.phi_rad();
    row[1] = plant_.phi_rate_rad_s();
    row[2] = plant_.platform_rate_rad_s(plant_.tick_time(ticks_))[2];
    row[3] = plant_.beta_rad();
    row[4] = plant_.indicated();
    row[5] = plant_.held_inputs().voltage;
    row[6] = static_cast<double>(last_.status);
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
    f["drift_rate_rad_s"] = drift;
    f["drift_predicted_rad_s"] = predicted;
    f["drift_rel_error_vs_book"] = book != 0.0 ? drift / -book - 1.0 : 0.0;
    f["drift_rel_error_vs_prediction"] = predicted != 0.0 ? drift / predicted - 1.0 : 0.0;
    const double predicted_sampled = -oracles::coning_rate_first_order(m.gyro, O1, O3 * mean_cos, nu, eps, S_sampled);
    f["drift_predicted_sampled_rad_s"] = predicted_sampled;
    f["drift_rel_error_vs_prediction_sampled"] = predicted_sampled != 0.0 ? drift / predicted_sampled - 1.0 : 0.0;
    f["loop_sensitivity_sampled_abs"] = std::abs(S_sampled);
    f["platform_mean_rate_rad_s"] = done_rate_ / n;
    f["gyro_mean_reading_rad_s"] =
        p_gyro ? done_reading_ / n : (last_block_.theta - first_.theta) / static_cast<double>(per_) / span;
    f["mean_cos_phi"] = mean_cos;
    f["max_abs_beta_rad"] = max_beta_;
    return f;
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
  msg::ActuatorFrame last_{};
  BlockSums block_{}, first_{}, last_block_{};
  std::int64_t in_block_{0}, blocks_{0};
  double run_cos_{0.0}, run_rate_{0.0}, run_reading_{0.0};     // over all samples so far
  double done_cos_{0.0}, done_rate_{0.0}, done_reading_{0.0};  // at the last completed period
  double max_beta_{0.0};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
};

struct ConingTraits {
  using Scene = ConingScene;
  using Binding = ConingRun;
  using Controller = tools::Controller;
  static std::vector<std::string> columns(const Scene&) { return tools::columns(); }
  // What moves the base (the vibration generator or the scene's [motion]): `gyrostab motion-record` writes it.
  static const motion::SceneBaseMotion* base_motion(const Scene& s) { return &s.plant.base; }
  // The drive's supply on axis 1 (the only command); no torques.
  static hil::ActuatorLimits actuator_limits(const Scene& s) {
    hil::ActuatorLimits l;
    l.torque_Nm[0] = l.torque_Nm[1] = 0.0;
    l.voltage_V[0] = s.plant.voltage_limit;
    l.voltage_V[1] = 0.0;
    l.from_scene = true;
    return l;
  }
  static nlohmann::json limits(const Scene& s) { return {{"drive_voltage_limit_V", s.plant.voltage_limit}}; }
};

}  // namespace

std::unique_ptr<DeviceScene> make_coning_scene(std::unique_ptr<ConingScene> s) {
  return std::make_unique<DeviceSceneOf<ConingTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
