// Scene binding of the two-axis power gyro stabilizer (Magnus §14.3, (14.19)-(14.40)): the full nonlinear
// gimbal gyro (sim/models/power_stabilizer.hpp) on a rolling base, disturbance torque steps, encoders and rate
// gyros (sim/sensors/rate_gyro.hpp), and the firmware's stabilization loops
// (firmware/app/power_stabilizer_controller.hpp, gains checked against (14.25) / (14.30) at start-up).
// Plant options, chosen by scene keys, each a template instantiation dispatched once at start-up (an option
// that is off costs nothing):
//   [drive] kind = "torque"    ideal torque motors on both gimbal axes (the law's gimbal_torque_Nm acts)
//                  "dc_motor"  sim/drives GimbalDrive on both axes (DC motor L, R, k_t, k_e, bus and current
//                              limits, gear with reflected inertia, Coulomb + viscous stick-slip, motor-side
//                              encoder); the firmware's current loops run as the drive task and their
//                              motor_voltage_V drives the motors (explicit coupling, drive first, per plant
//                              step: gimbal_drive.hpp)
//   [gyro] motor = "back_emf"  BackEmfMotor on axis 1 and the voltage law (14.27); (14.30) checked
//   [gyro] structure = "elastic"  ElasticPlatform (14.31); Rk4 with the sub-steps the step validation asks for
//   [gyro] fidelity = "precession"  the reduced model P0 (10.19)-(10.22) (PrecessionOnly: no nutation states),
//                              run beside the full model on the same scene: report.json "reduced_model"
//                              (ε = ω_P/ω_N, the digest's bounds, the measured error; the run-time ratio in
//                              timing.reduced_model); refused where P0 does not hold (ε ≥ 0.1, gimbal lock)
// The plant step is checked against the fastest mode before running (sim/dynamics/step_validation.hpp), and
// the loop (14.23) at the operating point of the inner gimbal ([initial] beta0_deg, the steady deflection
// (14.21)) with the gyroscopic coupling H cos β there (gimbal-lock approach).
// report.json "plant": what the loop assembled (model, state size, components); "drift" with
// [report] drift_period_s: the periodic steady state's departure over a long run (periodic_drift.hpp).
// Figures: the closed loop's nutation frequency and decay rate measured from α'(t) after the first
// disturbance step, beside the roots of the characteristic equation (14.23) / (14.29) (`_predicted`); the
// steady deflections beside (14.21); drive peaks; elastic: the platform frequency (14.37).
// Keys: docs/scenes.md#power_stabilizer.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <numbers>
#include <type_traits>

#include "firmware/app/power_stabilizer_controller.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/drives/gimbal_drive.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/power_stabilizer.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/rate_gyro.hpp"
#include "tools/accuracy/half_step_window.hpp"
#include "tools/accuracy/input_tap.hpp"
#include "tools/devices/power_stabilizer_study.hpp"
#include "tools/devices/periodic_drift.hpp"
#include "tools/devices/running_stats.hpp"
#include "tools/devices/scene_device.hpp"
#include "tools/run/closed_loop.hpp"
#include "tools/run/run_device.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/run/model_comparison.hpp"
#include "tools/run/nutation_meter.hpp"

namespace gyrostab::tools {
namespace {

using Base = models::HarmonicBaseRotation;
using Controller = firmware::BasicPowerStabilizerController<firmware::posix::MonotonicClock>;
enum Stream : std::uint64_t { kRateStream1 = 1, kRateStream2 };

struct Disturbance {
  double M1{0.0}, M2{0.0};    // step heights on axis 1 / axis 2 [N m]
  double t1{1.0}, t2{1.0};    // step times [s]
};

struct PowerScene {
  LoopConfig loop;
  models::GimbalGyroParams gyro;  // as entered in [gyro]
  double H{200.0};
  Base base{};
  Disturbance disturbance;
  sensors::RateGyroParams rate_gyro{};  // both gimbal axes (input axis unused: fed the gimbal rate)
  std::int64_t encoder_counts_per_rev{1 << 18};
  bool dc_drive{false};                  // [drive] kind = "dc_motor"
  drives::GimbalDriveParams drive{};     // both axes
  bool back_emf{false};                  // [gyro] motor = "back_emf"
  models::BackEmfMotor motor{};
  bool elastic{false};                   // [gyro] structure = "elastic"
  models::ElasticPlatform platform{};
  bool precession{false};               // [gyro] fidelity = "precession": the reduced model P0
  double alpha0{0.0}, beta0{0.0};       // [initial] alpha0_deg, beta0_deg [rad]
  double drift_period_s{0.0};           // [report] drift_period_s: periodic drift monitor (0: off)
  double drift_from_s{0.0};             // [report] drift_from_s: start of the reference period [s]
  firmware::PowerStabilizerControllerConfig controller;
  // The loop linearised at the inner gimbal's initial angle β0 (= controller.loops when β0 = 0): A → I(β0),
  // H → H cos β0. The `_predicted` nutation figures use it.
  firmware::PowerStabilizerConfig op_loops;
  // fidelity = "precession": the full model's loop for the comparison (its integrator and the sub-steps its
  // step validation needs) and the expected error (ε, the digest's bounds).
  LoopConfig full_loop;
  nlohmann::json reduced_expected;
  double measure_window_s{1.5};
  // What the plant integrates: with the dc drive the reflected inertias are added (axis 1: AA, or AP when
  // elastic; axis 2: BJ) and the bearing damping of a driven axis moves into the drive's friction.
  models::GimbalGyroParams plant_gyro;
  models::ElasticPlatform plant_platform{};
};

// Root with the largest |Im| (the nutation) of the polynomial c[0] λ^N + ... + c[N]; Im reported ≥ 0.
template <int N>
std::complex<double> nutation_root(const double (&c)[N + 1]) {
  Eigen::Matrix<double, N, N> companion = Eigen::Matrix<double, N, N>::Zero();
  for (int i = 0; i < N; ++i) companion(0, i) = -c[i + 1] / c[0];
  for (int i = 1; i < N; ++i) companion(i, i - 1) = 1.0;
  Eigen::EigenSolver<Eigen::Matrix<double, N, N>> es(companion, false);
  std::complex<double> best{0.0, 0.0};
  for (int i = 0; i < N; ++i) {
    if (std::abs(es.eigenvalues()[i].imag()) > std::abs(best.imag())) best = es.eigenvalues()[i];
  }
  return {best.real(), std::abs(best.imag())};
}

// The loop's nutation root from what the controller's check assumes (A incl. reflected inertia and, when
// elastic, A^P — the quasi-static limit; total viscous damping = commanded + bearings):
//   torque mode (14.23): AB λ⁴ + (A d2 + B d1) λ³ + (H² + d1 d2) λ² + H (k1 + k2) λ + k1 k2 = 0
//   back-EMF (14.29) with bearings: AB λ³ + (A d2 + B D1) λ² + (H² + D1 d2) λ + H r s = 0, D1 = s d + d1
std::complex<double> predicted_nutation(const firmware::PowerStabilizerConfig& l) {
  const double A = l.A, B = l.B, H = l.H;
  if (l.output == firmware::PowerStabilizerOutput::kBackEmfVoltage) {
    const double D1 = l.s * (l.d_emf + l.d_c) + l.bearing_d1, d2 = l.bearing_d2;
    const double c[4] = {A * B, A * d2 + B * D1, H * H + D1 * d2, H * l.r * l.s};
    return nutation_root<3>(c);
  }
  const double d1 = l.d1 + l.bearing_d1, d2 = l.d2 + l.bearing_d2;
  const double c[5] = {A * B, A * d2 + B * d1, H * H + d1 * d2, H * (l.k1 + l.k2), l.k1 * l.k2};
  return nutation_root<4>(c);
}

// When the nutation meter starts: the first disturbance step that is one (a torque applied from t = 0 is a
// load the loop starts with, e.g. the hold of [initial] beta0_deg, not a step).
double first_step_s(const Disturbance& d) {
  const bool s1 = d.M1 != 0.0 && d.t1 > 0.0, s2 = d.M2 != 0.0 && d.t2 > 0.0;
  if (s1 && s2) return std::min(d.t1, d.t2);
  if (s1) return d.t1;
  if (s2) return d.t2;
  return std::min(d.t1, d.t2);
}

// Stand-ins for the drives when the scene has none: empty, so an option that is off has no storage (two
// distinct types: [[no_unique_address]] members of one type would still need distinct addresses).
template <int kAxis>
struct NoGimbalDrive {
  explicit NoGimbalDrive(const drives::GimbalDriveParams&) {}
};

// Per-axis drive peaks over the run.
struct DrivePeaks {
  double current_A[2]{0.0, 0.0};
  double voltage_V[2]{0.0, 0.0};
  double torque_Nm[2]{0.0, 0.0};
  void add(std::size_t axis, double i, double u, double tq) {
    current_A[axis] = std::fmax(current_A[axis], std::fabs(i));
    voltage_V[axis] = std::fmax(voltage_V[axis], std::fabs(u));
    torque_Nm[axis] = std::fmax(torque_Nm[axis], std::fabs(tq));
  }
};

template <class Motor, class Structure, bool kDcDrive, template <class> class Integrator,
          class Fidelity = models::FullGimbal>
class PowerStabilizerDevice {
 public:
  using Plant = models::PowerStabilizer<Base, Motor, Structure, Fidelity>;
  static constexpr bool kElastic = Plant::kElastic;
  static constexpr bool kBackEmf = Plant::kVoltageDriven;
  static constexpr bool kPrecession = Plant::kPrecession;
  static_assert(!(kPrecession && kDcDrive), "a drive on a gimbal axis needs the axis inertia P0 drops");
  static constexpr int kH = kPrecession ? 2 : 4;  // index of H in the state
  // Continuous states the loop integrates: the plant's, and the two winding currents of the dc drives.
  static constexpr int kLoopStateSize = Plant::kStateSize + (kDcDrive ? 2 : 0);
  using Drive1 = std::conditional_t<kDcDrive, drives::GimbalDrive, NoGimbalDrive<1>>;
  using Drive2 = std::conditional_t<kDcDrive, drives::GimbalDrive, NoGimbalDrive<2>>;

