// Scene binding of the gyro vertical on an aircraft (Magnus §12.3, (12.35)-(12.51)): the instrument
// (sim/models/gyro_vertical.hpp, full or precession form) in the track frame of a vehicle flying over the
// rotating Earth (sim/motion/earth_vehicle.hpp: straight legs, coordinated turns, accelerations), erected by
// the firmware correction law (firmware/app/gyro_vertical_controller.hpp). Sensors: the erection sensor
// (tilt from the apparent vertical), the gimbal rate pick-offs (seeded noise), and a turn indicator — a P
// rate gyro with its own dynamics (sim/sensors/rate_integrating_gyro.hpp, (15.1)-(15.6)) on the aircraft's
// normal axis — whose reading drives the firmware's turn cut-out.
// Aircraft attitude: coordinated flight, bank φ = α_L (the apparent vertical's roll angle, (12.43)), pitch 0.
// Figures: per manoeuvre segment, the tilt (α, β) at its end beside the book's prediction from the segment's
// start — z = z_eq + (z0 − z_eq) e^(−[δ + i(ω + ω^P)] t), z_eq = (δ + iω^P)(α_L + iβ_L)/(δ + i(ω + ω^P))
// ((12.45)/(12.39); in a steady turn z_eq = z_G of (12.47)) — with δ = f/H, ω^P = c/H (plant + firmware
// row 1) when the law is the linear one (rows 1 and 4, equal on both axes; δ = 0 while cut out), else null;
// (12.47) neglects the Earth and transport rates, whose steady error is ≈ |Ω_h| H/f, and the bearing damping
// d that keeps the nutation stable (sim/models/gyro_vertical.hpp), which shifts δ by d(Hω + c)/(fH) relative
// and leaves the equilibrium unchanged. Also: the resonance turn
// rate −ω^P, the largest indicated-bank error |α|, the turn indicator's reading against the true turn rate
// (15.6: ≈ cosφ). Keys: docs/scenes.md#gyro_vertical.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <memory>

#include "firmware/app/gyro_vertical_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyro_vertical.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/rate_integrating_gyro.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/devices/gyro_frame_scene.hpp"
#include "tools/devices/manoeuvre_segment_log.hpp"
#include "tools/devices/scene_device.hpp"
#include "tools/devices/scene_run.hpp"
#include "tools/devices/vehicle_frame_feed.hpp"
#include "tools/devices/vehicle_motion_scene.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/run/run_device.hpp"

