// What a ship roll damper run reports: the plant of sim/plants/ship_roll_damper_plant.hpp with its meters
// (roll rms and peaks of the stabilized and the reference ship after the settling time, precession and torque
// peaks, end-stop penetration against its bound, the half-step error estimate), the CSV columns, the figures,
// and the scene's plant and controller for the run modes.
#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/ship_roll_damper_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "sim/analysis/running_stats.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_sampled.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_scene.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::ShipRollDamperPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicShipRollDamperController<firmware::posix::MonotonicClock>;

class ShipRollDamperRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::ship_roll_damper::Record;

  explicit ShipRollDamperRun(const ShipRollDamperScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        settle_tick_(static_cast<std::int64_t>(s.settle_s / s.loop.tick_s())),
        window_(std::min(settle_tick_, s.loop.ticks() / 2), static_cast<std::int64_t>(10.0 / s.loop.tick_s())),
        decay_trial_(roll_decay_trial(s)),
        decay_every_(std::max<std::int64_t>(1, static_cast<std::int64_t>(kDecaySampleS / s.loop.tick_s()))),
        decay_(decay_trial_ ? ship_roll_damper_sampled(s) : ShipRollDamperSampled{}),
        decay_fit_(0.0, decay_trial_ ? s.loop.duration_s : -1.0, s.loop.tick_s() * static_cast<double>(decay_every_),
                   static_cast<int>(decay_.roots.s.size()) + 2) {}

  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    if (decay_trial_ && tick % decay_every_ == 0)
      decay_fit_.add(static_cast<double>(tick) * s_.loop.tick_s(), plant_.roll_rad());
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
  }
  void advance(std::int64_t tick) {
    const Plant::HeldInputs in = plant_.held_inputs();
    window_.before_tick(tick, plant_.state(), in);
    plant_.advance_stabilized(tick);
    window_.after_tick(tick, plant_.state());
    plant_.advance_reference(tick);
    if (tick + 1 >= settle_tick_) {
      roll_.add(plant_.roll_rad());
      roll_ref_.add(plant_.reference_roll_rad());
    }
    precession_peak_ = std::fmax(precession_peak_, std::fabs(plant_.precession_rad()));
    torque_peak_ = std::fmax(torque_peak_, std::fabs(in.command_Nm));
    roll_rate_peak_ = std::fmax(roll_rate_peak_, std::fabs(plant_.roll_rate_rad_s()));
    precession_rate_peak_ = std::fmax(precession_rate_peak_, std::fabs(plant_.precession_rate_rad_s()));
    const bool contact = std::fabs(plant_.precession_rad()) > s_.plant.ship.beta_stop;
    penetration_peak_ = std::fmax(penetration_peak_, std::fabs(plant_.precession_rad()) - s_.plant.ship.beta_stop);
    if (tick + 1 >= settle_tick_) {
      if (contact && !in_contact_) ++stop_contacts_;
      const models::ShipMountLoads m = plant_.mount_loads();
      roll_moment_peak_ = std::fmax(roll_moment_peak_, std::fabs(m.roll));
      yaw_moment_peak_ = std::fmax(yaw_moment_peak_, std::fabs(m.yaw));
      yaw_unit_peak_ = std::fmax(yaw_unit_peak_, std::fabs(m.yaw_unit));
      pitch_moment_peak_ = std::fmax(pitch_moment_peak_, std::fabs(m.pitch));
      yaw_moment_.add(m.yaw);
    }
    in_contact_ = contact;
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    const double t = 1e-9 * static_cast<double>((static_cast<std::int64_t>(last_.tick) + 1) * s_.loop.tick_ns);
    r.roll_rad = plant_.roll_rad();
    r.roll_unstabilized_rad = plant_.reference_roll_rad();
    r.precession_rad = plant_.precession_rad();
    r.roll_rate_rad_s = plant_.roll_rate_rad_s();
    r.precession_rate_rad_s = plant_.precession_rate_rad_s();
    r.wave_moment_Nm = plant_.wave_moment_Nm(t);
    r.precession_torque_Nm = last_.precession_torque_Nm;
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    nlohmann::json f = base_figures();
    decay_figures(f);
    return f;
  }

  nlohmann::json base_figures() const {
    // The field's "roll reduction" is 1 − σ/σ₀ (84 % means the rms roll is 16 % of the unstabilized one).
    const double ratio = roll_ref_.rms() > 0 ? roll_.rms() / roll_ref_.rms() : 1.0;
    return {{"roll_rms_rad", roll_.rms()},
            {"roll_rms_unstabilized_rad", roll_ref_.rms()},
            {"roll_rms_ratio", ratio},
            {"roll_reduction", 1.0 - ratio},
            {"roll_max_rad", roll_.peak},
            {"roll_max_unstabilized_rad", roll_ref_.peak},
            {"precession_max_rad", precession_peak_},
            {"precession_torque_max_Nm", torque_peak_},
            {"wave_moment_rms_Nm", plant_.wave_moment_rms_Nm()},
            {"statistics_from_s", s_.settle_s},
            {"stop_penetration_max_rad", std::fmax(penetration_peak_, 0.0)},
            {"stop_penetration_bound_rad", stop_penetration_bound()},
            {"stop_contacts", stop_contacts_},
            {"roll_moment_max_Nm", roll_moment_peak_},
            {"yaw_moment_max_Nm", yaw_moment_peak_},
            {"yaw_moment_rms_Nm", yaw_moment_.rms()},
            {"yaw_moment_unit_max_Nm", yaw_unit_peak_},
            {"pitch_moment_max_Nm", pitch_moment_peak_}};
  }

  // report.json "error_estimate": the stabilized ship over 10 s from the start of the statistics (or the
  // run's middle, if shorter).
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics& p, const Plant::HeldInputs& in) {
      p.command_Nm = in.command_Nm;
      p.brake_Nms = in.brake_Nms;
    };
    return error_estimate_json<4>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"roll_rad", "precession_rad", "roll_rate_rad_s", "precession_rate_rad_s"},
        "none watched: sea, brake, control and roll damping act");
  }

  // report.json "plant": what the loop assembled. The gyro is (14.8) with its large-angle terms — both
  // inertias (roll A, case B), so nutation and precession; no reduced model is offered: for a ship gyro the
  // two are not separated (ω_N = H/sqrt(AB) = 1.5 rad/s against the roll's 0.6 rad/s for the default ship,
  // ε = O(1)), the condition under which precession theory P0 holds fails (docs/models/gimbal-gyro.md).
  nlohmann::json report_extra() const {
    const auto& p = s_.plant;
    nlohmann::json parts = nlohmann::json::array({"ship roll + gyro case precession (14.8), large-angle terms",
                                                  "precession end stops (spring-damper)",
                                                  "locked reference ship in the same sea"});
    if (p.ship.H == 0.0) parts[0] = "ship roll + gyro case (14.8) with H = 0: no gyroscopic coupling";
    if (p.ship.w > 0.0) parts.push_back("wall-sided righting arm");
    if (p.ship.d1 > 0.0 || p.ship.d2 > 0.0) parts.push_back("viscous roll / precession damping");
    if (p.ship.units == 2) parts.push_back("twin counter-rotating units, cases linked (yaw moments cancel)");
    if (p.ship.turn_rate != 0.0) parts.push_back("turning ship: gyroscopic stiffness H Omega3 (10.22)");
    parts.push_back(p.sea.regular() ? "regular sea (14.9)" : "irregular sea");
    if (p.sea.course.speed != 0.0 || p.sea.course.heading != 0.5 * std::numbers::pi)
      parts.push_back("sea at a heading and speed: encounter frequency, slope sin(mu)");
    if (p.ship.turn_rate != 0.0) parts.push_back("sea seen along a circular track (direct sum per call)");
    if (p.sensors.noisy()) parts.push_back("sensor noise");
    return {{"course", course()},
            {"plant",
             {{"model", models::ShipRollDamper::kName},
              {"fidelity", "full (14.8): no reduced model (epsilon = O(1) for a ship gyro)"},
              {"components", parts},
              {"mechanical_states", 4},
              {"reference_ship_states", 4},
              {"state_size", 8},
              {"device_bytes", sizeof(ShipRollDamperRun)},
              {"integrator", "rk4"},
              {"plant_substeps", s_.loop.substeps}}}};
  }

 private:
  // Largest penetration of the end stops the run's peaks allow (models/ship_roll_damper.hpp: k_s = B ω_s²,
  // ζ_s): the quasi-static push into the stop, (H |φ'|max + |M2|max + |Q| φ'²max/2)/k_s, plus the impact at
  // |β'|max, whose largest excursion in a spring-damper is |β'|/ω_s, or |β'|/(e ω_s) for ζ_s ≥ 1 (the force is
  // clipped at zero, which can only shorten the excursion; the pendulum moment q pushes out of the stop and
  // is left out).
  double stop_penetration_bound() const {
    const auto& p = s_.plant.ship;
    const double ks = p.total_B() * p.stop_frequency * p.stop_frequency;
    const double impact = precession_rate_peak_ / p.stop_frequency * (p.stop_damping_ratio >= 1.0 ? std::exp(-1.0) : 1.0);
    const double inertial = 0.5 * std::abs(p.total_Q()) * roll_rate_peak_ * roll_rate_peak_;  // |Q sinβ cosβ φ'²|
    const double turn = std::abs(p.spin_sum() * p.turn_rate);                                // |H Ω3 cosφ sinβ|
    return (p.total_H() * roll_rate_peak_ + torque_peak_ + inertial + turn) / ks + impact;
  }

  // The course the sea is seen from; the regular wave's encounter frequency (straight course).
  nlohmann::json course() const {
    const auto& p = s_.plant;
    nlohmann::json e{{"speed_m_s", p.sea.course.speed},
                     {"heading_deg", p.sea.course.heading * 180.0 / std::numbers::pi},
                     {"turn_rate_deg_s", p.ship.turn_rate * 180.0 / std::numbers::pi},
                     {"units", p.ship.units}};
    if (p.sea.regular() && !p.sea.course.turning() && p.ship.turn_rate == 0.0)
      e["encounter_frequency_rad_s"] = p.sea.course.encounter_frequency(p.sea.wave.omega);
    if (p.ship.spin_sum() > 0.0)
      e["turn_rate_bound_deg_s"] = p.ship.turn_rate_bound(centring_stiffness()) * 180.0 / std::numbers::pi;
    return e;
  }
  double centring_stiffness() const {
    return s_.controller.mode == firmware::ShipRollDamperMode::kActive ? s_.controller.active.centring_stiffness : 0.0;
  }

  const ShipRollDamperScene& s_;
  Plant plant_;
  std::int64_t settle_tick_;
  ActuatorFrame last_{};
  analysis::RunningStats roll_, roll_ref_;
  double precession_peak_{0.0}, torque_peak_{0.0};
  double roll_rate_peak_{0.0}, precession_rate_peak_{0.0}, penetration_peak_{-1e300};
  bool in_contact_{false};
  std::int64_t stop_contacts_{0};  // contact onsets after the settling time
  double roll_moment_peak_{0.0}, yaw_moment_peak_{0.0}, yaw_unit_peak_{0.0}, pitch_moment_peak_{0.0};
  analysis::RunningStats yaw_moment_;
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
  bool decay_trial_;
  std::int64_t decay_every_;
  ShipRollDamperSampled decay_;
  analysis::LinearPredictionMeter decay_fit_;

  // A roll-decay trial: calm water (a regular sea of E0 = 0), a ship let go from a heel, the law every tick.
  // The roots of the loop near the upright (ship_roll_damper_sampled.hpp), predicted and measured: a recurrence
  // fitted to φ every kDecaySampleS over the run, each root nearest its sampled prediction.
  static constexpr double kDecaySampleS = 0.05;
  static bool roll_decay_trial(const ShipRollDamperScene& s) {
    return s.plant.sea.regular() && s.plant.sea.wave.E0 == 0.0 && s.plant.initial_roll != 0.0 &&
           s.controller.runtime.control_divisor == 1;
  }
  void decay_figures(nlohmann::json& f) const {
    if (!decay_trial_) return;
    f["sampled_loop_max_abs_z"] = decay_.roots.max_abs_z;
    f["decay_fit_samples"] = decay_fit_.samples();
    const std::vector<std::complex<double>> fitted =
        decay_fit_.valid() ? decay_fit_.roots() : std::vector<std::complex<double>>{};
    nlohmann::json modes = nlohmann::json::array();
    for (std::size_t i = 0; i < decay_.continuous.size(); ++i) {
      const std::complex<double> c = decay_.continuous[i], sm = decay_.sampled[i];
      nlohmann::json m{{"decay_rate_per_s_predicted", -c.real()},
                       {"frequency_rad_s_predicted", c.imag()},
                       {"decay_rate_per_s_predicted_sampled", -sm.real()},
                       {"frequency_rad_s_predicted_sampled", std::fabs(sm.imag())}};
      if (!fitted.empty()) {
        const std::complex<double> got = analysis::nearest_root(fitted, sm);
        m["decay_rate_per_s"] = -got.real();
        m["frequency_rad_s"] = std::fabs(got.imag());
      } else {
        m["decay_rate_per_s"] = nullptr;
        m["frequency_rad_s"] = nullptr;
      }
      modes.push_back(m);
    }
    f["decay_modes"] = modes;
  }
};

struct ShipRollDamperTraits {
  using Scene = ShipRollDamperScene;
  using Binding = ShipRollDamperRun;
  using Controller = tools::Controller;
  static nlohmann::json limits(const Scene& s) {
    const auto& a = s.controller.active;
    nlohmann::json l{{"precession_stop_rad", s.plant.ship.beta_stop},
                     {"precession_torque_limit_Nm", a.torque_limit_Nm}};
    if (s.controller.mode == firmware::ShipRollDamperMode::kActive) l["precession_soft_limit_rad"] = a.beta_soft;
    return l;
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_ship_roll_damper_scene(std::unique_ptr<ShipRollDamperScene> s) {
  return std::make_unique<DeviceSceneOf<ShipRollDamperTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