  // The runtime guard's names (state_guard.hpp) and the reduced-model comparison's signals.
  static constexpr int kGuardedStates = Plant::kStateSize;
  static const char* state_name(int i) {
    if constexpr (kPrecession) {
      constexpr const char* n[] = {"alpha_rad", "beta_rad", "H_Nms"};
      return n[i];
    } else {
      constexpr const char* n[] = {"alpha_rad",       "beta_rad", "alpha_rate_rad_s",   "beta_rate_rad_s",
                                   "H_Nms",           "platform_rad", "platform_rate_rad_s"};
      return n[i];
    }
  }
  double state_value(int i) const { return x_[i]; }
  static constexpr int kComparedSignals = 2;
  static const char* compared_signal_name(int i) { return i == 0 ? "alpha_rad" : "beta_rad"; }
  double compared_signal(int i) const { return x_[i]; }
  // The axis-1 drive turns the platform when elastic (φ', state 6), else the outer gimbal (α', state 2).
  static constexpr int kRate1 = kElastic ? 6 : 2;
  static constexpr int kAngle1 = kElastic ? 5 : 0;

  explicit PowerStabilizerDevice(const PowerScene& s)
      : s_(s),
        plant_(s.plant_gyro, motor(s), structure(s), s.base),
        integ_(plant_),
        driver_(integ_, s.loop.tick_ns, s.loop.substeps),
        encoder_({s.encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kIncremental,
                  sensors::EncoderParams::Rounding::kNearest}),
        gyro1_(s.rate_gyro),
        gyro2_(s.rate_gyro),
        rng1_(s.loop.seed, kRateStream1),
        rng2_(s.loop.seed, kRateStream2),
        drive1_(s.drive),
        drive2_(s.drive),
        controller_(std::make_unique<Controller>(s.controller)),
        meter_(first_step_s(s.disturbance) + 0.02, first_step_s(s.disturbance) + s.measure_window_s),
        drift_(s.drift_period_s > 0.0 ? PeriodicDrift(4, std::llround(s.drift_period_s / s.loop.tick_s()),
                                                      std::llround(s.drift_from_s / s.loop.tick_s()))
                                      : PeriodicDrift()) {
    if constexpr (kPrecession) {
      x_ = Plant::make_state(s.alpha0, s.beta0, s.H);
      plant_.rates(0.0, x_, rate1_, rate2_);
    } else if constexpr (kElastic) {
      x_ = Plant::make_state(s.alpha0, s.beta0, 0.0, 0.0, s.H, s.alpha0, 0.0);
    } else {
      x_ = Plant::make_state(s.alpha0, s.beta0, 0.0, 0.0, s.H);
    }
  }

  void sense(std::int64_t tick, msg::SensorFrame& f) {
    begin_sensor_frame(f, tick, s_.loop.tick_ns);
    if constexpr (kDcDrive) {
      // Motor-side encoders (the axis-1 motor turns the platform φ when elastic); currents from the drives.
      drive1_.write_sensors(f, msg::kAxis1, x_[kAngle1]);
      drive2_.write_sensors(f, msg::kAxis2, x_[1]);
      f.gimbal_angle_rad[msg::kAxis1] = axis_angle(drive1_, x_[kAngle1]);
      f.gimbal_angle_rad[msg::kAxis2] = axis_angle(drive2_, x_[1]);
    } else {
      const std::int64_t c1 = encoder_.counts(x_[0]), c2 = encoder_.counts(x_[1]);
      f.encoder_count[msg::kAxis1] = static_cast<std::int32_t>(c1);
      f.encoder_count[msg::kAxis2] = static_cast<std::int32_t>(c2);
      f.gimbal_angle_rad[msg::kAxis1] = encoder_.angle_of(c1);
      f.gimbal_angle_rad[msg::kAxis2] = encoder_.angle_of(c2);
    }
    f.gimbal_rate_rad_s[msg::kAxis1] = gyro1_.measure(rate1(), rng1_);
    f.gimbal_rate_rad_s[msg::kAxis2] = gyro2_.measure(rate2(), rng2_);
    f.rotor_speed_rad_s = x_[kH] / s_.gyro.CR;
  }

  void actuate(const msg::ActuatorFrame& cmd) {
    last_ = cmd;
    if constexpr (kDcDrive) {
      drive1_.command(cmd, msg::kAxis1);
      drive2_.command(cmd, msg::kAxis2);
    } else if constexpr (kBackEmf) {
      plant_.inputs.u1 = cmd.motor_voltage_V[msg::kAxis1];
      plant_.inputs.M2K = 0.0;  // (14.28): no loop on axis 2
    } else {
      plant_.inputs.M1K = cmd.gimbal_torque_Nm[msg::kAxis1];
      plant_.inputs.M2K = cmd.gimbal_torque_Nm[msg::kAxis2];
    }
  }

  void advance(std::int64_t tick) {
    const double t = static_cast<double>(tick) * s_.loop.tick_s();
    plant_.inputs.M1S = t >= s_.disturbance.t1 ? s_.disturbance.M1 : 0.0;
    plant_.inputs.M2S = t >= s_.disturbance.t2 ? s_.disturbance.M2 : 0.0;
    if constexpr (kDcDrive) {
      // Drive first, per plant step (gimbal_drive.hpp): probe each axis's load at the step start, step the
      // drive, hold a stuck joint, then integrate with the drive torques held.
      const double h = driver_.substep();
      const double t0 = 1e-9 * static_cast<double>(tick * s_.loop.tick_ns);
      for (int k = 0; k < driver_.substeps(); ++k) {
        const double tk = t0 + k * h;
        const drives::AxisLoad load1 =
            drives::probe_axis_load(plant_, plant_.inputs.M1K, tk, x_, kRate1, drive1_.peak_torque());
        const drives::DriveOutput o1 = drive1_.step(h, x_[kRate1], load1);
        if (o1.hold) x_[kRate1] = 0.0;
        plant_.inputs.M1K = o1.torque;
        const drives::AxisLoad load2 =
            drives::probe_axis_load(plant_, plant_.inputs.M2K, tk, x_, 3, drive2_.peak_torque());
        const drives::DriveOutput o2 = drive2_.step(h, x_[3], load2);
        if (o2.hold) x_[3] = 0.0;
        plant_.inputs.M2K = o2.torque;
        integ_.step(tk, h, x_);
        peaks_.add(0, drive1_.current(), drive1_.last_interval().voltage_mean, drive1_.gear_torque());
        peaks_.add(1, drive2_.current(), drive2_.last_interval().voltage_mean, drive2_.gear_torque());
      }
    } else {
      window_.before_tick(tick, x_, plant_.inputs);
      driver_.advance_tick(tick, x_);
      window_.after_tick(tick, x_);
      // P0: the rates the sensors see at the tick's end, with the inputs held over it.
      if constexpr (kPrecession) plant_.rates(t + s_.loop.tick_s(), x_, rate1_, rate2_);
      if constexpr (kBackEmf) {
        peaks_.add(0, 0.0, plant_.inputs.u1, plant_.signals(x_, t + s_.loop.tick_s()).motor_torque1);
      } else {
        peaks_.add(0, 0.0, 0.0, plant_.inputs.M1K);
        peaks_.add(1, 0.0, 0.0, plant_.inputs.M2K);
      }
    }
    // The meter samples at the law's rate (1 kHz): at a 10 kHz base tick the friction's stick-slip steps in
    // α' would otherwise count as extrema; and no faster than ~100 samples per predicted period.
    if ((tick + 1) % meter_every_ == 0) {
      meter_.add(t + s_.loop.tick_s(), rate1());
    }
    alpha_.add(x_[0]);
    beta_.add(x_[1]);
    if (drift_.enabled()) {
      const double v[4] = {x_[0], x_[1], rate1(), rate2()};
      drift_.add(tick, v);
    }
  }

