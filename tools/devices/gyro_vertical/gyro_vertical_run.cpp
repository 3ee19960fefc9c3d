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
#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "sim/analysis/manoeuvre_segment_log.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/devices/gyro_vertical/gyro_vertical_scene.hpp"
#include "tools/devices/vehicle_instruments/segments_json.hpp"
#include "tools/run/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::GyroVerticalPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicGyroVerticalController<firmware::posix::MonotonicClock>;

const std::vector<std::string>& columns() {
  static const std::vector<std::string> c{"alpha_rad",  "beta_rad", "alpha_L_rad",     "beta_L_rad",
                                          "M1_Nm",      "M2_Nm",    "turn_rate_rad_s", "turn_indicator_rad_s",
                                          "status_bits"};
  return c;
}

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
  explicit GyroVerticalRun(const GyroVerticalScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        window_(plant_.model().stick_slip() ? 0 : s.loop.ticks() / 2, 1000),
        segments_(s.plant.vehicle),
        late_from_(s.loop.ticks() - s.loop.ticks() / 10) {
    begin_segment(segments_.current());
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) { plant_.sense(tick, f); }
  void actuate(const msg::ActuatorFrame& cmd) {
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

  void record(double* row) const {
    const models::ApparentVertical L = plant_.apparent_vertical();
    row[0] = plant_.alpha_rad();
    row[1] = plant_.beta_rad();
    row[2] = L.alpha_L;
    row[3] = L.beta_L;
    row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
    row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[6] = plant_.turn_rate_rad_s();
    row[7] = plant_.turn_indicator_rad_s();
    row[8] = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const firmware::GyroVerticalCorrectionParams& law = s_.controller.law;
    const models::GyroVerticalParams& gyro = s_.plant.gyro;
    const double H = gyro.gyro.H;
    // The plant's bearing damping d shifts δ by d(Hω + c)/(fH) only: it does not void the prediction.
    const bool linear = law.f1 == law.f2 && law.c1 == law.c2 && law.d1 == 0.0 && law.d2 == 0.0 &&
                        law.r1 == 0.0 && law.r2 == 0.0 && law.g1 == 0.0 && law.g2 == 0.0 && gyro.r1 == 0.0 &&
                        gyro.r2 == 0.0;
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
  msg::ActuatorFrame last_{};
  analysis::ManoeuvreSegmentLog<SegmentRecord> segments_;
  double alpha_peak_{0.0};
  std::int64_t late_from_;
  double late_rate_max_{0.0};
  std::int64_t ticks_{0};
};

struct GyroVerticalTraits {
  using Scene = GyroVerticalScene;
  using Binding = GyroVerticalRun;
  using Controller = tools::Controller;
  static std::vector<std::string> columns(const Scene&) { return tools::columns(); }
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
