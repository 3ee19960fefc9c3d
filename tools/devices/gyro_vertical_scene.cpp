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
#include <cstdio>
#include <memory>

#include <Eigen/Eigenvalues>

#include "firmware/app/gyro_vertical_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyro_vertical.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/rate_integrating_gyro.hpp"
#include "sim/sensors/sensor_noise.hpp"
#include "tools/devices/scene_device.hpp"
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

struct SegmentRecord {
  bool started{false}, ended{false}, cut_out{false};
  double t_start{0.0}, t_end{0.0};         // [s]
  double alpha_start{0.0}, beta_start{0.0};  // [rad]
  double alpha_end{0.0}, beta_end{0.0};
  double alpha_L{0.0}, beta_L{0.0};  // apparent vertical at the segment's start (+1 tick)
  double turn_rate{0.0};             // Ω3 of the frame [rad/s]
  double indicator_sum{0.0}, true_rate_sum{0.0};
  long samples{0};
};

class GyroVerticalDevice {
 public:
  explicit GyroVerticalDevice(const GvScene& s)
      : s_(s),
        plant_(s.gyro),
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        vehicle_(make_vehicle(s.motion)),
        corners_(s.motion),
        indicator_(s.turn_indicator),
        erection_noise_{sensors::SensorNoise({s.sensors.erection_noise_density, 0.0, 0.0}, s.loop.tick_s()),
                        sensors::SensorNoise({s.sensors.erection_noise_density, 0.0, 0.0}, s.loop.tick_s())},
        rate_noise_{sensors::SensorNoise({s.sensors.rate_noise_density, 0.0, 0.0}, s.loop.tick_s()),
                    sensors::SensorNoise({s.sensors.rate_noise_density, 0.0, 0.0}, s.loop.tick_s())},
        rng_{random::SeededRng(s.loop.seed, kErection1Stream), random::SeededRng(s.loop.seed, kErection2Stream),
             random::SeededRng(s.loop.seed, kRate1Stream), random::SeededRng(s.loop.seed, kRate2Stream)},
        controller_(std::make_unique<Controller>(s.controller)) {
    x_ = Model::make_state(s.alpha0, s.beta0);
    current_ = frame(0);
    plant_.inputs.frame.hold(current_);
    const sensors::GyroCaseMotion m = case_motion(current_);
    indicator_.reset_steady(m);
    case_ = m;
    segment_ = segment_at(0);
    begin_segment(segment_, 0.0);
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
    const double bank = models::apparent_vertical(current_.f).alpha_L;
    f.carrier_angle_rad[msg::kRoll] = bank - x_[0];
    f.carrier_angle_rad[msg::kPitch] = -x_[1];
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.inputs.M1 = cmd.gimbal_torque_Nm[msg::kAxis1];
    plant_.inputs.M2 = cmd.gimbal_torque_Nm[msg::kAxis2];
    if ((cmd.status & firmware::bit(firmware::LawStatusBit::kCorrectionCutOut)) != 0u) {
      segments_[static_cast<std::size_t>(segment_)].cut_out = true;
    }
  }

  void advance(std::int64_t tick) {
    const std::int64_t t1_ns = (tick + 1) * s_.loop.tick_ns;
    const models::FrameSample next = frame_of(vehicle_.sample_left_ns(t1_ns));  // left limit at a corner
    plant_.inputs.frame.t0 = static_cast<double>(tick) * s_.loop.tick_s();
    plant_.inputs.frame.h = s_.loop.tick_s();
    plant_.inputs.frame.s0 = current_;
    plant_.inputs.frame.s1 = next;
    driver_.advance_tick(tick, x_);
    const sensors::GyroCaseMotion m1 = case_motion(next);
    indicator_.update(case_, m1);
    case_ = m1;
    current_ = corners_.corner_at(t1_ns) ? frame(t1_ns) : next;
    plant_.inputs.frame.hold(current_);
    ticks_ = tick + 1;
    const double t1 = static_cast<double>(ticks_) * s_.loop.tick_s();
    alpha_peak_ = std::max(alpha_peak_, std::fabs(x_[0]));
    SegmentRecord& r = segments_[static_cast<std::size_t>(segment_)];
    if (!r.samples) {
      const models::ApparentVertical L = models::apparent_vertical(current_.f);
      r.alpha_L = L.alpha_L;
      r.beta_L = L.beta_L;
      r.turn_rate = current_.Omega.z();
    }
    r.indicator_sum += indicator_.indicated();
    r.true_rate_sum += current_.Omega.z();
    ++r.samples;
    const int seg = segment_at(t1_ns);
    if (seg != segment_) {
      end_segment(segment_, t1);
      segment_ = seg;
      begin_segment(seg, t1);
    }
  }