  bool finite() const { return x_.allFinite(); }
  const Plant& plant() const { return plant_; }                     // the accuracy study's input tap
  const typename Plant::State& state() const { return x_; }

  // report.json "error_estimate" (tools/accuracy/half_step_window.hpp): 1 s from the first disturbance step.
  nlohmann::json error_estimate() const {
    if constexpr (kDcDrive) {
      return {{"available", false},
              {"why", "not estimated: the dc drives step with the plant inside the tick (inputs change per sub-step)"}};
    } else {
      const auto apply = [](Plant& p, const models::PowerStabilizerInputs& in) { p.inputs = in; };
      std::array<const char*, Plant::kStateSize> names{};
      for (int i = 0; i < Plant::kStateSize; ++i) names[static_cast<std::size_t>(i)] = state_name(i);
      return window_.template estimate<Integrator>(plant_, apply, s_.loop.tick_ns, s_.loop.substeps,
                                                   Integrator<Plant>::kName == std::string("rk4") ? 4 : 2, names,
                                                   "none watched: motors, disturbances and bearing friction act");
    }
  }

  static std::vector<std::string> columns() {
    std::vector<std::string> c{"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s", "M1_motor_Nm",
                               "M2_motor_Nm", "M1_disturbance_Nm", "M2_disturbance_Nm", "status_bits"};
    if constexpr (kDcDrive) {
      for (const char* n : {"motor1_current_A", "motor2_current_A", "motor1_voltage_V", "motor2_voltage_V"}) {
        c.emplace_back(n);
      }
    }
    if constexpr (kBackEmf) c.emplace_back("motor1_voltage_V");
    if constexpr (kElastic) c.emplace_back("platform_rad");
    return c;
  }
  void record(double* row) const {
    row[0] = x_[0];
    row[1] = x_[1];
    row[2] = rate1();
    row[3] = rate2();
    if constexpr (kDcDrive) {
      row[4] = drive1_.gear_torque();  // what the motors put on the axes through the gears
      row[5] = drive2_.gear_torque();
    } else if constexpr (kBackEmf) {
      row[4] = kPrecession ? driven_torque1() - s_.motor.viscous() * rate1() : plant_.signals(x_).motor_torque1;
      row[5] = 0.0;
    } else {
      row[4] = last_.gimbal_torque_Nm[msg::kAxis1];
      row[5] = last_.gimbal_torque_Nm[msg::kAxis2];
    }
    row[6] = plant_.inputs.M1S;
    row[7] = plant_.inputs.M2S;
    row[8] = static_cast<double>(last_.status);
    int i = 9;
    if constexpr (kDcDrive) {
      row[i++] = drive1_.current();
      row[i++] = drive2_.current();
      row[i++] = drive1_.last_interval().voltage_mean;
      row[i++] = drive2_.last_interval().voltage_mean;
    }
    if constexpr (kBackEmf) row[i++] = plant_.inputs.u1;
    if constexpr (kElastic) row[i++] = x_[5];
  }

  msg::ActuatorFrame initial_command() const { return msg::ActuatorFrame{}; }
  Controller& controller() { return *controller_; }

  nlohmann::json figures() const {
    const auto& l = s_.controller.loops;
    const std::complex<double> root = predicted_nutation(s_.op_loops);
    const firmware::GainCheck g = firmware::check_power_stabilizer_gains(l);
    nlohmann::json f{{"nutation_frequency_rad_s_predicted", root.imag()},
                     {"nutation_decay_rate_per_s_predicted", -root.real()},
                     {"steady_alpha_rad", x_[0]},
                     {"steady_beta_rad", x_[1]},
                     {"alpha_max_rad", alpha_.peak},
                     {"beta_max_rad", beta_.peak},
                     {"gain_margin", g.gain_scale_max},
                     {"open_loop_nutation_rad_s", s_.H / std::sqrt(l.A * l.B)}};
    if constexpr (kBackEmf) {
      // (14.27) at rest: s r β = M1^S; α is neutral (λ = 0 of (14.29)): a constant M2^S makes it precess.
      f["steady_beta_rad_predicted"] = s_.disturbance.M1 / (l.s * l.r);
      f["steady_alpha_rad_predicted"] = nullptr;
      f["r_max_V_per_rad"] = g.r_max;
      f["motor1_voltage_peak_V"] = peaks_.voltage_V[0];
      f["motor1_torque_peak_Nm"] = peaks_.torque_Nm[0];
    } else {
      // (14.21) holds on a base at rest; on a rolling base the gimbal angles (relative to the base) also
      // carry the base motion.
      f["steady_alpha_rad_predicted"] = l.k2 != 0.0 ? -s_.disturbance.M2 / l.k2 : 0.0;
      f["steady_beta_rad_predicted"] = l.k1 != 0.0 ? s_.disturbance.M1 / l.k1 : 0.0;
      f["k_max_equal_Nm_per_rad"] = g.k_max_equal;
      f["motor1_torque_peak_Nm"] = peaks_.torque_Nm[0];
      f["motor2_torque_peak_Nm"] = peaks_.torque_Nm[1];
    }
    if constexpr (kDcDrive) {
      f["motor1_current_peak_A"] = peaks_.current_A[0];
      f["motor2_current_peak_A"] = peaks_.current_A[1];
      f["motor1_voltage_peak_V"] = peaks_.voltage_V[0];
      f["motor2_voltage_peak_V"] = peaks_.voltage_V[1];
      f["reflected_inertia_kg_m2"] = drive1_.reflected_inertia();
      f["drive_peak_torque_Nm"] = drive1_.peak_torque();
    }
    if constexpr (kElastic) {
      // (14.33)-(14.37): c* = c H²/(c B + H²), ω^P = sqrt(c*/A^P), α/φ = c B/(c B + H²).
      const double c = s_.plant_platform.c, B = l.B, H = s_.H;
      const double c_star = c * H * H / (c * B + H * H);
      f["platform_frequency_rad_s_predicted"] = std::sqrt(c_star / plant_.platform_inertia());
      f["effective_stiffness_Nm_per_rad_predicted"] = c_star;
      f["alpha_over_phi_predicted"] = c * B / (c * B + H * H);
      f["steady_platform_rad"] = x_[5];
    }
    // The measurement fits one exponentially decaying oscillation. Coulomb/stick-slip drive friction and the
    // elastic platform's extra mode make the response something else, and (14.23)'s roots do not model them:
    // there the measured figures are withheld (null) with the reason, never reported wrong.
    if (s_.beta0 != 0.0) f["operating_point_beta_rad"] = s_.beta0;
    if (kPrecession) {
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_decay_rate_per_s"] = nullptr;
      f["nutation_measurement"] = "not measured: the precession model (P0) has no nutation";
    } else if (kDcDrive || kElastic) {
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_decay_rate_per_s"] = nullptr;
      f["nutation_measurement"] = kDcDrive ? "not measured: the drives' stick-slip friction is not in (14.23)"
                                           : "not measured: the elastic platform adds a mode (14.31) not in (14.23)";
    } else if (meter_.valid()) {
      f["nutation_frequency_rad_s"] = meter_.angular_frequency();
      f["nutation_decay_rate_per_s"] = -meter_.growth_rate();
    } else {
      f["nutation_frequency_rad_s"] = nullptr;
      f["nutation_decay_rate_per_s"] = nullptr;
      f["nutation_measurement"] = "not measured: fewer than three nutation periods in the window";
    }
    return f;
  }

