// What a gyro vertical run reports: the plant of sim/plants/gyro_vertical_plant.hpp with its meters — per
// manoeuvre segment the tilt (α, β) at its end beside the book's prediction from the segment's start,
//   z = z_eq + (z0 − z_eq) e^(−[δ + i(ω + ω^P)] t),  z_eq = (δ + iω^P)(α_L + iβ_L)/(δ + i(ω + ω^P))
// ((12.45)/(12.39); in a steady turn z_eq = z_G of (12.47)), with δ = f/H, ω^P = c/H (plant + firmware row 1)
// when the law is the linear one (rows 1 and 4, equal on both axes; δ = 0 while cut out), else none; the
// resonance turn rate −ω^P, the largest indicated-bank error |α|, the turn indicator's reading against the
// true turn rate (15.6: ≈ cos φ), the half-step error estimate — the CSV columns, the figures, and the
// scene's plant and controller for the run modes. (12.47) neglects the Earth and transport rates, whose
// steady error is ≈ |Ω_h| H/f, and the bearing damping d that keeps the nutation stable, which shifts δ by
// d(Hω + c)/(fH) relative and leaves the equilibrium unchanged.
// With bearing Coulomb friction r1, r2 in the plant ("dead_zone"): the band of Fig. 12.12 in which the
// correction cannot move the gimbals — for the pure linear correction (no pendulous row) the stuck set
//   |−f1 e2 + T1| ≤ r1,  |f2 e1 + T2| ≤ r2,   T1 = −AΩ1' − HΩ2 − HΩ3 α,  T2 = −BΩ2' + HΩ1 − HΩ3 β
// (the frame's torques of (10.22) at rest shift it; evaluated at the end's angles)
// — beside the residual tilt e at the end, how far outside the band it lies, whether the gimbals are held,
// and the largest gimbal rate over the run's last tenth (the creep: 0 when both are held).
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/planar_mode_fit.hpp"
#include "sim/analysis/manoeuvre_segment_log.hpp"
#include "gyrostab_signals/gyro_vertical_outputs.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/gyro_vertical/gyro_vertical_sampled.hpp"
#include "tools/devices/gyro_vertical/gyro_vertical_scene.hpp"
#include "tools/devices/vehicle_instruments/segments_json.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::GyroVerticalPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicGyroVerticalController<firmware::posix::MonotonicClock>;

struct SegmentRecord : analysis::SegmentSpan {
  bool cut_out{false};
  double alpha_start{0.0}, beta_start{0.0};  // [rad]
  double alpha_end{0.0}, beta_end{0.0};
  double alpha_L{0.0}, beta_L{0.0};  // apparent vertical at the segment's start (+1 tick)
  double turn_rate{0.0};             // Ω3 of the frame [rad/s]
  double indicator_sum{0.0}, true_rate_sum{0.0};
};

class GyroVerticalRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::gyro_vertical::Record;

  explicit GyroVerticalRun(const GyroVerticalScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        window_(plant_.model().stick_slip() ? 0 : s.loop.ticks() / 2, 1000),
        segments_(s.plant.vehicle),
        late_from_(s.loop.ticks() - s.loop.ticks() / 10),
        divisor_(std::max<std::int64_t>(1, static_cast<std::int64_t>(s.controller.runtime.control_divisor))),
        linear_(linear_law(s)),
        book_(-s.controller.law.f1 / s.plant.gyro.gyro.H, (s.plant.gyro.c + s.controller.law.c1) / s.plant.gyro.gyro.H),
        erection_(erection_window(s) > 0.0 ? gyro_vertical_sampled(s, book_) : GyroVerticalSampled{}),
        every_(fit_every(s)),
        window_end_(erection_window(s)),
        fit_(erection_window_start(s), erection_window(s),
             s.loop.tick_s() * static_cast<double>(divisor_ * every_)) {
    begin_segment(segments_.current());
    noise_u_.fill(Eigen::Vector2d::Zero());
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    if (!(window_end_ > 0.0) || static_cast<double>(tick) * s_.loop.tick_s() > window_end_) return;
    const std::int64_t k = tick;
    // The response to the errors of the signals the law read (sensed − the model's), through the sampled loop,
    // comes off the tilt before the fit: the erection noise reaches the tilt through the correction as a
    // random walk of 1e-3 of the late transient, which the fit's few unknowns would otherwise turn into a bias
    // of a few %; a 2 % error of the loop model in this small part moves the fit by < 1e-5.
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    double e[4];
    plant_.model().erection_signal(t, plant_.state(), e[0], e[1]);
    plant_.model().rates(t, plant_.state(), e[2], e[3]);
    const Eigen::Vector4d v(f.erection_e1_rad - e[0], f.erection_e2_rad - e[1], f.alpha_rate_rad_s - e[2],
                            f.beta_rate_rad_s - e[3]);
    const std::size_t slots = noise_u_.size(), L = static_cast<std::size_t>(s_.loop.latency_ticks);
    noise_u_[static_cast<std::size_t>(k) % slots] = erection_.Kx * noise_x_ + erection_.Kv * v;
    const Eigen::Vector2d applied = static_cast<std::size_t>(k) >= L
                                        ? noise_u_[(static_cast<std::size_t>(k) - L) % slots]
                                        : Eigen::Vector2d::Zero();
    // Block means of the compensated tilt: they average the nutation out and keep the mode's ratio e^{λ dt}.
    sum_a_ += plant_.alpha_rad() - noise_x_[0];
    sum_b_ += plant_.beta_rad() - noise_x_[1];
    noise_max_ = std::max({noise_max_, std::fabs(noise_x_[0]), std::fabs(noise_x_[1])});
    if ((k + 1) % every_ == 0) {
      fit_.add(t, sum_a_ / static_cast<double>(every_), sum_b_ / static_cast<double>(every_));
      sum_a_ = sum_b_ = 0.0;
    }
    noise_x_ = erection_.Phi * noise_x_ + erection_.Gamma * applied;
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
    if ((cmd.status & firmware::bit(firmware::LawStatusBit::kCorrectionCutOut)) != 0u) {
      segments_.current().cut_out = true;
    }
  }
  void advance(std::int64_t tick) {
    plant_.begin_tick(tick);
    window_.before_tick(tick, plant_.state(), plant_.inputs());
    plant_.integrate(tick);
    window_.after_tick(tick, plant_.state());
    plant_.end_tick();
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    alpha_peak_ = std::max(alpha_peak_, std::fabs(plant_.alpha_rad()));
    if (tick >= late_from_) {
      const Plant::State& x = plant_.state();
      late_rate_max_ = std::max(
          {late_rate_max_, std::fabs(x[Plant::Model::kAlphaRate]), std::fabs(x[Plant::Model::kBetaRate])});
    }
    SegmentRecord& r = segments_.current();
    if (!r.samples) {
      const models::ApparentVertical L = plant_.apparent_vertical();
      r.alpha_L = L.alpha_L;
      r.beta_L = L.beta_L;
      r.turn_rate = plant_.turn_rate_rad_s();
    }
    r.indicator_sum += plant_.turn_indicator_rad_s();
    r.true_rate_sum += plant_.turn_rate_rad_s();
    ++r.samples;
    segments_.advance(
        ticks_ * s_.loop.tick_ns, t1, [this](SegmentRecord& e) { end_segment(e); },
        [this](SegmentRecord& b) { begin_segment(b); });
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    const models::ApparentVertical L = plant_.apparent_vertical();
    r.alpha_rad = plant_.alpha_rad();
    r.beta_rad = plant_.beta_rad();
    r.alpha_L_rad = L.alpha_L;
    r.beta_L_rad = L.beta_L;
    r.M1_Nm = last_.torquer1_Nm;
    r.M2_Nm = last_.torquer2_Nm;
    r.turn_rate_rad_s = plant_.turn_rate_rad_s();
    r.turn_indicator_rad_s = plant_.turn_indicator_rad_s();
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    nlohmann::json f = base_figures();
    // The erection root over the first, straight segment (gyro_vertical_sampled.hpp).
    if (erection_window(s_) > 0.0) {
      f["erection_decay_rate_per_s_predicted"] = -erection_.continuous.real();
      f["erection_frequency_rad_s_predicted"] = erection_.continuous.imag();
      f["erection_decay_rate_per_s_predicted_sampled"] = -erection_.sampled.real();
      f["erection_frequency_rad_s_predicted_sampled"] = erection_.sampled.imag();
      f["sampled_loop_max_abs_z"] = erection_.roots.max_abs_z;
      f["erection_window_from_s"] = erection_window_start(s_);
      f["erection_window_to_s"] = erection_window(s_);
      f["erection_fit_samples"] = fit_.samples();
      f["erection_noise_response_max_rad"] = noise_max_;
      if (fit_.valid()) {
        const std::complex<double> m = fit_.root();
        f["erection_decay_rate_per_s"] = -m.real();
        f["erection_frequency_rad_s"] = std::fabs(m.imag());
      } else {
        f["erection_decay_rate_per_s"] = nullptr;
        f["erection_frequency_rad_s"] = nullptr;
      }
    } else {
      f["erection_root"] = "not computed: the first segment turns or accelerates, the law is not the linear one (rows 1, 4), or it runs below the tick rate";
    }
    return f;
  }

 private:
  static bool linear_law(const GyroVerticalScene& s) {
    const firmware::GyroVerticalCorrectionParams& law = s.controller.law;
    const models::GyroVerticalParams& gyro = s.plant.gyro;
    return law.f1 == law.f2 && law.c1 == law.c2 && law.d1 == 0.0 && law.d2 == 0.0 && law.r1 == 0.0 &&
           law.r2 == 0.0 && law.g1 == 0.0 && law.g2 == 0.0 && gyro.r1 == 0.0 && gyro.r2 == 0.0;
  }
  // The erection fit's window [s]: in the first segment, while it flies straight with the linear law, from when the
  // nutation the start excited has decayed by e^-5 (its rate d/A − δ, model header) for 3 erection time
  // constants H/f at most; its end is 0 when there is none.
  static double erection_window_start(const GyroVerticalScene& s) {
    const models::GyroVerticalParams& g = s.plant.gyro;
    if (g.fidelity != models::InstrumentFidelity::kFull) return 0.0;
    const double nutation_decay = std::min(g.d1, g.d2) / std::max(g.gyro.A, g.gyro.B) - s.controller.law.f1 / g.gyro.H;
    return nutation_decay > 0.0 ? 5.0 / nutation_decay : 0.0;
  }
  // The fit's sampling: 50 samples per erection time constant H/f, in whole law periods.
  static std::int64_t fit_every(const GyroVerticalScene& s) {
    const double T = s.loop.tick_s() * static_cast<double>(std::max<std::int64_t>(1, s.controller.runtime.control_divisor));
    const double want = s.controller.law.f1 > 0.0 ? s.plant.gyro.gyro.H / s.controller.law.f1 / 50.0 : T;
    return std::max<std::int64_t>(1, static_cast<std::int64_t>(want / T));
  }
  static double erection_window(const GyroVerticalScene& s) {
    const motion::VehicleMotionParams& v = s.plant.vehicle;
    if (!linear_law(s) || v.count < 1 || v.segments[0].turn_rate != 0.0 || v.segments[0].acceleration != 0.0 ||
        !(s.controller.law.f1 > 0.0) || s.controller.runtime.control_divisor != 1)
      return 0.0;
    const double seg = 1e-9 * static_cast<double>(v.segments[0].duration_ns);
    const double end = std::min({seg, s.loop.duration_s, erection_window_start(s) + 3.0 * s.plant.gyro.gyro.H / s.controller.law.f1});
    return end > erection_window_start(s) ? end : 0.0;
  }

 public:
  nlohmann::json base_figures() const {
    const firmware::GyroVerticalCorrectionParams& law = s_.controller.law;
    const models::GyroVerticalParams& gyro = s_.plant.gyro;
    const double H = gyro.gyro.H;
    // The plant's bearing damping d shifts δ by d(Hω + c)/(fH) only: it does not void the prediction.
    const bool linear = linear_;
    const double delta = law.f1 / H, omega_P = (gyro.c + law.c1) / H, omega_P_plant = gyro.c / H;
    const double alpha = plant_.alpha_rad(), beta = plant_.beta_rad();
    nlohmann::json f{{"ticks", ticks_},
                     {"H_Nms", H},
                     {"delta_s", delta},
                     {"omega_P_rad_s", omega_P},
                     {"resonance_turn_rate_rad_s", -omega_P},
                     {"indicated_bank_error_max_rad", alpha_peak_},
                     {"alpha_end_rad", alpha},
                     {"beta_end_rad", beta},
                     {"prediction_applies", linear}};
    if (gyro.fidelity == models::InstrumentFidelity::kFull) {
      f["nutation_frequency_rad_s"] = models::nutation_frequency(gyro.gyro);
    }
    if (gyro.r1 > 0.0 || gyro.r2 > 0.0) f["dead_zone"] = dead_zone();
    const double t_now = static_cast<double>(ticks_) * s_.loop.tick_s();
    f["segments"] = segments_json(segments_, t_now, [&](nlohmann::json& j, const SegmentRecord& r) {
      j["turn_rate_rad_s"] = r.turn_rate;
      j["alpha_L_rad"] = r.alpha_L;
      j["beta_L_rad"] = r.beta_L;
      j["correction_cut_out"] = r.cut_out;
      j["alpha_end_rad"] = r.ended ? r.alpha_end : alpha;
      j["beta_end_rad"] = r.ended ? r.beta_end : beta;
      const double mean_true = r.true_rate_sum / static_cast<double>(r.samples);
      j["turn_indicator_over_true"] = std::fabs(mean_true) > 1e-6
                                          ? nlohmann::json(r.indicator_sum / r.true_rate_sum)
                                          : nlohmann::json(nullptr);
      if (linear) {
        // (12.45)/(12.39): the constant-coefficient solution from the segment's start.
        using C = std::complex<double>;
        const double d = r.cut_out ? 0.0 : delta, wP = r.cut_out ? omega_P_plant : omega_P;
        const C k(d, r.turn_rate + wP);
        const C z_eq = C(d, wP) * C(r.alpha_L, r.beta_L) / k;
        const double T = (r.ended ? r.t_end : t_now) - r.t_start;
        const C z = z_eq + (C(r.alpha_start, r.beta_start) - z_eq) * std::exp(-k * T);
        j["alpha_G_rad"] = z_eq.real();  // (12.47) in a steady turn
        j["beta_G_rad"] = z_eq.imag();
        j["alpha_book_end_rad"] = z.real();
        j["beta_book_end_rad"] = z.imag();
      }
    });
    return f;
  }

  // report.json "error_estimate": 1000 ticks from the run's middle (the frame's motion is interpolated within
  // the tick exactly as in the run, so the re-integration at half the step sees the same forcing). With
  // stick-slip friction the window is the run's first second instead — the breakaway from rest and the
  // nutation's rate reversals, where the stick and landing decisions happen (later the gimbals are often
  // held and the estimate would be 0 for want of events) — and, since those decisions fall on step
  // boundaries, an event is located to within a step: first order there, Richardson's factor is order 1's
  // (2, not 16/15); the estimate states the order it assumed.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Model& m, const Plant::Inputs& in) { m.inputs = in; };
    const int order = plant_.model().stick_slip() ? 1 : 4;
    nlohmann::json e = error_estimate_json<4>(
        window_.estimate<dynamics::Rk4>(plant_.model(), apply, s_.loop.tick_ns, s_.loop.substeps, order),
        {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"},
        "none watched: vehicle motion, correction torques and friction act");
    if (order == 1) {
      e["order_note"] =
          "stick-slip bearing friction: events located to a step, first order (RK4 between them)";
    }
    return e;
  }

 private:
  void begin_segment(SegmentRecord& r) const {
    r.alpha_start = plant_.alpha_rad();
    r.beta_start = plant_.beta_rad();
  }
  void end_segment(SegmentRecord& r) const {
    r.alpha_end = plant_.alpha_rad();
    r.beta_end = plant_.beta_rad();
  }

  nlohmann::json dead_zone() const {
    const firmware::GyroVerticalCorrectionParams& law = s_.controller.law;
    const models::GyroVerticalParams& gyro = s_.plant.gyro;
    const bool stick_slip = plant_.model().stick_slip();
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    double e1, e2;
    plant_.model().erection_signal(t, plant_.state(), e1, e2);
    nlohmann::json j{{"friction_model", stick_slip ? "stick_slip" : "smooth"},
                     {"r1_Nm", gyro.r1},
                     {"r2_Nm", gyro.r2},
                     {"residual_tilt_rad", {e1, e2}},
                     {"late_rate_max_rad_s", late_rate_max_}};
    if (stick_slip) {
      j["held"] = {plant_.model().bearings().stuck(0), plant_.model().bearings().stuck(1)};
    }
    const bool pure_correction = gyro.c == 0.0 && law.c1 == 0.0 && law.c2 == 0.0 && law.f1 > 0.0 &&
                                 law.f2 > 0.0 && law.g1 == 0.0 && law.g2 == 0.0 && law.r1 == 0.0 &&
                                 law.r2 == 0.0 && law.d1 == 0.0 && law.d2 == 0.0;
    if (!pure_correction) {
      j["band"] = nullptr;
      j["band_why_not"] = "the band is given for the linear correction alone (rows 3 + 4, Fig. 12.12)";
      return j;
    }
    // The frame's torques of (10.22) at rest, at the end's angles: what the bearings hold besides f·e.
    const models::FrameSample& w = plant_.frame();
    const double H = gyro.gyro.H, alpha = plant_.alpha_rad(), beta = plant_.beta_rad();
    const double T1 = -gyro.gyro.A * w.Omega_dot.x() - H * w.Omega.y() - H * w.Omega.z() * alpha;
    const double T2 = -gyro.gyro.B * w.Omega_dot.y() + H * w.Omega.x() - H * w.Omega.z() * beta;
    const double e1_lo = (-gyro.r2 - T2) / law.f2, e1_hi = (gyro.r2 - T2) / law.f2;
    const double e2_lo = (-gyro.r1 + T1) / law.f1, e2_hi = (gyro.r1 + T1) / law.f1;
    j["band"] = {{"e1_rad", {e1_lo, e1_hi}},
                 {"e2_rad", {e2_lo, e2_hi}},
                 {"half_width_rad", {gyro.r2 / law.f2, gyro.r1 / law.f1}}};
    const double out1 = std::max({0.0, e1_lo - e1, e1 - e1_hi}),
                 out2 = std::max({0.0, e2_lo - e2, e2 - e2_hi});
    j["outside_band_rad"] = std::hypot(out1, out2);
    return j;
  }

  const GyroVerticalScene& s_;
  Plant plant_;
  analysis::HalfStepWindow<Plant::Model, Plant::Inputs> window_;
  ActuatorFrame last_{};
  analysis::ManoeuvreSegmentLog<SegmentRecord> segments_;
  double alpha_peak_{0.0};
  std::int64_t late_from_;
  double late_rate_max_{0.0};
  std::int64_t ticks_{0};
  std::int64_t divisor_;
  bool linear_;
  std::complex<double> book_;  // −δ + i ω^P
  GyroVerticalSampled erection_;
  std::int64_t every_;
  double window_end_;
  analysis::PlanarModeFit fit_;
  double sum_a_{0.0}, sum_b_{0.0};
  double noise_max_{0.0};  // largest |α|, |β| of the sensor errors' response [rad]
  Eigen::Vector4d noise_x_{Eigen::Vector4d::Zero()};
  std::array<Eigen::Vector2d, kMaxLatencyTicks + 1> noise_u_{};
};

struct GyroVerticalTraits {
  using Scene = GyroVerticalScene;
  using Binding = GyroVerticalRun;
  using Controller = tools::Controller;
  static nlohmann::json limits(const Scene& s) {
    const auto& law = s.controller.law;
    nlohmann::json l{{"torquer_limit_Nm", law.torque_limit_Nm}};
    if (law.turn_cutout_rate > 0.0) l["turn_cutout_rad_s"] = law.turn_cutout_rate;
    return l;
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_gyro_vertical_scene(std::unique_ptr<GyroVerticalScene> s) {
  return std::make_unique<DeviceSceneOf<GyroVerticalTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
