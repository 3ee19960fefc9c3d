// The two-axis power gyro stabilizer as it runs in a scene (Magnus §14.3, (14.19)-(14.40)): the gimbal gyro
// of sim/models/power_stabilizer.hpp on a moving base (sim/motion/scene_base_motion.hpp), disturbance torque steps on both axes,
// and the sensors the firmware reads — gimbal encoders (or, with DC drives, the motor-side encoders) and a
// rate gyro per gimbal axis. The options are template parameters, chosen once at start-up, so an option that
// is off costs nothing:
//   Motor       TorqueMotors (the law's torques act) or BackEmfMotor (the voltage law (14.26)-(14.27))
//   Structure   RigidStructure or ElasticPlatform (14.31)
//   kDcDrive    GimbalDrive on both axes (sim/drives: DC motor L, R, k_t, k_e, limits, gear, stick-slip bearing,
//               motor-side encoder), coupled explicitly per plant step, drive first (gimbal_drive.hpp)
//   Integrator  dynamics::GyroscopicExponential or dynamics::Rk4
//   Fidelity    FullGimbal (10.4) or PrecessionOnly, the reduced model P0 (10.19)-(10.22)
//
// State: models::PowerStabilizer's [α, β, α', β', H (, φ, φ')] (rad, rad/s, N m s), named accessors below;
// the precession model has [α, β, H] and its rates are outputs. Frames: the power stabilizer's own
// (tools/devices/power_stabilizer/power_stabilizer_signals.toml, docs/icd/power_stabilizer.md): in,
// motor1_torque_Nm, motor2_torque_Nm (torque motors), motor1_voltage_V (back-EMF), motor1_voltage_V and
// motor2_voltage_V (DC drives; their torques with a current-regulated drive); out, encoder1_count,
// encoder2_count and alpha_rad, beta_rad from them, alpha_rate_rad_s, beta_rate_rad_s (rate gyros),
// rotor_speed_rad_s; with DC drives motor1_current_A, motor2_current_A and a drive fault in the status.
// Random streams of the scene seed: 1 the axis-1 rate gyro, 2 the axis-2 rate gyro.
// The defaults of the parameters below are the scene's (docs/scenes.md#power_stabilizer).
// Allocation-free after construction. Docs: docs/models/power-stabilizer.md. Oracles:
// tests/oracle/power_stabilizer_test.cpp (the model), tests/oracle/gimbal_drive_test.cpp (the drives),
// tests/stiff/plant_composition_test.cpp (what each option adds to the loop).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <type_traits>

#include "firmware/msg/fault_bits.hpp"
#include "gyrostab_signals/power_stabilizer_frames.hpp"
#include "sim/analysis/drive_peaks.hpp"
#include "sim/drives/gimbal_drive.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/base_motion.hpp"
#include "sim/models/power_stabilizer.hpp"
#include "sim/motion/scene_base_motion.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/encoder.hpp"
#include "sim/sensors/rate_gyro.hpp"