  // report.json "plant" (what this loop assembled: only what the scene names is in it) and, with
  // [report] drift_period_s, "drift".
  nlohmann::json report_extra() const {
    nlohmann::json parts = nlohmann::json::array();
    parts.push_back(kPrecession ? "precession model P0 (10.19)-(10.22), no nutation states"
                                : "gimbal gyro (10.4) with nutation");
    if constexpr (kBackEmf) parts.push_back("back-EMF motor (14.26), current lag neglected");
    if constexpr (kDcDrive) parts.push_back("motor electrics: dc drives on both axes (winding current, gear, friction)");
    if constexpr (kElastic) parts.push_back("structural elasticity: platform on a shaft (14.31)");
    if (s_.base.amplitude > 0.0) parts.push_back("base motion: harmonic roll");
    if (s_.plant_gyro.d1 > 0.0 || s_.plant_gyro.d2 > 0.0) parts.push_back("bearing viscous friction");
    if constexpr (kDcDrive) {
      if (s_.drive.friction.coulomb > 0.0) parts.push_back("bearing Coulomb friction (stick-slip)");
    }
    const auto& n = s_.rate_gyro.noise;
    if (n.white_density > 0.0 || n.bias != 0.0 || n.bias_random_walk > 0.0) parts.push_back("rate gyro noise");
    using Order = sensors::LowpassParams::Order;
    const Order order = s_.rate_gyro.bandwidth.order;
    const int filter = order == Order::kNone ? 0 : order == Order::kFirst ? 1 : 2;  // states per rate gyro
    nlohmann::json j;
    j["plant"] = {{"model", Plant::kName},
                  {"fidelity", kPrecession ? "precession" : "full"},
                  {"components", parts},
                  {"mechanical_states", Plant::kStateSize},
                  {"electrical_states", kDcDrive ? 2 : 0},
                  {"sensor_filter_states", 2 * filter},
                  {"state_size", kLoopStateSize + 2 * filter},
                  {"device_bytes", sizeof(PowerStabilizerDevice)},
                  {"integrator", Integrator<Plant>::kName},
                  {"plant_substeps", s_.loop.substeps}};
    if (drift_.enabled()) {
      static const char* const names[] = {"alpha_rad", "beta_rad", "alpha_rate_rad_s", "beta_rate_rad_s"};
      j["drift"] = drift_.report(names, s_.loop.tick_s());
      j["drift"]["bound_rad"] = drift_bound();
      const double worst = std::max(drift_.worst(0), drift_.worst(1));
      j["drift"]["within_bound"] = drift_.compared_ticks() > 0 && worst <= drift_bound();
    }
    return j;
  }
  // The angles' bound on the periodic drift: two encoder counts. The loop is exponentially stable and the
  // law memoryless, so an integration error is forgotten at the loop's decay rate instead of accumulating;
  // what can remain is the loop settling, from period to period, on neighbouring encoder counts (its only
  // non-smooth element), each count moving the angles by less than one count in the steady state.
  double drift_bound() const { return 2.0 * 2.0 * std::numbers::pi / static_cast<double>(s_.encoder_counts_per_rev); }

 private:
  double rate1() const {
    if constexpr (kPrecession) {
      return rate1_;
    } else {
      return x_[2];
    }
  }
  double rate2() const {
    if constexpr (kPrecession) {
      return rate2_;
    } else {
      return x_[3];
    }
  }
  double driven_torque1() const { return s_.motor.s * plant_.inputs.u1; }
  static Motor motor(const PowerScene& s) {
    if constexpr (kBackEmf) {
      return s.motor;
    } else {
      (void)s;
      return Motor{};
    }
  }
  static Structure structure(const PowerScene& s) {
    if constexpr (kElastic) {
      return s.plant_platform;
    } else {
      (void)s;
      return Structure{};
    }
  }
  // Axis angle from the motor-side encoder [rad] (counts before the 32-bit wrap of the contract).
  static double axis_angle(const drives::GimbalDrive& d, double angle) {
    const std::int64_t c = d.encoder().counts(d.gear().motor_angle(angle));
    return d.encoder().angle_of(c) / d.gear().ratio();
  }