  bool finite() const { return x_.allFinite(); }

  static std::vector<std::string> columns() {
    return {"alpha_rad",       "beta_rad",        "alpha_L_rad", "beta_L_rad", "M1_Nm", "M2_Nm",
            "turn_rate_rad_s", "turn_indicator_rad_s", "status_bits"};
  }
  void record(double* row) const {
    const models::ApparentVertical L = models::apparent_vertical(current_.f);
    row[0] = x_[0];
    row[1] = x_[1];
    row[2] = L.alpha_L;
    row[3] = L.beta_L;
    row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
    row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    row[6] = current_.Omega.z();
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
    nlohmann::json segs = nlohmann::json::array();
    for (int i = 0; i <= s_.motion.count; ++i) {
      const SegmentRecord& r = segments_[static_cast<std::size_t>(i)];
      if (!r.started || r.samples == 0) continue;
      nlohmann::json j{{"segment", i + 1 <= s_.motion.count ? i + 1 : 0},  // 0: the final cruise
                       {"t_start_s", r.t_start},
                       {"t_end_s", r.ended ? r.t_end : static_cast<double>(ticks_) * s_.loop.tick_s()},
                       {"turn_rate_rad_s", r.turn_rate},
                       {"alpha_L_rad", r.alpha_L},
                       {"beta_L_rad", r.beta_L},
                       {"correction_cut_out", r.cut_out},
                       {"alpha_end_rad", r.ended ? r.alpha_end : x_[0]},
                       {"beta_end_rad", r.ended ? r.beta_end : x_[1]}};
      const double mean_true = r.true_rate_sum / static_cast<double>(r.samples);
      j["turn_indicator_over_true"] =
          std::fabs(mean_true) > 1e-6 ? nlohmann::json(r.indicator_sum / r.true_rate_sum) : nlohmann::json(nullptr);
      if (linear) {
        // (12.45)/(12.39): constant-coefficient solution from the segment's start.
        using C = std::complex<double>;
        const double d = r.cut_out ? 0.0 : delta, wP = r.cut_out ? omega_P_plant : omega_P;
        const C k(d, r.turn_rate + wP);
        const C z_eq = C(d, wP) * C(r.alpha_L, r.beta_L) / k;
        const double T = (r.ended ? r.t_end : static_cast<double>(ticks_) * s_.loop.tick_s()) - r.t_start;
        const C z = z_eq + (C(r.alpha_start, r.beta_start) - z_eq) * std::exp(-k * T);
        j["alpha_G_rad"] = z_eq.real();  // (12.47) in a steady turn
        j["beta_G_rad"] = z_eq.imag();
        j["alpha_book_end_rad"] = z.real();
        j["beta_book_end_rad"] = z.imag();
      }
      segs.push_back(j);
    }
    f["segments"] = segs;
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
  // The track frame at t_ns, with the plumb line as the vertical at rest (remove_centrifugal_tilt).
  models::FrameSample frame(std::int64_t t_ns) const { return frame_of(vehicle_.sample_ns(t_ns)); }
  models::FrameSample frame_of(const motion::EarthVehicleSample& v) const {
    motion::Trihedron T = v.track;
    remove_centrifugal_tilt(v, s_.motion.earth.rotation_rate, T);
    return frame_forward_right_down(T);
  }
  int segment_at(std::int64_t t_ns) const {
    int k = 0;
    while (k < s_.motion.count && t_ns >= segment_start_ns(s_.motion, k + 1)) ++k;
    return k;
  }
  void begin_segment(int i, double t) {
    SegmentRecord& r = segments_[static_cast<std::size_t>(i)];
    r.started = true;
    r.t_start = t;
    r.alpha_start = x_[0];
    r.beta_start = x_[1];
  }
  void end_segment(int i, double t) {
    SegmentRecord& r = segments_[static_cast<std::size_t>(i)];
    r.ended = true;
    r.t_end = t;
    r.alpha_end = x_[0];
    r.beta_end = x_[1];
  }

  const GvScene& s_;
  Model plant_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  Model::State x_;
  VehicleGenerator vehicle_;
  CornerClock corners_;
  models::FrameSample current_{};
  sensors::SingleAxisGyro indicator_;
  sensors::GyroCaseMotion case_{};
  std::array<sensors::SensorNoise, 2> erection_noise_, rate_noise_;
  std::array<random::SeededRng, 4> rng_;
  std::unique_ptr<Controller> controller_;
  msg::ActuatorFrame last_{};
  std::array<SegmentRecord, kMaxVehicleSegments + 1> segments_{};
  int segment_{0};
  double alpha_peak_{0.0};
  std::int64_t ticks_{0};
};

bool read_scene(SceneReader& r, GvScene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  s.motion = read_vehicle_motion(r, 50.0);
  auto& g = s.gyro;
  const std::string fidelity =
      r.choice("gyro", "fidelity", "full", {"full", "precession"}, "full (10.22) or precession (12.35) form");
  g.fidelity = fidelity == "precession" ? models::InstrumentFidelity::kPrecession : models::InstrumentFidelity::kFull;
  g.gyro.H = r.required("gyro", "H", Range::positive(), "spin momentum [N m s]");
  g.gyro.A = r.number("gyro", "A", 2e-3, Range::positive(), "inertia about gimbal axis 1 [kg m²]");
  g.gyro.B = r.number("gyro", "B", 2e-3, Range::positive(), "inertia about gimbal axis 2 [kg m²]");
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
      const double A = g.gyro.A, B = g.gyro.B, H = g.gyro.H;
      Eigen::Matrix4d J;
      J << 0, 0, 1, 0,  //
          0, 0, 0, 1,   //
          -(g.c + l.c1) / A, -l.f1 / A, -(g.d1 + l.d1) / A, -H / A,  //
          l.f2 / B, -(g.c + l.c2) / B, H / B, -(g.d2 + l.d2) / B;
      const Eigen::EigenSolver<Eigen::Matrix4d> es(J, false);
      double growth = -1e300;
      for (int i = 0; i < 4; ++i) growth = std::max(growth, es.eigenvalues()[i].real());
      if (growth > 0.0) {
        char msg[256];
        std::snprintf(msg, sizeof msg,
                      "the correction makes the nutation grow at %.3g /s (a circulatory force, model header): "
                      "bearing damping d1/A, d2/B must exceed about f/H = %.3g /s",
                      growth, l.f1 / H);
        r.fail("gyro", "d1", msg);
      }
      const double h_sub = s.loop.tick_s() / s.loop.substeps;
      Model m(g);
      const dynamics::StepCheck step =
          dynamics::check_step(dynamics::Method::kRk4, dynamics::fastest_mode(m, 0.0, Model::make_state(0, 0)), h_sub);
      if (!step.ok) r.fail("loop", "plant_substeps", step.message);
    }
  }
  r.finish();
  return r.ok();
}

}  // namespace

int run_gyro_vertical(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<GvScene>();
  if (!read_scene(reader, *scene)) return 2;
  if (req.check_only) return 0;
  auto device = std::make_unique<GyroVerticalDevice>(*scene);
  return run_device(*device, scene->loop, req);
}

}  // namespace gyrostab::tools