namespace gyrostab::plants {

struct PowerDisturbance {
  double M1{0.0}, M2{0.0};  // step heights on axis 1 / axis 2 [N m]
  double t1{1.0}, t2{1.0};  // step times [s]
};

inline sensors::RateGyroParams power_stabilizer_rate_gyro() {
  sensors::RateGyroParams g;
  g.noise.white_density = 1e-4;  // [rad/s/√Hz]
  return g;
}

inline drives::GimbalDriveParams power_stabilizer_drive() {
  drives::GimbalDriveParams d;
  d.command = drives::GimbalDriveParams::Command::kVoltage;
  d.motor.J_m = 0.0;
  d.encoder = {4096, 0.0, sensors::EncoderParams::Mode::kIncremental, sensors::EncoderParams::Rounding::kNearest};
  return d;
}

struct PowerStabilizerPlantParams {
  // The gyro as integrated: with DC drives the reflected inertias are added (axis 1: A^A, or A^P when elastic;
  // axis 2: B^J) and a driven bearing's damping moves into the drive's friction.
  models::GimbalGyroParams gyro{};
  double H{200.0};  // rotor spin momentum [N m s]
  motion::SceneBaseMotion base{};  // harmonic roll (amplitude 0: at rest), prescribed or recorded
  PowerDisturbance disturbance{};
  sensors::RateGyroParams rate_gyro{power_stabilizer_rate_gyro()};  // both gimbal axes
  std::int64_t encoder_counts_per_rev{1 << 18};                      // gimbal encoders (torque drives)
  drives::GimbalDriveParams drive{power_stabilizer_drive()};         // both axes, when kDcDrive
  models::BackEmfMotor motor{2.0, 0.25, 1.0, 0.0};                   // axis 1, when the motor is BackEmfMotor
  models::ElasticPlatform platform{};                                // as integrated, when elastic
  double alpha0{0.0}, beta0{0.0};                                    // initial gimbal angles, at rest [rad]
};

// Stand-ins for the drives when the scene has none: empty, so an option that is off has no storage (two
// distinct types: [[no_unique_address]] members of one type would still need distinct addresses).
template <int kAxis>
struct NoGimbalDrive {
  explicit NoGimbalDrive(const drives::GimbalDriveParams&) {}
};

template <class Motor, class Structure, bool kDcDrive, template <class> class Integrator,
          class Fidelity = models::FullGimbal>
class PowerStabilizerPlant {
 public:
  using SensorFrame = msg::power_stabilizer::SensorFrame;
  using ActuatorFrame = msg::power_stabilizer::ActuatorFrame;
  using Model = models::PowerStabilizer<motion::SceneBaseMotion, Motor, Structure, Fidelity>;
  using State = typename Model::State;
  using Inputs = models::PowerStabilizerInputs;
  static constexpr bool kElastic = Model::kElastic;
  static constexpr bool kBackEmf = Model::kVoltageDriven;
  static constexpr bool kPrecession = Model::kPrecession;
  static constexpr bool kDrives = kDcDrive;
  static_assert(!(kPrecession && kDcDrive), "a drive on a gimbal axis needs the axis inertia P0 drops");
  // Continuous states the loop integrates: the model's, and the two winding currents of the DC drives.
  static constexpr int kLoopStateSize = Model::kStateSize + (kDcDrive ? 2 : 0);
  using Drive1 = std::conditional_t<kDcDrive, drives::GimbalDrive, NoGimbalDrive<1>>;
  using Drive2 = std::conditional_t<kDcDrive, drives::GimbalDrive, NoGimbalDrive<2>>;
  enum Stream : std::uint64_t { kRateStream1 = 1, kRateStream2 };