namespace gyrostab::tools {
namespace {

using Controller = firmware::BasicGyroVerticalController<firmware::posix::MonotonicClock>;
using Model = models::GyroVertical;

enum Stream : std::uint64_t { kErection1Stream = 1, kErection2Stream, kRate1Stream, kRate2Stream };

struct GvSensors {
  double erection_noise_density{0.0};  // erection sensor [rad/√Hz]
  double rate_noise_density{0.0};      // gimbal rate pick-offs [rad/s/√Hz]
};

struct GvScene {
  LoopConfig loop;
  VehicleMotionConfig motion;
  models::GyroVerticalParams gyro;
  double alpha0{0.0}, beta0{0.0};  // initial tilt [rad]
  sensors::SingleAxisGyroParams turn_indicator;
  GvSensors sensors;
  firmware::GyroVerticalConfig controller;
};

struct SegmentRecord : SegmentSpan {
  bool cut_out{false};
  double alpha_start{0.0}, beta_start{0.0};  // [rad]
  double alpha_end{0.0}, beta_end{0.0};
  double alpha_L{0.0}, beta_L{0.0};  // apparent vertical at the segment's start (+1 tick)
  double turn_rate{0.0};             // Ω3 of the frame [rad/s]
  double indicator_sum{0.0}, true_rate_sum{0.0};
};

class GyroVerticalDevice {
 public:
  explicit GyroVerticalDevice(const GvScene& s)
      : s_(s),
        plant_(s.gyro),
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        feed_(s.motion, s.loop.tick_ns,
              PlumbFrame{&motion::EarthVehicleSample::track, frame_forward_right_down, s.motion.earth.rotation_rate}),
        indicator_(s.turn_indicator),
        erection_noise_{sensors::SensorNoise({s.sensors.erection_noise_density, 0.0, 0.0}, s.loop.tick_s()),
                        sensors::SensorNoise({s.sensors.erection_noise_density, 0.0, 0.0}, s.loop.tick_s())},
        rate_noise_{sensors::SensorNoise({s.sensors.rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
                    sensors::SensorNoise({s.sensors.rate_noise_density, 0.0, 0.0}, s.loop.tick_s())},
        rng_{random::SeededRng(s.loop.seed, kErection1Stream), random::SeededRng(s.loop.seed, kErection2Stream),
             random::SeededRng(s.loop.seed, kRate1Stream), random::SeededRng(s.loop.seed, kRate2Stream)},
        controller_(std::make_unique<Controller>(s.controller)),
        segments_(s.motion) {
    x_ = Model::make_state(s.alpha0, s.beta0);
    plant_.inputs.frame.hold(feed_.frame());
    const sensors::GyroCaseMotion m = case_motion(feed_.frame());
    indicator_.reset_steady(m);
    case_ = m;
    begin_segment(segments_.current());
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    double e1, e2, a_rate, b_rate;
    plant_.erection_signal(t, x_, e1, e2);
    plant_.rates(t, x_, a_rate, b_rate);
    f.gimbal_angle_rad[msg::kAxis1] = e1 + erection_noise_[0].sample(rng_[0]);
    f.gimbal_angle_rad[msg::kAxis2] = e2 + erection_noise_[1].sample(rng_[1]);
    f.gimbal_rate_rad_s[msg::kAxis1] = a_rate + rate_noise_[0].sample(rng_[2]);
    f.gimbal_rate_rad_s[msg::kAxis2] = b_rate + rate_noise_[1].sample(rng_[3]);
    f.carrier_rate_rad_s[msg::kYaw] = indicator_.indicated();
    const double bank = models::apparent_vertical(feed_.frame().f).alpha_L;
    f.carrier_angle_rad[msg::kRoll] = bank - x_[0];
    f.carrier_angle_rad[msg::kPitch] = -x_[1];
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.inputs.M1 = cmd.gimbal_torque_Nm[msg::kAxis1];
    plant_.inputs.M2 = cmd.gimbal_torque_Nm[msg::kAxis2];
    if ((cmd.status & firmware::bit(firmware::LawStatusBit::kCorrectionCutOut)) != 0u) {
      segments_.current().cut_out = true;
    }
  }

  void advance(std::int64_t tick) {
    feed_.begin_tick(tick, plant_.inputs.frame);
    window_.before_tick(tick, x_, plant_.inputs);
    driver_.advance_tick(tick, x_);
    window_.after_tick(tick, x_);
    const sensors::GyroCaseMotion m1 = case_motion(feed_.next_frame());
    indicator_.update(case_, m1);
    case_ = m1;
    feed_.end_tick(plant_.inputs.frame);
    const models::FrameSample& w = feed_.frame();
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    alpha_peak_ = std::max(alpha_peak_, std::fabs(x_[0]));
    SegmentRecord& r = segments_.current();
    if (!r.samples) {
      const models::ApparentVertical L = models::apparent_vertical(w.f);
      r.alpha_L = L.alpha_L;
      r.beta_L = L.beta_L;
      r.turn_rate = w.Omega.z();
    }
    r.indicator_sum += indicator_.indicated();
    r.true_rate_sum += w.Omega.z();
    ++r.samples;
    segments_.advance(ticks_ * s_.loop.tick_ns, t1, [this](SegmentRecord& e) { end_segment(e); },
                      [this](SegmentRecord& b) { begin_segment(b); });
  }

  bool finite() const { return x_.allFinite(); }

  // report.json "error_estimate": the half-step comparison (the frame's motion is interpolated within the tick
  // exactly as in the run, so the re-integration at half the step sees the same forcing).
  nlohmann::json error_estimate() const {
    const auto apply = [](auto& p, const auto& in) { p.inputs = in; };
    return window_.template estimate<dynamics::Rk4>(plant_, apply, s_.loop.tick_ns, s_.loop.substeps, 4, {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"},
                                                    "none watched: vehicle motion, correction torques and friction act");
  }

  static std::vector<std::string> columns() {
    return {"alpha_rad",       "beta_rad",        "alpha_L_rad", "beta_L_rad", "M1_Nm", "M2_Nm",
            "turn_rate_rad_s", "turn_indicator_rad_s", "status_bits"};
  }
  void record(double* row) const {
    const models::ApparentVertical L = models::apparent_vertical(feed_.frame().f);
    row[0] = x_[0];
    row[1] = x_[1];
    row[2] = L.alpha_L;
    row[3] = L.beta_L;
    row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
    row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[6] = feed_.frame().Omega.z();
    row[7] = indicator_.indicated();
    row[8] = static_cast<double>(last_.status);
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const firmware::GyroVerticalCorrectionParams& law = s_.controller.law;
    const double H = s_.gyro.gyro.H;
    const bool linear = law.f1 == law.f2 && law.c1 == law.c2 && law.d1 == 0.0 && law.d2 == 0.0 &&
                        law.r1 == 0.0 && law.r2 == 0.0 && law.g1 == 0.0 && law.g2 == 0.0 && s_.gyro.r1 == 0.0 &&
                        s_.gyro.r2 == 0.0;  // plant bearing damping d: shifts δ by d(Hω + c)/(fH) only
    const double delta = law.f1 / H, omega_P = (s_.gyro.c + law.c1) / H, omega_P_plant = s_.gyro.c / H;
    nlohmann::json f{{"ticks", ticks_},
                     {"H_Nms", H},
                     {"delta_s", delta},
                     {"omega_P_rad_s", omega_P},
                     {"resonance_turn_rate_rad_s", -omega_P},
                     {"indicated_bank_error_max_rad", alpha_peak_},
                     {"alpha_end_rad", x_[0]},
                     {"beta_end_rad", x_[1]},
                     {"prediction_applies", linear}};
    if (s_.gyro.fidelity == models::InstrumentFidelity::kFull) {
      f["nutation_frequency_rad_s"] = models::nutation_frequency(s_.gyro.gyro);
    }
    const double t_now = static_cast<double>(ticks_) * s_.loop.tick_s();
    f["segments"] = segments_.to_json(t_now, [&](nlohmann::json& j, const SegmentRecord& r) {
      j["turn_rate_rad_s"] = r.turn_rate;
      j["alpha_L_rad"] = r.alpha_L;
      j["beta_L_rad"] = r.beta_L;
      j["correction_cut_out"] = r.cut_out;
      j["alpha_end_rad"] = r.ended ? r.alpha_end : x_[0];
      j["beta_end_rad"] = r.ended ? r.beta_end : x_[1];
      const double mean_true = r.true_rate_sum / static_cast<double>(r.samples);
      j["turn_indicator_over_true"] =
          std::fabs(mean_true) > 1e-6 ? nlohmann::json(r.indicator_sum / r.true_rate_sum) : nlohmann::json(nullptr);
      if (linear) {
        // (12.45)/(12.39): constant-coefficient solution from the segment's start.
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

 private:
  // The turn indicator's case motion (15.5): input axis = aircraft normal (down), output = longitudinal,
  // spin = lateral (right), with the aircraft banked by φ = α_L about the forward axis.
  static sensors::GyroCaseMotion case_motion(const models::FrameSample& w) {
    const double bank = models::apparent_vertical(w.f).alpha_L;
    const double cb = std::cos(bank), sb = std::sin(bank);
    sensors::GyroCaseMotion m;
    m.Omega1 = -sb * w.Omega.y() + cb * w.Omega.z();  // body down
    m.Omega3 = cb * w.Omega.y() + sb * w.Omega.z();   // body right
    m.Omega2_dot = w.Omega_dot.x();
    return m;
  }
  void begin_segment(SegmentRecord& r) const {
    r.alpha_start = x_[0];
    r.beta_start = x_[1];
  }
  void end_segment(SegmentRecord& r) const {
    r.alpha_end = x_[0];
    r.beta_end = x_[1];
  }

  const GvScene& s_;
  Model plant_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  Model::State x_;
  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): 1000 ticks from the run's middle.
  accuracy::HalfStepWindow<Model, std::remove_cvref_t<decltype(std::declval<Model&>().inputs)>> window_{s_.loop.ticks() / 2, 1000};
  VehicleFrameFeed<PlumbFrame> feed_;  // the track frame
  sensors::SingleAxisGyro indicator_;
  sensors::GyroCaseMotion case_{};
  std::array<sensors::SensorNoise, 2> erection_noise_, rate_noise_;
  std::array<random::SeededRng, 4> rng_;
  std::unique_ptr<Controller> controller_;
  msg::ActuatorFrame last_{};
  ManoeuvreSegmentLog<SegmentRecord> segments_;
  double alpha_peak_{0.0};
  std::int64_t ticks_{0};
};

bool read_scene(SceneReader& r, GvScene& s) {
  read_gyro_frame_scene_head(r,
                             {2e-3, "full (10.22) or precession (12.35) form",
                              "inertia about gimbal axis 1 [kg m²]",
                              "inertia about gimbal axis 2 [kg m²]"},
                             s);
  auto& g = s.gyro;
  g.c = r.number("gyro", "c", 0.0, Range::non_negative(), "pendulous moment m g s, (12.35) row 1 [N m/rad]");
  g.d1 = r.number("gyro", "d1", 0.0, Range::non_negative(), "viscous bearing friction axis 1 [N m s/rad]");
  g.d2 = r.number("gyro", "d2", 0.0, Range::non_negative(), "viscous bearing friction axis 2 [N m s/rad]");
  g.r1 = r.number("gyro", "r1", 0.0, Range::non_negative(), "Coulomb bearing friction axis 1 [N m]");
  g.r2 = r.number("gyro", "r2", 0.0, Range::non_negative(), "Coulomb bearing friction axis 2 [N m]");
  g.coulomb_rate =
      r.number("gyro", "coulomb_rate", 1e-4, Range::positive(), "rate resolution of the Coulomb friction [rad/s]");
  s.alpha0 = kDeg * r.number("gyro", "alpha0_deg", 0.0, Range::closed(-30.0, 30.0), "initial tilt about axis 1 [deg]");
  s.beta0 = kDeg * r.number("gyro", "beta0_deg", 0.0, Range::closed(-30.0, 30.0), "initial tilt about axis 2 [deg]");
  if (const char* why = g.invalid_reason()) r.fail("gyro", "H", why);

  auto& ti = s.turn_indicator;
  ti.sample_period = s.loop.tick_s();
  ti.H = r.number("turn_indicator", "H", 0.01, Range::positive(), "turn indicator spin momentum [N m s]");
  ti.B = r.number("turn_indicator", "B", 2e-5, Range::positive(), "output-axis inertia [kg m²]");
  ti.c2 = r.number("turn_indicator", "c2", 0.2, Range::positive(), "spring [N m/rad] (P-gyro: > 0)");
  ti.d2 = r.number("turn_indicator", "d2", 2e-3, Range::non_negative(), "output-axis damping [N m s/rad]");
  if (const char* why = ti.invalid_reason()) r.fail("turn_indicator", "H", why);

  s.sensors.erection_noise_density = r.number("sensors", "erection_noise_density", 0.0, Range::non_negative(),
                                              "erection sensor noise [rad/sqrt(Hz)]");
  s.sensors.rate_noise_density = r.number("sensors", "rate_noise_density", 0.0, Range::non_negative(),
                                          "gimbal rate pick-off noise [rad/s/sqrt(Hz)]");

  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  auto& l = c.law;
  l.H = g.gyro.H;
  l.c1 = r.number("controller", "c1", 0.0, Range::non_negative(), "row 1 synthesized pendulum, axis 1 [N m/rad]");
  l.c2 = r.number("controller", "c2", l.c1, Range::non_negative(), "row 1, axis 2 [N m/rad]");
  l.d1 = r.number("controller", "d1", 0.0, Range::non_negative(), "row 2 viscous, axis 1 [N m s/rad]");
  l.d2 = r.number("controller", "d2", l.d1, Range::non_negative(), "row 2, axis 2 [N m s/rad]");
  l.r1 = r.number("controller", "r1", 0.0, Range::non_negative(), "row 3 Coulomb, axis 1 [N m]");
  l.r2 = r.number("controller", "r2", l.r1, Range::non_negative(), "row 3, axis 2 [N m]");
  l.f1 = r.number("controller", "f1", 0.0, Range::non_negative(), "row 4 linear correction, M1 = -f1 e2 [N m/rad]");
  l.f2 = r.number("controller", "f2", l.f1, Range::non_negative(), "row 4, M2 = +f2 e1 [N m/rad]");
  l.g1 = r.number("controller", "g1", 0.0, Range::non_negative(), "row 5 relay correction, M1 = -g1 sgn e2 [N m]");
  l.g2 = r.number("controller", "g2", l.g1, Range::non_negative(), "row 5, M2 = +g2 sgn e1 [N m]");
  l.rate_deadband =
      r.number("controller", "rate_deadband", 0.0, Range::non_negative(), "row 3 sgn dead band [rad/s]");
  l.tilt_deadband = r.number("controller", "tilt_deadband", 0.0, Range::non_negative(), "row 5 sgn dead band [rad]");
  l.torque_limit_Nm = r.number("controller", "torque_limit_Nm", 0.05, Range::positive(), "torquer limit [N m]");
  l.turn_cutout_rate = kDeg * r.number("controller", "turn_cutout_deg_s", 0.0, Range::non_negative(),
                                       "correction off while |turn indicator| >= this; 0: never [deg/s]");
  l.cutout = r.choice("controller", "cutout", "both", {"both", "axis1"}, "what the cut-out switches off") == "axis1"
                 ? firmware::TurnCutout::kAxis1
                 : firmware::TurnCutout::kBoth;

  if (r.ok()) {
    if (const char* why = corners_on_ticks(s.motion, s.loop.tick_ns)) r.fail("segment1", "duration_s", why);
    const firmware::ConfigCheck check = Controller::check(c);
    if (!check.ok) r.fail("controller", "f1", "refused by the controller's start-up check: " + describe(check));
    if (g.fidelity == models::InstrumentFidelity::kFull) {
      // The linear rows close a loop whose nutation the precession theory does not see (model header):
      // refuse a configuration whose linearization at rest (Ω = 0) has a growing mode.
      refuse_growing_nutation(r, g.gyro, {g.c + l.c1, l.f1, -l.f2, g.c + l.c2}, g.d1 + l.d1, g.d2 + l.d2,
                              "the correction",
                              "bearing damping d1/A, d2/B must exceed about f/H = " + format_3g(l.f1 / g.gyro.H) + " /s");
      refuse_long_rk4_substep(r, s.loop, Model(g));
    }
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_gyro_vertical(SceneReader& reader, const RunRequest& req) {
  return run_scene<GyroVerticalDevice>(reader, req, read_scene);
}

}  // namespace gyrostab::tools