  const PowerScene& s_;
  Plant plant_;
  Integrator<Plant> integ_;
  dynamics::SubstepDriver<Integrator<Plant>> driver_;
  typename Plant::State x_;
  sensors::Encoder encoder_;
  sensors::RateGyro gyro1_, gyro2_;
  random::SeededRng rng1_, rng2_;
  [[no_unique_address]] Drive1 drive1_;
  [[no_unique_address]] Drive2 drive2_;
  std::unique_ptr<Controller> controller_;
  NutationMeter meter_;
  PeriodicDrift drift_;
  // The meter's sampling: every control_divisor ticks, or a multiple of it giving ~100 samples per period
  // of the predicted oscillation. A slow loop (the gimbal-lock approach: a 31 s period) sampled at 1 kHz
  // would count the encoder's one-count torque jitter near each turning point as extrema.
  std::int64_t meter_every_{meter_interval(s_)};
  static std::int64_t meter_interval(const PowerScene& s) {
    const auto divisor = static_cast<std::int64_t>(s.controller.runtime.control_divisor);
    const double w = predicted_nutation(s.op_loops).imag();
    if (!(w > 0.0)) return divisor;
    const double per_period = 2.0 * std::numbers::pi / w / (100.0 * s.loop.tick_s() * static_cast<double>(divisor));
    return divisor * std::max<std::int64_t>(1, static_cast<std::int64_t>(per_period));
  }
  double rate1_{0.0}, rate2_{0.0};  // P0: gimbal rates at the end of the last tick (outputs, not states)
  msg::ActuatorFrame last_{};
  RunningStats alpha_, beta_;
  DrivePeaks peaks_;
  accuracy::HalfStepWindow<Plant, models::PowerStabilizerInputs> window_{
      static_cast<std::int64_t>(std::min(s_.disturbance.t1, s_.disturbance.t2) / s_.loop.tick_s()),
      static_cast<std::int64_t>(1.0 / s_.loop.tick_s())};
};

bool read_scene(SceneReader& r, PowerScene& s) {
  const std::string structure = r.choice("gyro", "structure", "rigid", {"rigid", "elastic"},
                                         "platform: rigid, or elastic shaft to the gyro (14.31)");
  s.elastic = structure == "elastic";
  s.back_emf = r.choice("gyro", "motor", "torque", {"torque", "back_emf"},
                        "axis-1 stabilization motor: torque-controlled, or geared back-EMF motor (14.26)") ==
               "back_emf";
  s.precession = r.choice("gyro", "fidelity", "full", {"full", "precession"},
                          "gyro model: full gimbal gyro (10.4), or the precession model P0 (10.19)-(10.22)") ==
                 "precession";
  if (s.precession && s.elastic) {
    r.fail("gyro", "fidelity",
           "\"precession\" (P0) drops the gimbal inertia, so it has no platform-gyro shaft mode (14.31): use "
           "structure = \"rigid\", or fidelity = \"full\"");
  }
  // The elastic variant has no exact gyroscopic flow (power_stabilizer.hpp): RK4 only; nor has P0.
  if (s.precession) {
    s.loop = read_loop_config(r, "rk4", {"rk4"});
  } else if (s.elastic) {
    s.loop = read_loop_config(r, "rk4", {"rk4"});
  } else {
    s.loop = read_loop_config(r, "gyro-exponential", {"gyro-exponential", "rk4"});
  }
  auto& g = s.gyro;
  g.CR = r.required("gyro", "CR", Range::positive(), "rotor axial moment C^R [kg m²]");
  g.AR = r.required("gyro", "AR", Range::positive(), "rotor transverse moment A^R [kg m²]");
  g.AJ = r.number("gyro", "AJ", 0.0, Range::non_negative(), "inner gimbal A^J [kg m²]");
  g.BJ = r.number("gyro", "BJ", 0.0, Range::non_negative(), "inner gimbal B^J [kg m²]");
  g.CJ = r.number("gyro", "CJ", 0.0, Range::non_negative(), "inner gimbal C^J [kg m²]");
  g.AA = r.number("gyro", "AA", 0.0, Range::non_negative(), "outer gimbal / platform about axis 1 [kg m²]");
  g.d1 = r.number("gyro", "d1", 0.0, Range::non_negative(), "outer bearing viscous friction [N m s/rad]");
  g.d2 = r.number("gyro", "d2", 0.0, Range::non_negative(), "inner bearing viscous friction [N m s/rad]");
  const double rpm = r.required("gyro", "rpm", Range::non_negative(), "rotor speed [rpm]");
  s.H = g.CR * rpm * 2.0 * std::numbers::pi / 60.0;
  if (rpm == 0.0) {
    r.fail("gyro", "rpm",
           "zero spin: without H there is no gyroscopic coupling, and the loops (14.19) are then a circulatory "
           "coupling of two inertias that no damping stabilises (the H (k1 + k2) term of (14.23) vanishes, "
           "D3 = -(A d2 + B d1)^2 k1 k2 < 0); a power stabilizer needs a spinning rotor");
  }
  // At gimbal lock (β = ±90°) the outer axis carries only P = A^A + C^J (I(β) = A cos²β + P sin²β): with P = 0
  // the mass matrix is singular there (digest gyro-fundamentals §9, "near-singular inertia").
  if (!(g.AA + g.CJ > 0.0)) {
    r.fail("gyro", "AA",
           "P = AA + CJ = 0: the outer-axis inertia I(beta) = A cos^2 beta + P sin^2 beta vanishes at gimbal lock "
           "(beta = 90 deg) and the gimbal equations (10.4) become singular there; give the outer gimbal or the "
           "inner gimbal's C^J some inertia (digest: keep P > 0)");
  }
  // Inertia triangle (1.10) for the rotor: 2 A^R >= C^R for a body of revolution.
  if (!(2.0 * g.AR >= g.CR)) r.fail("gyro", "AR", "rotor inertia triangle violated: need 2 A^R >= C^R (Magnus (1.10))");
  if (s.back_emf) {
    auto& m = s.motor;
    m.s = r.required("gyro", "s", Range::closed(1e-6, 1e6), "motor torque per volt at the gimbal, kappa k_t/R [N m/V]");
    m.d = r.required("gyro", "d", Range::closed(0.0, 1e6), "motor back-EMF per gimbal rate, kappa k_e [V s/rad]");
    m.kappa = r.number("gyro", "kappa", 1.0, Range::closed(1e-3, 1e5), "motor gear ratio [-]");
    m.I = r.number("gyro", "I", 0.0, Range::closed(0.0, 1e3), "motor rotor inertia [kg m²]");
  }
  if (s.elastic) {
    s.platform.c = r.required("gyro", "c", Range::closed(1e-3, 1e12), "shaft stiffness platform-gyro [N m/rad]");
    s.platform.AP = r.required("gyro", "AP", Range::closed(1e-6, 1e9), "platform inertia about axis 1 [kg m²]");
  }

  constexpr double kDeg = std::numbers::pi / 180.0;
  s.alpha0 = kDeg * r.number("initial", "alpha0_deg", 0.0, Range::closed(-180.0, 180.0),
                             "initial outer-gimbal angle (at rest) [deg]");
  s.beta0 = kDeg * r.number("initial", "beta0_deg", 0.0, Range::closed(-89.99, 89.99),
                            "initial inner-gimbal angle (at rest); gimbal lock at +-90 deg [deg]");
  const double roll = r.number("base", "roll_amplitude_rad", 0.0, Range::closed(0.0, 0.5), "base roll amplitude [rad]");
  const double freq = r.number("base", "roll_frequency_rad_s", 0.6, Range::positive(), "base roll frequency [rad/s]");
  const std::int64_t axis = r.integer("base", "roll_axis", 1, 1, 2, "base axis the roll is about");
  s.base = Base{axis == 1 ? dynamics::Vec3::UnitX() : dynamics::Vec3::UnitY(), roll, freq, dynamics::Vec3::UnitZ()};

  s.disturbance.M1 = r.number("disturbance", "M1_Nm", 0.0, Range::closed(-1e6, 1e6), "torque step on axis 1 [N m]");
  s.disturbance.t1 = r.number("disturbance", "M1_time_s", 1.0, Range::non_negative(), "time of the axis-1 step [s]");
  s.disturbance.M2 = r.number("disturbance", "M2_Nm", 0.0, Range::closed(-1e6, 1e6), "torque step on axis 2 [N m]");
  s.disturbance.t2 = r.number("disturbance", "M2_time_s", 1.0, Range::non_negative(), "time of the axis-2 step [s]");

  auto& rg = s.rate_gyro;
  rg.sample_period = s.loop.tick_s();
  rg.noise.white_density = r.number("sensors", "rate_noise_density", 1e-4, Range::closed(0.0, 1.0),
                                    "gimbal rate gyro noise density [rad/s/sqrt(Hz)]");
  rg.noise.bias = r.number("sensors", "rate_bias_rad_s", 0.0, Range::closed(-0.1, 0.1), "gimbal rate gyro bias [rad/s]");
  const double bw = r.number("sensors", "rate_bandwidth_hz", 0.0, Range::closed(0.0, 1e5),
                             "gimbal rate gyro -3 dB bandwidth [Hz]; 0: no filter");
  const std::int64_t order = r.integer("sensors", "rate_filter_order", 2, 1, 2, "rate gyro low-pass order [-]");
  const double zeta = r.number("sensors", "rate_damping", std::numbers::sqrt2 / 2, Range::closed(0.05, 5.0),
                               "rate gyro damping ratio, second order [-]");
  if (bw > 0.0) {
    rg.bandwidth.order = order == 1 ? sensors::LowpassParams::Order::kFirst : sensors::LowpassParams::Order::kSecond;
    rg.bandwidth.bandwidth_hz = bw;
    rg.bandwidth.damping = zeta;
    if (!(bw < 0.5 / s.loop.tick_s())) {
      r.fail("sensors", "rate_bandwidth_hz",
             "must lie below the Nyquist frequency of the base tick, " + std::to_string(0.5 / s.loop.tick_s()) + " Hz");
    }
  }
  s.encoder_counts_per_rev = r.integer("sensors", "encoder_counts_per_rev", 1 << 18, 16, 1 << 30,
                                       "gimbal encoder resolution [counts/rev] (torque drive)");

  // Drives.
  s.dc_drive = r.choice("drive", "kind", "torque", {"torque", "dc_motor"},
                        "gimbal drives: ideal torque motors, or DC motors with gears and current loops") == "dc_motor";
  auto& c = s.controller;
  double loop_bandwidth = 0.0;
  if (s.dc_drive) {
    drives::GimbalDriveParams d;
    d.command = drives::GimbalDriveParams::Command::kVoltage;
    d.motor.R = r.required("drive", "R_ohm", Range::closed(1e-4, 1e4), "winding resistance [ohm]");
    d.motor.L = r.required("drive", "L_H", Range::closed(0.0, 10.0), "winding inductance [H]");
    d.motor.k_t = r.required("drive", "k_t_Nm_per_A", Range::closed(1e-5, 1e3), "motor torque constant [N m/A]");
    d.motor.k_e = r.number("drive", "k_e_V_s_per_rad", d.motor.k_t, Range::closed(0.0, 1e3),
                           "motor back-EMF constant [V s/rad] (default k_t)");
    d.motor.J_m = r.number("drive", "J_m_kg_m2", 0.0, Range::closed(0.0, 10.0), "motor rotor inertia [kg m²]");
    d.motor.voltage_limit = r.required("drive", "voltage_limit_V", Range::closed(0.1, 1e4), "bus voltage limit [V]");
    d.motor.current_limit = r.required("drive", "current_limit_A", Range::closed(1e-3, 1e4), "current clamp [A]");
    d.gear.ratio = r.number("drive", "gear_ratio", 1.0, Range::closed(1.0, 1e4), "motor turns per gimbal turn [-]");
    d.gear.efficiency = r.number("drive", "gear_efficiency", 1.0, Range::open_closed(0.0, 1.0), "gear efficiency [-]");
    d.gear.input_inertia = r.number("drive", "gear_input_inertia_kg_m2", 0.0, Range::closed(0.0, 10.0),
                                    "gear stages at motor speed [kg m²]");
    d.friction.coulomb = r.number("drive", "coulomb_Nm", 0.0, Range::closed(0.0, 1e5), "bearing Coulomb friction [N m]");
    d.friction.breakaway = r.number("drive", "breakaway_Nm", d.friction.coulomb, Range::closed(0.0, 1e5),
                                    "bearing breakaway (static) friction [N m], >= coulomb_Nm");
    d.friction.viscous = r.number("drive", "viscous_Nms", 0.0, Range::closed(0.0, 1e6),
                                  "bearing viscous friction beside [gyro] d1/d2 [N m s/rad]");
    d.friction.stick_velocity = r.number("drive", "stick_velocity_rad_s", 1e-5, Range::closed(1e-12, 1.0),
                                         "Karnopp dead band [rad/s]");
    d.encoder = {r.integer("drive", "encoder_counts_per_rev", 4096, 4, 1 << 30,
                           "motor-side encoder resolution [counts/rev]"),
                 0.0, sensors::EncoderParams::Mode::kIncremental, sensors::EncoderParams::Rounding::kNearest};
    loop_bandwidth = r.number("drive", "current_loop_bandwidth_rad_s", 2000.0, Range::positive(),
                              "closed current-loop bandwidth [rad/s], <= ln(4/3)/T_drive");
    if (d.friction.breakaway < d.friction.coulomb) r.fail("drive", "breakaway_Nm", "must be >= coulomb_Nm");
    if (const char* why = drives::GimbalDrive::check(d)) r.fail("drive", "kind", why);
    s.drive = d;
    if (s.back_emf) {
      r.fail("drive", "kind",
             "[gyro] motor = \"back_emf\" is itself the axis-1 drive (voltage law (14.27)); use [drive] kind = \"torque\"");
    }
  }

  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.runtime.control_divisor = static_cast<std::uint32_t>(
      r.integer("controller", "control_divisor", 1, 1, 1000, "control law every N base ticks [-]"));
  c.runtime.drive_divisor = static_cast<std::uint32_t>(
      r.integer("controller", "drive_divisor", 1, 1, 1000, "current loops every N base ticks [-] (dc_motor)"));
  auto& l = c.loops;
  l.H = s.H;
  l.bearing_d1 = g.d1 + (s.dc_drive ? s.drive.friction.viscous : 0.0);
  l.bearing_d2 = g.d2 + (s.dc_drive ? s.drive.friction.viscous : 0.0);
  if (s.back_emf) {
    l.output = firmware::PowerStabilizerOutput::kBackEmfVoltage;
    l.r = r.required("controller", "r", Range::any(), "u per rad of beta (14.27) [V/rad]");
    l.d_c = r.number("controller", "d_c", 0.0, Range::closed(0.0, 1e6),
                     "electronic rate feedback, adds to the back-EMF d [V s/rad]");
    l.voltage_limit_V = r.number("controller", "voltage_limit_V", 24.0, Range::closed(0.1, 1e4),
                                 "motor voltage limit [V]");
    l.s = s.motor.s;
    l.d_emf = s.motor.d;
  } else {
    l.k1 = r.required("controller", "k1", Range::any(), "M1 per rad of beta (14.19) [N m/rad]");
    l.k2 = r.required("controller", "k2", Range::any(), "M2 per rad of alpha (14.19) [N m/rad]");
    l.d1 = r.number("controller", "d1", 0.0, Range::non_negative(), "commanded rate damping, axis 1 [N m s/rad]");
    l.d2 = r.number("controller", "d2", 0.0, Range::non_negative(), "commanded rate damping, axis 2 [N m s/rad]");
    const double limit = r.number("controller", "torque_limit_Nm", 100.0, Range::positive(), "motor torque limit [N m]");
    l.torque_limit_Nm[0] = l.torque_limit_Nm[1] = limit;
  }
  s.measure_window_s = r.number("report", "nutation_window_s", 1.5, Range::positive(),
                                "window after the first disturbance step for the nutation measurement [s]");
  s.drift_period_s = r.number("report", "drift_period_s", 0.0, Range::non_negative(),
                              "period of the forcing for the periodic-drift monitor; 0: off [s]");
  s.drift_from_s = r.number("report", "drift_from_s", 0.0, Range::non_negative(),
                            "start of the drift monitor's reference period, after the transients [s]");
  if (s.drift_period_s > 0.0) {
    const double n = s.drift_period_s / s.loop.tick_s();
    if (std::abs(n - std::round(n)) > 1e-9 * n) {
      r.fail("report", "drift_period_s", "must be a whole number of ticks (the phase must repeat exactly)");
    }
    if (roll > 0.0) {
      const double periods = s.drift_period_s * freq / (2.0 * std::numbers::pi);
      if (std::abs(periods - std::round(periods)) > 1e-9 || std::round(periods) < 1.0) {
        r.fail("report", "drift_period_s",
               "must be a whole number of base roll periods 2 pi/roll_frequency_rad_s = " +
                   std::to_string(2.0 * std::numbers::pi / freq) + " s");
      }
    }
    if (!(s.drift_from_s + 2.0 * s.drift_period_s <= s.loop.duration_s)) {
      r.fail("report", "drift_from_s", "drift_from_s + 2 drift_period_s must not exceed [scene] duration_s");
    }
  } else if (r.has("report", "drift_from_s")) {
    r.fail("report", "drift_from_s", "only with drift_period_s > 0");
  }

  // The plant as integrated: reflected inertias in, bearing damping of driven axes into the drives.
  s.plant_gyro = g;
  s.plant_platform = s.platform;
  if (s.dc_drive && r.ok()) {
    const drives::GimbalDrive probe(s.drive);
    const double refl = probe.reflected_inertia();
    if (s.elastic) {
      s.plant_platform.AP += refl;
    } else {
      s.plant_gyro.AA += refl;
      s.plant_gyro.d1 = 0.0;
    }
    s.plant_gyro.BJ += refl;
    s.plant_gyro.d2 = 0.0;
    auto& dc = c.drive;
    dc.enabled = true;
    for (auto& a : dc.axis) {
      const double N = s.drive.gear.ratio;
      a.torque_constant_Nm_per_A = N * s.drive.gear.efficiency * s.drive.motor.k_t;
      a.back_emf_V_s_per_rad = N * s.drive.motor.k_e;
      a.resistance_ohm = s.drive.motor.R;
      a.inductance_H = s.drive.motor.L;
      a.bandwidth_rad_s = loop_bandwidth;
      a.current_limit_A = s.drive.motor.current_limit;
      a.voltage_limit_V = s.drive.motor.voltage_limit;
    }
  }
  r.finish();
  return r.ok();
}

// Checks that need the plant built with the chosen options: physical validity, the plant step against the
// fastest mode (sim/dynamics/step_validation.hpp), the explicit drive coupling's stable step, and the
// controller's start-up check with A, B as the plant has them (reflected inertia, A^P when elastic).
// The loop (14.23) / (14.29) linearised at inner-gimbal angle beta: the gyroscopic coupling H cos β and the
// outer-axis inertia I(β) (gimbal_gyro.hpp) replace H and A.
template <class Plant>
firmware::PowerStabilizerConfig loops_at(const Plant& plant, firmware::PowerStabilizerConfig l, double beta) {
  const models::GimbalGyroParams& p = plant.gyro().params();
  l.A = l.A - p.A() + p.outer_axis_inertia(beta);
  l.H = l.H * std::cos(beta);
  return l;
}

// The gimbal-lock approach: the controller checks its gains at β = 0, but near β = ±90° the coupling H cos β
// that makes the loop work fades. The loop is checked at the operating points of the inner gimbal (the
// initial angle, the steady deflection (14.21)) with the same Hurwitz test; refused where it fails.
template <class Plant>
void check_operating_points(SceneReader& r, PowerScene& s, const Plant& plant) {
  const auto& l = s.controller.loops;
  s.op_loops = loops_at(plant, l, s.beta0);
  double points[2] = {s.beta0, 0.0};
  const char* what[2] = {"the initial angle [initial] beta0_deg", "the steady deflection M1/k1 (14.21)"};
  if (l.output == firmware::PowerStabilizerOutput::kTorque && l.k1 > 0.0) points[1] = s.disturbance.M1 / l.k1;
  if (l.output == firmware::PowerStabilizerOutput::kBackEmfVoltage && l.r > 0.0) {
    points[1] = s.disturbance.M1 / (l.r * l.s);
  }
  for (int i = 0; i < 2; ++i) {
    const double beta = points[i];
    if (beta == 0.0 || (i == 1 && std::abs(beta - points[0]) < 1e-9)) continue;  // held at β0: said once
    if (!(std::abs(beta) < 0.5 * std::numbers::pi)) {
      r.fail(i == 0 ? "initial" : "disturbance", i == 0 ? "beta0_deg" : "M1_Nm",
             "the inner gimbal would reach gimbal lock (|beta| >= 90 deg) at " + std::string(what[i]));
      continue;
    }
    const firmware::GainCheck g = firmware::check_power_stabilizer_gains(loops_at(plant, l, beta));
    if (!g.accepted) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "gimbal-lock approach: at beta = %.4g deg (%s) the gyroscopic coupling falls to H cos beta = %.4g "
                    "N m s (from %.4g) and the stabilization loop is unstable there: ",
                    beta * 180.0 / std::numbers::pi, what[i], l.H * std::cos(beta), l.H);
      r.fail(i == 0 ? "initial" : "controller", i == 0 ? "beta0_deg" : (s.back_emf ? "r" : "k1"),
             std::string(buf) + g.reason + " (gain margin there " + std::to_string(g.gain_scale_max) + ")");
    }
  }
}

