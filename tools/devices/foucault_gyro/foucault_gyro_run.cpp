// What a Foucault gyro run reports: the plant of sim/plants/foucault_gyro_plant.hpp with its meter — the
// extrema of the offset from the equilibrium (sim/analysis/extrema_meter.hpp): the period and decay rate on
// the small-amplitude extrema against the linearised equation's roots and the book's period (13.6), the
// equilibrium (Aitken's Δ² on the last extrema) and the final angle against α = 0 or ϑ = φ, the settling time
// against the envelope's; the half-step error estimate; the CSV columns, and the scene's plant and controller.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/foucault_gyro_outputs.hpp"
#include "sim/analysis/extrema_meter.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/foucault_gyro/foucault_gyro_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::FoucaultGyroPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = FoucaultGyroController<firmware::posix::MonotonicClock>;
constexpr double kDeg = std::numbers::pi / 180.0;
// An extremum counts once the offset has moved back by this much: far above the angle's round-off (1e-16 rad)
// so that the parabola through three samples still places the extremum (its curvature over a tick is
// a ω0² h² ≈ 1e-7 a for the scenes), far below any amplitude the figures use.
constexpr double kHysteresisRad = 1e-6;

class FoucaultGyroRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::foucault_gyro::Record;

  explicit FoucaultGyroRun(const FoucaultGyroScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        linear_(models::FoucaultLinear::of(s.plant.gyro)),
        offset0_(plant_.offset_rad()),
        extrema_(kHysteresisRad),
        window_(0, std::min<std::int64_t>(1000, std::max<std::int64_t>(1, s.loop.ticks()))) {}

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
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    const double x = plant_.offset_rad();
    extrema_.add(t1, x);
    if (std::fabs(x) > s_.settle_tolerance) last_outside_s_ = t1;
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.angle_rad = plant_.angle_rad();
    r.offset_rad = plant_.offset_rad();
    r.rate_rad_s = plant_.rate_rad_s();
    r.directive_torque_Nm = plant_.directive_torque_Nm();
    r.envelope_rad = envelope(static_cast<double>(ticks_) * s_.loop.tick_s());
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const models::FoucaultGyroParams& g = s_.plant.gyro;
    const bool decl = g.kind == models::FoucaultKind::kDeclinometer;
    const double sigma = linear_.decay_rate(), wd2 = linear_.damped_rate_squared();
    const double t_end = static_cast<double>(ticks_) * s_.loop.tick_s();
    const auto or_null = [](bool ok, double v) { return ok ? nlohmann::json(v) : nlohmann::json(nullptr); };
    nlohmann::json f{{"kind", decl ? "declinometer" : "inclinometer"},
                     {"H_Nms", g.H},
                     {"latitude_deg", g.latitude / kDeg},
                     {"directive_rate_rad_s", g.directive_rate()},
                     {"directive_torque_per_rad_Nm", g.H * g.directive_rate()},
                     {"centrifugal_relative", (g.J_a - g.J_c) * g.directive_rate() / g.H},
                     {"equilibrium_book_rad", g.equilibrium()},
                     {"angle0_rad", s_.plant.angle0},
                     {"angle_end_rad", plant_.angle_rad()},
                     {"offset_end_rad", plant_.offset_rad()},
                     {"period_book_13_6_s", models::foucault_book_period(g)},
                     {"period_linear_s", or_null(wd2 > 0.0, wd2 > 0.0 ? linear_.damped_period() : 0.0)},
                     {"decay_rate_linear_s", sigma},
                     {"damping_ratio", linear_.damping_ratio()},
                     {"small_amplitude_rad", s_.small_amplitude},
                     {"settle_tolerance_rad", s_.settle_tolerance},
                     {"extrema", extrema_.count()},
                     {"ticks", ticks_}};
    // Settled when the offset was last outside the tolerance before the run's last tenth.
    const bool settled = last_outside_s_ < 0.9 * t_end;
    f["settled"] = settled;
    f["settling_time_measured_s"] = or_null(settled, std::max(last_outside_s_, 0.0));
    // The extrema of the linear motion from rest lie on A0 e^(−σt): it reaches the tolerance at ln(A0/tol)/σ.
    const bool envelope_known = sigma > 0.0 && wd2 > 0.0 && std::fabs(offset0_) > s_.settle_tolerance;
    f["settling_time_envelope_s"] =
        or_null(envelope_known, envelope_known ? std::log(std::fabs(offset0_) / s_.settle_tolerance) / sigma : 0.0);
    // The extrema in the small-amplitude regime: from the first below small_amplitude on.
    const int n = extrema_.count();
    int first = 0;
    while (first < n && std::fabs(extrema_.value(first)) >= s_.small_amplitude) ++first;
    const int small = n - first;
    f["extrema_small"] = small;
    f["period_measured_s"] = or_null(small >= 2, small >= 2 ? extrema_.period(first, n - 1) : 0.0);
    f["decay_rate_measured_s"] = or_null(small >= 3, small >= 3 ? extrema_.decay_rate(first) : 0.0);
    f["equilibrium_measured_rad"] =
        or_null(n >= 3, n >= 3 ? g.equilibrium() + extrema_.equilibrium(n - 3) : 0.0);
    return f;
  }

  // report.json "error_estimate": the first 1000 ticks (the large-amplitude start, the pendulum's nonlinearity).
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics&, const Plant::HeldInputs&) {};
    return error_estimate_json<2>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"angle_rad", "rate_rad_s"}, "none watched: the damper acts (without it: the energy integral)");
  }

 private:
  // The linear envelope of the offset's extrema, |x0| e^(−σt) [rad].
  double envelope(double t) const { return std::fabs(offset0_) * std::exp(-linear_.decay_rate() * t); }

  const FoucaultGyroScene& s_;
  Plant plant_;
  models::FoucaultLinear linear_;
  double offset0_;
  analysis::ExtremaMeter<96> extrema_;
  ActuatorFrame last_{};
  double last_outside_s_{-1.0};
  std::int64_t ticks_{0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
};

struct FoucaultGyroTraits {
  using Scene = FoucaultGyroScene;
  using Binding = FoucaultGyroRun;
  using Controller = tools::Controller;
};

}  // namespace

std::unique_ptr<DeviceScene> make_foucault_gyro_scene(std::unique_ptr<FoucaultGyroScene> s) {
  return std::make_unique<DeviceSceneOf<FoucaultGyroTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
