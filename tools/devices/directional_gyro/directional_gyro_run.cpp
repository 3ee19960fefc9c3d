// What a directional gyro run reports: the plant of sim/plants/directional_gyro_plant.hpp with its meters —
// the apparent drift of the indication over the run beside the book's (12.22) along the flown path and the
// law's compensation, split into what the torquers precessed and what the free gyro would have drifted; per
// manoeuvre segment the heading turned, the bank, β and the rotor's azimuth drift δ beside the book's turn
// error (12.25) + (12.29) and (12.32) (as corrected) where the book's setting holds — the CSV columns, the
// half-step error estimate, and the scene's plant and controller for the run modes.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/linear_prediction_fit.hpp"
#include "sim/analysis/manoeuvre_segment_log.hpp"
#include "gyrostab_signals/directional_gyro_outputs.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/directional_gyro/directional_gyro_scene.hpp"
#include "tools/devices/directional_gyro/directional_gyro_sampled.hpp"
#include "tools/devices/vehicle_instruments/segments_json.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::DirectionalGyroPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicDirectionalGyroController<firmware::posix::MonotonicClock>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadSToDegH = 180.0 / kPi * 3600.0;

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }
double azimuth_of(const dynamics::Vec3& ned) { return std::atan2(ned.y(), ned.x()); }

// The book's turn error (12.25) + (12.29) of β and (12.32) (as corrected) of δ, right turn, ψ turned, bank φ0.
double beta_book(double c, double phi0, double psi) {
  return -phi0 * std::sin(psi) + c * phi0 / (c * c + 1) * (std::exp(-c * psi) + c * std::sin(psi) - std::cos(psi));
}
double delta_book(double c, double phi0, double psi) {
  const double s = std::sin(psi), co = std::cos(psi);
  return c * phi0 * phi0 / (2 * (c * c + 1)) *
         (c * psi + c * s * co + s * s - 2 * c / (c * c + 1) * (std::exp(-c * psi) * (s - c * co) + c));
}

struct SegmentRecord : analysis::SegmentSpan {
  bool cut_out{false};
  double turn_rate{0.0};                   // r of the generator [rad/s]
  double bank_sum{0.0};                    // [rad]
  double heading_turned{0.0};              // unwrapped true heading change [rad]
  double azimuth_change{0.0};              // unwrapped rotor azimuth change [rad]
  double beta_start{0.0}, beta_end{0.0};   // [rad]
  double along_track_start{0.0};           // rotor azimuth − true heading at the start [rad]
};

class DirectionalGyroRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::directional_gyro::Record;

  explicit DirectionalGyroRun(const DirectionalGyroScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        window_(s.loop.ticks() / 2, 1000),
        segments_(s.plant.vehicle),
        indicated0_(plant_.indicated_heading_unwrapped_rad()),
        fit_window_(inner_gimbal_window(s)),
        fit_every_(fit_every(s)),
        fit_(fit_window_.from, fit_window_.to, s.loop.tick_s() * static_cast<double>(fit_every_), kFitOrder) {
    heading_prev_ = plant_.true_heading_rad();
    azimuth_prev_ = azimuth_of(plant_.rotor_axis_ned());
    begin_segment(segments_.current());
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    compass_ = f.compass_heading_rad;
    if (tick % fit_every_ == 0) fit_.add(static_cast<double>(tick) * s_.loop.tick_s(), plant_.beta_rad());
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
    if ((cmd.status & firmware::bit(firmware::LawStatusBit::kCorrectionCutOut)) != 0u) {
      segments_.current().cut_out = true;
    }
  }
  void advance(std::int64_t tick) {
    const double h = s_.loop.tick_s();
    const firmware::DirectionalGyroCorrectionParams& law = s_.controller.law;
    const motion::EarthVehicleSample& m = plant_.motion();
    const double phi = m.latitude, t_phi = std::tan(phi);
    earth_sum_ += -law.earth_rate * std::sin(phi) * h;
    transport_sum_ += -(m.speed / law.earth_radius) * std::sin(m.heading) * t_phi * h;
    if (law.compensate) {
      compensation_sum_ += -firmware::drift_compensation_torque(law, plant_.indicated_heading_rad()) / law.H * h;
    }
    torque_share_ += -plant_.inputs().M2 * h / (law.H * std::cos(plant_.beta_rad()));
    // The bank that (12.22) leaves out: the case's normal axis, tilted by the bank φ_b, picks up the level
    // (track) frame's horizontal rate across the track, Ω_left sin φ_b; the indication drifts by that too.
    const dynamics::Vec3 w_T =
        plants::plumb_referred(m, m.track, s_.plant.vehicle.earth.rotation_rate).w_IZ_Z;  // forward, left, up
    bank_sum_ += std::sin(plant_.bank_rad()) * w_T.y() * h;
    SegmentRecord& r = segments_.current();
    if (!r.samples) r.turn_rate = m.turn_rate;
    r.bank_sum += plant_.bank_rad();
    ++r.samples;

    plant_.begin_tick(tick);
    window_.before_tick(tick, plant_.state(), plant_.inputs());
    plant_.integrate(tick);
    window_.after_tick(tick, plant_.state());
    plant_.end_tick();
    ticks_ = tick + 1;

    const double heading = plant_.true_heading_rad(), azimuth = azimuth_of(plant_.rotor_axis_ned());
    const double dpsi = wrap(heading - heading_prev_), daz = wrap(azimuth - azimuth_prev_);
    heading_turned_ += dpsi;
    r.heading_turned += dpsi;
    r.azimuth_change += daz;
    heading_prev_ = heading;
    azimuth_prev_ = azimuth;
    segments_.advance(
        ticks_ * s_.loop.tick_ns, static_cast<double>(ticks_) * h, [this](SegmentRecord& e) { end_segment(e); },
        [this](SegmentRecord& b) { begin_segment(b); });
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.indicated_heading_rad = plant_.indicated_heading_rad();
    r.true_heading_rad = plant_.true_heading_rad();
    r.heading_error_rad = wrap(plant_.indicated_heading_rad() - plant_.true_heading_rad());
    r.compass_rad = compass_;
    r.alpha_rad = plant_.alpha_rad();
    r.beta_rad = plant_.beta_rad();
    r.bank_rad = plant_.bank_rad();
    r.rotor_azimuth_rad = azimuth_of(plant_.rotor_axis_ned());
    r.M1_Nm = last_.outer_torquer_Nm;
    r.M2_Nm = last_.inner_torquer_Nm;
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const double T = static_cast<double>(ticks_) * s_.loop.tick_s();
    const double per = T > 0.0 ? kRadSToDegH / T : 0.0;
    // Indicated − true, unwrapped through the run: the indication's own change minus the heading turned.
    const double measured = plant_.indicated_heading_unwrapped_rad() - indicated0_ - heading_turned_;
    nlohmann::json f{{"H_Nms", s_.plant.gyro.H},
                     {"ticks", ticks_},
                     {"final_heading_error_deg", wrap(plant_.indicated_heading_rad() - plant_.true_heading_rad()) *
                                                     180.0 / kPi}};
    f["drift"] = {{"measured_deg_h", measured * per},
                  {"free_gyro_deg_h", (measured - torque_share_) * per},
                  {"book_12_22_deg_h", (earth_sum_ + transport_sum_) * per},
                  {"earth_rate_term_deg_h", earth_sum_ * per},
                  {"transport_term_deg_h", transport_sum_ * per},
                  {"compensation_deg_h", compensation_sum_ * per},
                  {"book_residual_deg_h", (earth_sum_ + transport_sum_ + compensation_sum_) * per},
                  {"bank_term_deg_h", bank_sum_ * per},
                  {"book_12_22_with_bank_deg_h", (earth_sum_ + transport_sum_ + bank_sum_) * per},
                  {"book_residual_with_bank_deg_h", (earth_sum_ + transport_sum_ + compensation_sum_ + bank_sum_) * per}};
    // The free gyro's drift (the indication's less the torquers' share) against (12.22) along the path, with and
    // without the bank term.
    const double free = (measured - torque_share_), book = earth_sum_ + transport_sum_;
    f["drift"]["free_gyro_rel_error_vs_book_12_22"] = book != 0.0 ? nlohmann::json(free / book - 1.0) : nlohmann::json();
    f["drift"]["free_gyro_rel_error_vs_book_with_bank"] =
        book + bank_sum_ != 0.0 ? nlohmann::json(free / (book + bank_sum_) - 1.0) : nlohmann::json();
    const firmware::DirectionalGyroCorrectionParams& law = s_.controller.law;
    inner_gimbal_figures(f);
    f["segments"] = segments_json(segments_, T, [&](nlohmann::json& j, const SegmentRecord& r) {
      const double bank = r.bank_sum / static_cast<double>(r.samples);
      const bool ended = r.ended;
      const double beta_end = ended ? r.beta_end : plant_.beta_rad();
      j["turn_rate_rad_s"] = r.turn_rate;
      j["bank_rad"] = bank;
      j["heading_turned_rad"] = r.heading_turned;
      j["beta_start_rad"] = r.beta_start;
      j["beta_end_rad"] = beta_end;
      j["rotor_azimuth_change_rad"] = r.azimuth_change;
      j["correction_cut_out"] = r.cut_out;
      const double span = (ended ? r.t_end : T) - r.t_start;
      const double yaw_rate = span > 0.0 ? std::fabs(r.heading_turned) / span : 0.0;
      if (r.turn_rate == 0.0 || !(yaw_rate > 0.0)) return;
      const double c = law.k / (law.H * yaw_rate);
      j["c"] = c;
      const bool applies = law.k > 0.0 && !r.cut_out && std::fabs(r.along_track_start) < 0.01 &&
                           std::fabs(r.beta_start) < 0.01;
      j["book_applies"] = applies;
      if (!applies) return;
      // A left turn is the mirror image of a right one: β the same, δ of the opposite sign.
      const double sgn = r.heading_turned >= 0.0 ? 1.0 : -1.0, psi = std::fabs(r.heading_turned);
      j["beta_book_end_rad"] = beta_book(c, std::fabs(bank), psi);
      j["delta_book_rad"] = sgn * delta_book(c, std::fabs(bank), psi);
    });
    return f;
  }

  // report.json "error_estimate": 1000 ticks from the run's middle (the case's motion is interpolated within
  // the tick exactly as in the run, so the re-integration at half the step sees the same forcing).
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Model& m, const Plant::Inputs& in) { m.inputs = in; };
    return error_estimate_json<2>(
        window_.estimate<dynamics::Rk4>(plant_.model(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"alpha_rad", "beta_rad"}, "none watched: vehicle motion and correction torques act");
  }

 private:
  // The inter-gimbal correction's root (12.24), predicted and measured in the last segment when it flies
  // straight and level: a recurrence fitted to β sampled 50 times per time constant H/k, from the segment's
  // start for 5 time constants (the mode and a slowly moving equilibrium: order 3), its real root nearest
  // the prediction; the prediction linearised where the run ends (directional_gyro_sampled.hpp).
  static constexpr int kFitOrder = 3;
  struct Window {
    double from{0.0}, to{-1.0};
  };
  static Window inner_gimbal_window(const DirectionalGyroScene& s) {
    const firmware::DirectionalGyroCorrectionParams& law = s.controller.law;
    const motion::VehicleMotionParams& v = s.plant.vehicle;
    if (!(law.k > 0.0) || s.controller.runtime.control_divisor != 1) return {};
    double from = 0.0;
    if (v.count > 0) {
      const motion::ManoeuvreSegment& last = v.segments[static_cast<std::size_t>(v.count - 1)];
      if (last.turn_rate != 0.0 || last.acceleration != 0.0) return {};
      for (int i = 0; i + 1 < v.count; ++i) from += 1e-9 * static_cast<double>(v.segments[static_cast<std::size_t>(i)].duration_ns);
    }
    const double to = std::min(s.loop.duration_s, from + 5.0 * law.H / law.k);
    return to > from ? Window{from, to} : Window{};
  }
  static std::int64_t fit_every(const DirectionalGyroScene& s) {
    const double T = s.loop.tick_s(), k = s.controller.law.k;
    return k > 0.0 ? std::max<std::int64_t>(1, static_cast<std::int64_t>(s.controller.law.H / k / 50.0 / T)) : 1;
  }
  void inner_gimbal_figures(nlohmann::json& f) const {
    const firmware::DirectionalGyroCorrectionParams& law = s_.controller.law;
    if (!(fit_window_.to > fit_window_.from)) {
      f["inner_gimbal_root"] =
          "not computed: no inter-gimbal correction, a last segment that turns or accelerates, or a law below "
          "the tick rate";
      return;
    }
    const DirectionalGyroSampled d = directional_gyro_sampled(s_, plant_);
    f["inner_gimbal_decay_rate_book_12_24_per_s"] = law.k / law.H;
    f["inner_gimbal_decay_rate_per_s_predicted"] = -d.continuous;
    f["inner_gimbal_decay_rate_per_s_predicted_sampled"] = -d.sampled.real();
    f["sampled_loop_max_abs_z"] = d.roots.max_abs_z;
    f["inner_gimbal_window_from_s"] = fit_window_.from;
    f["inner_gimbal_window_to_s"] = fit_window_.to;
    f["inner_gimbal_fit_samples"] = fit_.samples();
    double measured = 0.0;
    if (fit_.valid()) {
      // The real roots only: the mode is not oscillatory.
      std::vector<std::complex<double>> real;
      for (const std::complex<double>& z : fit_.roots())
        if (z.imag() == 0.0) real.push_back(z);
      if (!real.empty()) measured = -analysis::nearest_root(real, d.sampled).real();
    }
    f["inner_gimbal_decay_rate_per_s"] = measured > 0.0 ? nlohmann::json(measured) : nlohmann::json(nullptr);
  }

  void begin_segment(SegmentRecord& r) const {
    r.beta_start = plant_.beta_rad();
    r.along_track_start = wrap(azimuth_of(plant_.rotor_axis_ned()) - plant_.true_heading_rad());
  }
  void end_segment(SegmentRecord& r) const { r.beta_end = plant_.beta_rad(); }

  const DirectionalGyroScene& s_;
  Plant plant_;
  analysis::HalfStepWindow<Plant::Model, Plant::Inputs> window_;
  ActuatorFrame last_{};
  analysis::ManoeuvreSegmentLog<SegmentRecord> segments_;
  double indicated0_;  // the indication at t = 0, unwrapped [rad]
  double heading_prev_{0.0}, azimuth_prev_{0.0}, heading_turned_{0.0};
  double earth_sum_{0.0}, transport_sum_{0.0}, compensation_sum_{0.0}, torque_share_{0.0};  // [rad]
  double bank_sum_{0.0};  // ∫ Ω_left sin φ_b dt [rad]
  double compass_{0.0};
  std::int64_t ticks_{0};
  Window fit_window_;
  std::int64_t fit_every_;
  analysis::LinearPredictionMeter fit_;
};

struct DirectionalGyroTraits {
  using Scene = DirectionalGyroScene;
  using Binding = DirectionalGyroRun;
  using Controller = tools::Controller;
  static nlohmann::json limits(const Scene& s) {
    const auto& law = s.controller.law;
    nlohmann::json l{{"torquer_limit_Nm", law.torque_limit_Nm}};
    if (law.turn_cutout_rate > 0.0) l["turn_cutout_rad_s"] = law.turn_cutout_rate;
    return l;
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_directional_gyro_scene(std::unique_ptr<DirectionalGyroScene> s) {
  return std::make_unique<DeviceSceneOf<DirectionalGyroTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