  PowerStabilizerPlant(const PowerStabilizerPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        model_(p.gyro, motor(p), structure(p), p.base),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        encoder_({p.encoder_counts_per_rev, 0.0, sensors::EncoderParams::Mode::kIncremental,
                  sensors::EncoderParams::Rounding::kNearest}),
        gyro1_(p.rate_gyro),
        gyro2_(p.rate_gyro),
        rng1_(t.seed, kRateStream1),
        rng2_(t.seed, kRateStream2),
        drive1_(p.drive),
        drive2_(p.drive) {
    x_ = initial_state(p);
    if constexpr (kPrecession) model_.rates(0.0, x_, rate1_, rate2_);
  }

  static State initial_state(const PowerStabilizerPlantParams& p) {
    if constexpr (kPrecession) {
      return Model::make_state(p.alpha0, p.beta0, p.H);
    } else if constexpr (kElastic) {
      return Model::make_state(p.alpha0, p.beta0, 0.0, 0.0, p.H, p.alpha0, 0.0);
    } else {
      return Model::make_state(p.alpha0, p.beta0, 0.0, 0.0, p.H);
    }
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    if constexpr (kDcDrive) {
      // Motor-side encoders (the axis-1 motor turns the platform φ when elastic); currents from the drives.
      const drives::DriveReadings r1 = drive1_.readings(x_[kAngle1]);
      const drives::DriveReadings r2 = drive2_.readings(beta_rad());
      f.motor1_current_A = r1.current_A;
      f.encoder1_count = static_cast<double>(r1.encoder_count);
      f.motor2_current_A = r2.current_A;
      f.encoder2_count = static_cast<double>(r2.encoder_count);
      if (r1.fault || r2.fault) f.status |= msg::bit(msg::SensorStatusBit::kDriveFault);
      f.alpha_rad = axis_angle(drive1_, x_[kAngle1]);
      f.beta_rad = axis_angle(drive2_, beta_rad());
    } else {
      const std::int64_t c1 = encoder_.counts(alpha_rad()), c2 = encoder_.counts(beta_rad());
      f.encoder1_count = static_cast<double>(static_cast<std::int32_t>(c1));
      f.encoder2_count = static_cast<double>(static_cast<std::int32_t>(c2));
      f.alpha_rad = encoder_.angle_of(c1);
      f.beta_rad = encoder_.angle_of(c2);
    }
    f.alpha_rate_rad_s = gyro1_.measure(alpha_rate_rad_s(), rng1_);
    f.beta_rate_rad_s = gyro2_.measure(beta_rate_rad_s(), rng2_);
    f.rotor_speed_rad_s = x_[Model::kSpin] / p_.gyro.CR;
  }

  void actuate(const ActuatorFrame& cmd) {
    if constexpr (kDcDrive) {
      drive1_.command(cmd.motor1_voltage_V, cmd.motor1_torque_Nm, cmd.status);
      drive2_.command(cmd.motor2_voltage_V, cmd.motor2_torque_Nm, cmd.status);
    } else if constexpr (kBackEmf) {
      model_.inputs.u1 = cmd.motor1_voltage_V;
      model_.inputs.M2K = 0.0;  // (14.28): no loop on axis 2
    } else {
      model_.inputs.M1K = cmd.motor1_torque_Nm;
      model_.inputs.M2K = cmd.motor2_torque_Nm;
    }
  }

  // Tick k in three parts, so that a meter can see the inputs held over the tick and the state it reached:
  // the disturbance steps of the tick; the integration (with DC drives: drive first, per plant step — probe
  // each axis's load at the step start, step the drive, hold a stuck joint, then integrate with the drive
  // torques held; `peaks` sees every step's current, voltage and gear torque); the precession model's rates
  // at the tick's end.
  void begin_tick(std::int64_t tick) {
    const double t = static_cast<double>(tick) * t_.tick_s();
    model_.inputs.M1S = t >= p_.disturbance.t1 ? p_.disturbance.M1 : 0.0;
    model_.inputs.M2S = t >= p_.disturbance.t2 ? p_.disturbance.M2 : 0.0;
  }
  void integrate(std::int64_t tick, analysis::DrivePeaks& peaks) {
    if constexpr (kDcDrive) {
      const double h = driver_.substep();
      const double t0 = 1e-9 * static_cast<double>(tick * t_.tick_ns);
      for (int k = 0; k < driver_.substeps(); ++k) {
        const double tk = t0 + k * h;
        const drives::AxisLoad load1 =
            drives::probe_axis_load(model_, model_.inputs.M1K, tk, x_, kRate1, drive1_.peak_torque());
        const drives::DriveOutput o1 = drive1_.step(h, x_[kRate1], load1);
        if (o1.hold) x_[kRate1] = 0.0;
        model_.inputs.M1K = o1.torque;
        const drives::AxisLoad load2 =
            drives::probe_axis_load(model_, model_.inputs.M2K, tk, x_, Model::kBetaRate, drive2_.peak_torque());
        const drives::DriveOutput o2 = drive2_.step(h, x_[Model::kBetaRate], load2);
        if (o2.hold) x_[Model::kBetaRate] = 0.0;
        model_.inputs.M2K = o2.torque;
        integ_.step(tk, h, x_);
        peaks.add(0, drive1_.current(), drive1_.last_interval().voltage_mean, drive1_.gear_torque());
        peaks.add(1, drive2_.current(), drive2_.last_interval().voltage_mean, drive2_.gear_torque());
      }
    } else {
      (void)peaks;
      driver_.advance_tick(tick, x_);
    }
  }
  void end_tick(std::int64_t tick) {
    if constexpr (kPrecession) {
      // P0: the rates the sensors see at the tick's end, with the inputs held over it.
      model_.rates(static_cast<double>(tick) * t_.tick_s() + t_.tick_s(), x_, rate1_, rate2_);
    } else {
      (void)tick;
    }
  }

  bool finite() const { return x_.allFinite(); }

  double alpha_rad() const { return x_[Model::kAlpha]; }
  double beta_rad() const { return x_[Model::kBeta]; }
  double alpha_rate_rad_s() const {
    if constexpr (kPrecession) {
      return rate1_;
    } else {
      return x_[Model::kAlphaRate];
    }
  }
  double beta_rate_rad_s() const {
    if constexpr (kPrecession) {
      return rate2_;
    } else {
      return x_[Model::kBetaRate];
    }
  }
  // The rate the axis-1 drive turns: the platform's when elastic, else the outer gimbal's.
  double axis1_rate_rad_s() const { return kElastic ? x_[kRate1] : alpha_rate_rad_s(); }
  double platform_rad() const requires kElastic { return x_[Model::kPlatform]; }
  // The axis-1 motor torque actually applied (back-EMF included) at time t [N m].
  double motor1_torque_Nm(double t) const { return model_.signals(x_, t).motor_torque1; }
  double disturbance1_Nm() const { return model_.inputs.M1S; }
  double disturbance2_Nm() const { return model_.inputs.M2S; }
  const Inputs& inputs() const { return model_.inputs; }
  const State& state() const { return x_; }
  const Model& model() const { return model_; }
  const Drive1& drive1() const { return drive1_; }
  const Drive2& drive2() const { return drive2_; }

  static constexpr int kGuardedStates = Model::kStateSize;
  static const char* state_name(int i) {
    if constexpr (kPrecession) {
      constexpr const char* n[] = {"alpha_rad", "beta_rad", "H_Nms"};
      return n[i];
    } else {
      constexpr const char* n[] = {"alpha_rad",   "beta_rad",     "alpha_rate_rad_s",   "beta_rate_rad_s",
                                   "H_Nms",       "platform_rad", "platform_rate_rad_s"};
      return n[i];
    }
  }
  double state_value(int i) const { return x_[i]; }

 private:
  // The axis-1 drive turns the platform when elastic (φ, φ'), else the outer gimbal (α, α').
  static constexpr int kRate1 = kElastic ? Model::kPlatformRate : Model::kAlphaRate;
  static constexpr int kAngle1 = kElastic ? Model::kPlatform : Model::kAlpha;

  static Motor motor(const PowerStabilizerPlantParams& p) {
    if constexpr (kBackEmf) {
      return p.motor;
    } else {
      (void)p;
      return Motor{};
    }
  }
  static Structure structure(const PowerStabilizerPlantParams& p) {
    if constexpr (kElastic) {
      return p.platform;
    } else {
      (void)p;
      return Structure{};
    }
  }
  // Axis angle from the motor-side encoder [rad] (counts before the 32-bit wrap of the contract).
  static double axis_angle(const drives::GimbalDrive& d, double angle) {
    const std::int64_t c = d.encoder().counts(d.gear().motor_angle(angle));
    return d.encoder().angle_of(c) / d.gear().ratio();
  }

  const PowerStabilizerPlantParams& p_;
  PlantTiming t_;
  Model model_;
  Integrator<Model> integ_;
  dynamics::SubstepDriver<Integrator<Model>> driver_;
  State x_;
  sensors::Encoder encoder_;
  sensors::RateGyro gyro1_, gyro2_;
  random::SeededRng rng1_, rng2_;
  [[no_unique_address]] Drive1 drive1_;
  [[no_unique_address]] Drive2 drive2_;
  double rate1_{0.0}, rate2_{0.0};  // P0: gimbal rates at the end of the last tick (outputs, not states)
};

}  // namespace gyrostab::plants