template <class Motor, class Structure, class Fidelity = models::FullGimbal>
bool check_plant(SceneReader& r, PowerScene& s) {
  using Plant = models::PowerStabilizer<Base, Motor, Structure, Fidelity>;
  Motor motor{};
  Structure structure{};
  if constexpr (Plant::kVoltageDriven) motor = s.motor;
  if constexpr (Plant::kElastic) structure = s.plant_platform;
  const Plant plant(s.plant_gyro, motor, structure, s.base);
  if (const char* why = plant.invalid_reason()) {
    r.fail("gyro", "CR", why);
    return false;
  }
  auto& l = s.controller.loops;
  l.A = plant.outer_axis_inertia();
  l.B = plant.gyro().params().B();
  const firmware::ConfigCheck check = Controller::check(s.controller);
  if (!check.ok) {
    r.fail("controller", s.back_emf ? "r" : "k1", "refused by the controller's start-up check: " + describe(check));
  }
  check_operating_points(r, s, plant);
  typename Plant::State x0;
  if constexpr (Plant::kPrecession) {
    x0 = Plant::make_state(s.alpha0, s.beta0, s.H);
  } else if constexpr (Plant::kElastic) {
    x0 = Plant::make_state(s.alpha0, s.beta0, 0, 0, s.H, s.alpha0, 0);
  } else {
    x0 = Plant::make_state(s.alpha0, s.beta0, 0, 0, s.H);
  }
  const dynamics::Mode mode = dynamics::fastest_mode(plant, 0.0, x0);
  const auto method = s.loop.integrator == "rk4" ? dynamics::Method::kRk4 : dynamics::Method::kGyroExponential;
  const double h = s.loop.tick_s() / s.loop.substeps;
  const dynamics::StepCheck step = dynamics::check_step(method, mode, h);
  if (!step.ok) r.fail("loop", "plant_substeps", step.message);
  if (s.dc_drive) {
    const drives::GimbalDrive d(s.drive);
    const double J1 = Plant::kElastic ? s.plant_platform.AP : l.A, J2 = l.B;
    const double h_max = std::min(d.max_stable_step(J1), d.max_stable_step(J2));
    if (!(h < h_max)) {
      r.fail("loop", "plant_substeps",
             "plant step " + std::to_string(h) + " s is beyond the explicit drive coupling's stable step 2J/(b + b_e) = " +
                 std::to_string(h_max) + " s (gimbal_drive.hpp): use more sub-steps");
    }
  }
  return r.ok();
}

