// What a U-gyro run reports: the plant of sim/plants/u_gyro_plant.hpp with its meter — over the whole
// twice-spin periods after the settling time, the output's mean and its component at twice the spin
// frequency (a least-squares fit of mean, trend and the 2γ harmonic against the spin angle γ, which keeps
// the mean out of the harmonic whatever the window: sim/analysis/harmonic_fit.hpp) beside the book's (15.29)
// through the frame's response
// (sim/oracles/u_gyro_output.hpp), and the asymmetry (A^R − B^R)/C^R recovered from the measured amplitude.
// The CSV columns, the half-step error estimate, and the scene's plant and controller for the run modes.
#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/u_gyro_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/harmonic_fit.hpp"
#include "sim/oracles/u_gyro_output.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/u_gyro/u_gyro_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::UGyroPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = UGyroController<firmware::posix::MonotonicClock>;

class UGyroRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::u_gyro::Record;

  explicit UGyroRun(const UGyroScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        settle_tick_(static_cast<std::int64_t>(std::llround(s.settle_s / s.loop.tick_s()))),
        window_(std::min(settle_tick_, s.loop.ticks() / 2),
                std::max<std::int64_t>(1, static_cast<std::int64_t>(0.05 / s.loop.tick_s()))) {}

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
    if (ticks_ < settle_tick_) return;
    const double gamma = plant_.spin_angle_rad();
    if (!started_) {
      started_ = true;
      gamma_start_ = gamma;
    }
    // A completed twice-spin period (half a revolution): the samples so far cover whole periods; keep them.
    const auto periods = static_cast<std::int64_t>(std::floor(std::fabs(gamma - gamma_start_) / std::numbers::pi));
    if (periods > periods_) {
      periods_ = periods;
      done_ = run_;
    }
    run_.add(2.0 * gamma, plant_.beta_rad(), static_cast<double>(ticks_) * s_.loop.tick_s());
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.beta_rad = plant_.beta_rad();
    r.beta_rate_rad_s = plant_.beta_rate_rad_s();
    r.gyro_torque_Nm = plant_.gyro_torque_Nm();
    r.book_torque_Nm = oracles::u_gyro_output_torque(s_.plant.gyro, s_.plant.table_rate, plant_.spin_angle_rad());
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const models::UGyroParams& g = s_.plant.gyro;
    const double Omega = s_.plant.table_rate;
    const double mean_book = oracles::u_gyro_mean_output(g, Omega);
    const double twice_book = oracles::u_gyro_twice_spin_output(g, Omega);
    const double twice_coupled = oracles::u_gyro_twice_spin_output_coupled(g, Omega);
    const double receptance = std::abs(oracles::u_gyro_frame_response(g, 2.0 * g.spin));
    nlohmann::json f{{"H_Nms", g.H()},
                     {"asymmetry_book", g.asymmetry()},
                     {"mean_output_book_rad", mean_book},
                     {"twice_spin_amplitude_book_rad", twice_book},
                     {"twice_spin_torque_amplitude_book_Nm", std::fabs(g.asymmetry()) * g.H() * Omega},
                     {"frame_receptance_at_twice_spin_rad_per_Nm", receptance},
                     {"twice_spin_amplitude_coupled_rad", twice_coupled},
                     {"inertia_coupling_rel", oracles::u_gyro_inertia_coupling(g)},
                     {"periods", periods_},
                     {"statistics_from_s", s_.settle_s},
                     {"ticks", ticks_}};
    const char* measured[] = {"mean_output_rad", "twice_spin_amplitude_rad", "twice_spin_amplitude_rel_error",
                              "twice_spin_amplitude_coupled_rel_error",
                              "mean_output_rel_error", "asymmetry_measured"};
    const analysis::HarmonicFit::Result d = done_.solve();
    if (periods_ == 0 || !d.valid) {  // no whole twice-spin period after settling (a short run)
      for (const char* key : measured) f[key] = nullptr;
      return f;
    }
    const double mean = d.mean, twice = d.amplitude();
    // A relative error without a reference (Ω = 0: the book's values are 0) is null, not 0.
    const auto rel = [](double got, double ref) { return ref != 0.0 ? nlohmann::json((got - ref) / ref) : nlohmann::json(); };
    f["mean_output_rad"] = mean;
    f["twice_spin_amplitude_rad"] = twice;
    f["mean_output_rel_error"] = rel(mean, mean_book);
    f["twice_spin_amplitude_rel_error"] = rel(twice, twice_book);
    f["twice_spin_amplitude_coupled_rel_error"] = rel(twice, twice_coupled);
    // |ε| recovered from the output: the twice-spin amplitude over the frame's receptance and H Ω.
    f["asymmetry_measured"] =
        Omega != 0.0 ? nlohmann::json(twice / (receptance * g.H() * std::fabs(Omega))) : nlohmann::json();
    f["samples"] = done_.samples();
    return f;
  }

  // report.json "error_estimate": 50 ms (ten twice-spin periods of the scene) from the end of settling.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics& m, const Plant::HeldInputs& in) { m.inputs.Omega = in.Omega; };
    return error_estimate_json<3>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"beta_rad", "beta_rate_rad_s", "gamma_rad"}, "none watched: the spin motor and the damper act");
  }

 private:
  const UGyroScene& s_;
  Plant plant_;
  std::int64_t settle_tick_;
  ActuatorFrame last_{};
  bool started_{false};
  double gamma_start_{0.0};
  std::int64_t periods_{0};
  // The fit's sums so far, and at the last completed twice-spin period (mean, trend and the 2γ harmonic).
  analysis::HarmonicFit run_{true}, done_{true};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
};

struct UGyroTraits {
  using Scene = UGyroScene;
  using Binding = UGyroRun;
  using Controller = tools::Controller;
};

}  // namespace

std::unique_ptr<DeviceScene> make_u_gyro_scene(std::unique_ptr<UGyroScene> s) {
  return std::make_unique<DeviceSceneOf<UGyroTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