// fidelity = "precession": where P0 holds (digest gyro-fundamentals §8: ε = ω_P/ω_N ≪ 1, no gimbal lock, no
// drive on a gimbal axis), the expected error, and the full model's loop for the comparison run (the
// sub-steps its own step validation needs: the step ratio ≈ 1/ε is P0's saving).
template <class Motor>
bool check_reduced(SceneReader& r, PowerScene& s) {
  if (s.dc_drive) {
    r.fail("drive", "kind",
           "fidelity = \"precession\" (P0) drops the gimbal inertia that a drive on a gimbal axis acts on (the "
           "drive's stick and its stable step need it): use [drive] kind = \"torque\", or fidelity = \"full\"");
    return false;
  }
  if (!check_plant<Motor, models::RigidStructure, models::PrecessionOnly>(r, s)) return false;
  using Full = models::PowerStabilizer<Base, Motor, models::RigidStructure, models::FullGimbal>;
  Motor motor{};
  if constexpr (Full::kVoltageDriven) motor = s.motor;
  const Full full(s.plant_gyro, motor, {}, s.base);
  const auto& l = s.controller.loops;
  const bool torque = l.output == firmware::PowerStabilizerOutput::kTorque;
  // Worst operating point for P0: the larger |β| of the initial angle and the steady deflection.
  const double beta_ss = torque ? (l.k1 > 0 ? s.disturbance.M1 / l.k1 : 0.0) : s.disturbance.M1 / (l.r * l.s);
  const double beta_op = std::max(std::abs(s.beta0), std::abs(beta_ss));
  const firmware::PowerStabilizerConfig lo = loops_at(full, l, beta_op);
  const double B = l.B, A = lo.A, He = lo.H;
  const double omega_N = He / std::sqrt(A * B);
  // The slow roots of (14.23) → precession theory (14.24): λ = −k1/H, −k2/H; of (14.29): −r s/H.
  const double omega_P = torque ? std::max(std::abs(l.k1), std::abs(l.k2)) / He : l.r * l.s / He;
  const double eps = omega_P / omega_N;
  constexpr double kEpsMax = 0.1;
  if (!(eps < kEpsMax)) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "the precession model P0 does not hold here: eps = omega_P/omega_N = %.3g (omega_P = %.4g rad/s, "
                  "omega_N = %.4g rad/s at beta = %.4g deg%s) is not << 1 (refused at eps >= %.2g; P0's error is "
                  "O(eps), digest gyro-fundamentals §8)%s",
                  eps, omega_P, omega_N, beta_op * 180.0 / std::numbers::pi,
                  beta_op > 1.0 ? ", near gimbal lock where P0 is singular: H cos beta -> 0" : "", kEpsMax,
                  beta_op > 1.0 ? "; use fidelity = \"full\"" : "; use fidelity = \"full\" or a faster rotor");
    r.fail("gyro", "fidelity", buf);
    return false;
  }
  // Digest §8 (torque step M on an astatic gyro): the torqued axis offsets by ≤ 2 M I_other/H², the other
  // axis errs by ≤ M/(H ω_N); the O(ε) error of the slow (precession) response, ε · M/k = M/(H ω_N) per step,
  // adds to both. A base rolling at Φ sin νt about axis i acts like a torque I_i Φ ν² on that axis.
  double M1 = std::abs(s.disturbance.M1), M2 = std::abs(s.disturbance.M2);
  const double roll_torque = s.base.amplitude * s.base.frequency * s.base.frequency;
  if (s.base.axis_B.x() != 0.0) M1 += A * roll_torque; else M2 += B * roll_torque;
  const double cross = (M1 + M2) / (He * omega_N);
  const double a_bound = 2.0 * M1 * B / (He * He) + cross;
  const double b_bound = 2.0 * M2 * A / (He * He) + cross;
  s.reduced_expected = {{"model", "precession (engineering) theory P0, (10.19)-(10.22)"},
                        {"full_model", "gimbal gyro (10.4), nutation resolved"},
                        {"epsilon", eps},
                        {"omega_P_rad_s", omega_P},
                        {"omega_N_rad_s", omega_N},
                        {"nutation_over_precession", 1.0 / eps},
                        {"operating_point_beta_rad", beta_op},
                        {"torque_step_alpha_offset_bound_rad", 2.0 * M1 * B / (He * He)},
                        {"torque_step_beta_offset_bound_rad", 2.0 * M2 * A / (He * He)},
                        {"precession_error_bound_rad", cross},
                        {"alpha_rad_bound", a_bound},
                        {"beta_rad_bound", b_bound},
                        {"bounds_from", "digest gyro-fundamentals §8: |alpha| <= 2MB/H^2, |beta - Mt/H| <= M/(H omega_N); "
                                        "relative error O(eps) of the precession response"}};
  // The full model's loop: its default integrator, with the sub-steps its step validation asks for.
  s.full_loop = s.loop;
  s.full_loop.integrator = "gyro-exponential";
  const dynamics::Mode mode = dynamics::fastest_mode(full, 0.0, Full::make_state(s.alpha0, s.beta0, 0, 0, s.H));
  const dynamics::StepCheck step = dynamics::check_step(dynamics::Method::kGyroExponential, mode, s.loop.tick_s());
  s.full_loop.substeps = std::max(1, step.substeps_needed);
  if (s.full_loop.substeps > 100000) {
    r.fail("gyro", "fidelity", "the full model for the comparison would need more than 100000 sub-steps: " + step.message);
  }
  s.reduced_expected["full_model_plant_substeps"] = s.full_loop.substeps;
  s.reduced_expected["reduced_model_plant_substeps"] = s.loop.substeps;
  return r.ok();
}

// The CSV columns of the scene's variant (they depend on the drive, the motor and the structure only).
std::vector<std::string> scene_columns(const PowerScene& s) {
  using models::BackEmfMotor, models::TorqueMotors, models::ElasticPlatform, models::RigidStructure;
  if (s.elastic) {
    if (s.back_emf) return PowerStabilizerDevice<BackEmfMotor, ElasticPlatform, false, dynamics::Rk4>::columns();
    if (s.dc_drive) return PowerStabilizerDevice<TorqueMotors, ElasticPlatform, true, dynamics::Rk4>::columns();
    return PowerStabilizerDevice<TorqueMotors, ElasticPlatform, false, dynamics::Rk4>::columns();
  }
  if (s.back_emf) return PowerStabilizerDevice<BackEmfMotor, RigidStructure, false, dynamics::Rk4>::columns();
  if (s.dc_drive) return PowerStabilizerDevice<TorqueMotors, RigidStructure, true, dynamics::Rk4>::columns();
  return PowerStabilizerDevice<TorqueMotors, RigidStructure, false, dynamics::Rk4>::columns();
}

bool validate_plant(SceneReader& r, PowerScene& s);

bool validate(SceneReader& r, PowerScene& s) {
  if (!read_scene(r, s)) return false;
  // [output] signals: refused here (by `gyrostab check` too) with the variant's valid names.
  const std::string bad = Recorder::check_signals(scene_columns(s), s.loop.signals);
  if (!bad.empty()) r.fail("output", "signals", bad);
  return validate_plant(r, s) && r.ok();
}

bool validate_plant(SceneReader& r, PowerScene& s) {
  if (s.precession) {
    return s.back_emf ? check_reduced<models::BackEmfMotor>(r, s) : check_reduced<models::TorqueMotors>(r, s);
  }
  if (s.elastic) {
    return s.back_emf ? check_plant<models::BackEmfMotor, models::ElasticPlatform>(r, s)
                      : check_plant<models::TorqueMotors, models::ElasticPlatform>(r, s);
  }
  return s.back_emf ? check_plant<models::BackEmfMotor, models::RigidStructure>(r, s)
                    : check_plant<models::TorqueMotors, models::RigidStructure>(r, s);
}

template <class Motor, class Structure, bool kDcDrive, template <class> class Integrator>
int run_with(const PowerScene& scene, const RunRequest& req) {
  using Device = PowerStabilizerDevice<Motor, Structure, kDcDrive, Integrator>;
  auto device = std::make_unique<Device>(scene);
  return run_device(*device, scene.loop, req);
}

// Integrator, then drive: the elastic variant runs under Rk4 only (validated at read time).
template <class Motor, class Structure, bool kDcDrive>
int run_integrator(const PowerScene& scene, const RunRequest& req) {
  if constexpr (Structure::kExtraStates > 0) {
    return run_with<Motor, Structure, kDcDrive, dynamics::Rk4>(scene, req);
  } else {
    if (scene.loop.integrator == "rk4") return run_with<Motor, Structure, kDcDrive, dynamics::Rk4>(scene, req);
    return run_with<Motor, Structure, kDcDrive, dynamics::GyroscopicExponential>(scene, req);
  }
}

template <class Structure>
int run_structure(const PowerScene& scene, const RunRequest& req) {
  if (scene.back_emf) return run_integrator<models::BackEmfMotor, Structure, false>(scene, req);
  if (scene.dc_drive) return run_integrator<models::TorqueMotors, Structure, true>(scene, req);
  return run_integrator<models::TorqueMotors, Structure, false>(scene, req);
}

// fidelity = "precession": the full model on the same scene first (its α, β traced), then P0 compared with it
// tick by tick (tools/run/model_comparison.hpp). Another role (plant/controller process, replay) runs P0 alone.
template <class Motor>
int run_reduced(const PowerScene& scene, const RunRequest& req) {
  using Reduced = PowerStabilizerDevice<Motor, models::RigidStructure, false, dynamics::Rk4, models::PrecessionOnly>;
  using Full = PowerStabilizerDevice<Motor, models::RigidStructure, false, dynamics::GyroscopicExponential>;
  auto reduced = std::make_unique<Reduced>(scene);
  if (req.role != Role::kInProcess) return run_device(*reduced, scene.loop, req);
  auto full_scene = std::make_unique<PowerScene>(scene);
  full_scene->loop = scene.full_loop;
  auto full = std::make_unique<Full>(*full_scene);
  LoopConfig cfg = full_scene->loop;
  if (req.ticks >= 0) cfg.duration_s = static_cast<double>(req.ticks) * cfg.tick_s();
  auto trace = std::make_unique<ComparisonTrace>();
  trace->size_for(cfg.ticks(), Full::kComparedSignals);
  TracingDevice<Full> tracing(*full, *trace);
  const LoopOutcome fo = run_closed_loop(tracing, cfg, nullptr, false);
  auto setup = std::make_unique<ComparisonSetup>();
  setup->expected = scene.reduced_expected;
  setup->full_wall_s = fo.wall_s;
  setup->full_ticks = fo.ticks_run;
  setup->full_diverged = fo.diverged;
  setup->full_diverged_tick = fo.diverged_tick;
  setup->full_substeps = cfg.substeps;
  setup->full_integrator = cfg.integrator;
  auto compare = std::make_unique<ComparingDevice<Reduced>>(*reduced, *trace, *setup);
  return run_device(*compare, scene.loop, req);
}

}  // namespace

int run_power_stabilizer(SceneReader& reader, const RunRequest& req) {
  auto scene = std::make_unique<PowerScene>();
  if (!validate(reader, *scene)) return 2;
  if (req.check_only) return 0;
  if (scene->precession) {
    return scene->back_emf ? run_reduced<models::BackEmfMotor>(*scene, req) : run_reduced<models::TorqueMotors>(*scene, req);
  }
  if (scene->elastic) return run_structure<models::ElasticPlatform>(*scene, req);
  return run_structure<models::RigidStructure>(*scene, req);
}

}  // namespace gyrostab::tools

// The accuracy study's view of a scene (power_stabilizer_study.hpp): the rigid plant with torque motors only
// (the variants that add states or step a drive inside the tick are not in the study yet).
namespace gyrostab::tools {
namespace {

template <template <class> class Integrator>
int record_study_inputs(const PowerScene& scene, const LoopConfig& loop, PowerStabilizerStudySetup& out) {
  using Device = PowerStabilizerDevice<models::TorqueMotors, models::RigidStructure, false, Integrator>;
  auto device = std::make_unique<Device>(scene);
  const std::int64_t ticks = loop.ticks();
  out.inputs.reserve(static_cast<std::size_t>(ticks));
  out.states.reserve(static_cast<std::size_t>(ticks));
  auto tap = accuracy::make_input_tap(*device, [&out](const Device& d, std::int64_t) {
    out.inputs.push_back(d.plant().inputs);
    out.states.push_back(d.state());
  });
  const LoopOutcome o = run_closed_loop(tap, loop, nullptr);
  out.closed_loop_wall_s = o.wall_s;
  return o.diverged ? 3 : 0;
}

}  // namespace

int power_stabilizer_study_setup(SceneReader& reader, std::int64_t ticks, PowerStabilizerStudySetup& out,
                                 std::string& why) {
  auto scene = std::make_unique<PowerScene>();
  if (!validate(reader, *scene)) return 2;
  if (scene->elastic || scene->back_emf || scene->dc_drive || scene->precession) {
    why = "the accuracy study takes the rigid power stabilizer with torque motors; this scene has " +
          std::string(scene->elastic      ? "an elastic platform"
                      : scene->back_emf   ? "a back-EMF motor"
                      : scene->dc_drive   ? "dc drives"
                                          : "the precession model (fidelity = \"precession\")");
    return 4;
  }
  out.loop = scene->loop;
  out.scene_duration_s = scene->loop.duration_s;
  if (ticks >= 0) out.loop.duration_s = static_cast<double>(ticks) * out.loop.tick_s();
  out.plant_gyro = scene->plant_gyro;
  out.base = scene->base;
  out.H = scene->H;
  if (scene->loop.integrator == "rk4") return record_study_inputs<dynamics::Rk4>(*scene, out.loop, out);
  return record_study_inputs<dynamics::GyroscopicExponential>(*scene, out.loop, out);
}

}  // namespace gyrostab::tools
