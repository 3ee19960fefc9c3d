// The Schuler-tuned inertial platform as it runs in a scene (Magnus ch. 16, (16.1)-(16.50)): the single-axis
// platform of Fig. 16.9 on the book's great circle over a non-rotating Earth (track trihedron T), or a
// three-axis local-level platform in the azimuth-free trihedron F of a vehicle over the rotating Earth
// (sim/models/inertial_platform.hpp; motion sim/motion/earth_vehicle.hpp fed per tick by
// vehicle_frame_feed.hpp, the raw specific force: the platform levels to the geocentric vertical), held by
// three rate-integrating gyros with their cross-coupling (16.11)-(16.13) (or decoupled, the large-H/d limit)
// or by two position gyros (16.19)-(16.21) (sim/models/inertial_platform_position_gyros.hpp) and the analog
// servos, integrated by RK4 with the scene's sub-steps; and its
// sensors: integrating (Δv) accelerometers, read as the apparent tilt θ = specific force / g0 averaged over
// the previous tick (the trapezoid between the tick's ends: exact for the frame's linear motion within the
// tick, O(T²) in the platform's own; white noise), and the gyro pick-offs.
// Start: the tilt e(0) of the scene, the platform turning with the level frame, each gyro at its servo
// offset (16.2) — for three axes the gyro angles at which the platform rests while it turns with the level
// frame under the torquers that hold it there (with the coupling's offsets, (16.15), (16.22)).
//
// State: single axis [e (rad), ω_P (rad/s), β (rad), β' (rad/s)]; three axes [e1..3 (rad), ω_P1..3 (rad/s),
// β1..3 (rad), β'1..3 (rad/s)]. Frames: the inertial platform's own (tools/devices/inertial_platform/
// inertial_platform_signals.toml, docs/icd/inertial_platform.md): in, torquer1_Nm, torquer2_Nm = the level
// channels' gyro torquer commands M^K [N m] (three axes: the azimuth gyro's is 0 — F has no vertical rate);
// out, theta1_rad (, theta2_rad for three axes) = the channels' apparent tilts θ [rad]; gyro_angle<i>_rad,
// gyro_rate<i>_rad_s = the pick-off angle and rate that stabilize channel i (integrating gyros: β_i; position
// gyros: α^Y for channel 1, β^X for channel 2); a single axis leaves channel 2's values 0.
// Torquers of the position gyros: channel 1 torques gyro Y's inner axis, channel 2 gyro X's outer axis, wired so
// that M = −H ω_cmd turns the platform at ω_cmd as with the integrating gyros (the firmware is the same).
// Random streams of the scene seed (seeded_rng.hpp): 1, 2 the accelerometers of channels 1, 2.
// Allocation-free after construction. Docs: docs/models/inertial-platform.md. Oracle:
// tests/oracle/inertial_platform_test.cpp (the models); this plant in the shipped scenes through
// tests/determinism/scene_determinism_test.cpp and tests/alloc/scene_alloc_test.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/inertial_platform_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/inertial_platform.hpp"
#include "sim/models/inertial_platform_position_gyros.hpp"
#include "sim/motion/vehicle_motion.hpp"
#include "sim/plants/instrument_frames.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/plants/vehicle_frame_feed.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

struct PlatformAxisSetup {
  models::PlatformAxisParams params{};
  double tilt0{0.0};  // initial tilt e(0) [rad]
};

// Which gyros hold the three-axis platform: three rate-integrating (Fig. 16.4) or two position gyros (Fig. 16.5).
enum class PlatformGyros : int { kThreeIntegrating = 0, kTwoPosition = 1 };

struct InertialPlatformPlantParams {
  int axes{3};  // 1: single-axis (Fig. 16.9), 3: three-axis
  PlatformGyros gyros{PlatformGyros::kThreeIntegrating};
  models::PlatformCoupling coupling{models::PlatformCoupling::kFull};  // three integrating gyros
  motion::VehicleMotionParams vehicle{.start = {.latitude = std::numbers::pi / 180.0 * 45.0}};
  PlatformAxisSetup axis[3]{};      // axes 1, 2 (level), 3 (up); the single axis uses axis 1
  double gravity_gradient{0.0};     // single axis: (3g/R)(B_p − C_p) of (16.30) [N m/rad]
  double accel_noise_density{0.0};  // accelerometer white noise [m/s²/√Hz]
};

using InertialPlatformSensorFrame = msg::inertial_platform::SensorFrame;
using InertialPlatformActuatorFrame = msg::inertial_platform::ActuatorFrame;

// The platforms behind one interface: frame, torquers, channel tilts, apparent tilts, gyro outputs.
template <class Model>
struct PlatformAxes;

template <>
struct PlatformAxes<models::SingleAxisPlatform> {
  using M = models::SingleAxisPlatform;
  static constexpr int kChannels = 1;
  static constexpr std::array<const char*, M::kStateSize> kStateNames{"tilt_rad", "platform_rate_rad_s",
                                                                      "gyro_angle_rad", "gyro_rate_rad_s"};
  static models::FrameSample frame(const motion::EarthVehicleSample& m) { return frame_as_is(m.track); }
  static void set_torquers(M& p, const InertialPlatformActuatorFrame& cmd) { p.inputs.torquer = cmd.torquer1_Nm; }
  static double tilt(const M::State& x, int) { return x[M::kTilt]; }
  static double frame_rate(const models::FrameSample& w, int) { return w.Omega.y(); }
  static void apparent(const M& p, double t, const M::State& x, double (&theta)[2]) {
    theta[0] = p.apparent_tilt(t, x);
    theta[1] = 0.0;
  }
  static double gyro_angle(const M::State& x, int) { return x[M::kGyroAngle]; }
  static double gyro_rate(const M::State& x, int) { return x[M::kGyroRate]; }
  static M::State initial(const InertialPlatformPlantParams& p, const models::FrameSample& w) {
    const models::PlatformAxisParams& a = p.axis[0].params;
    M::State x;
    x << p.axis[0].tilt0, w.Omega.y(), a.disturbance / a.k, 0.0;
    return x;
  }
  static M make(const InertialPlatformPlantParams& p) { return M({p.axis[0].params, p.gravity_gradient}); }
};

template <>
struct PlatformAxes<models::ThreeAxisPlatform> {
  using M = models::ThreeAxisPlatform;
  static constexpr int kChannels = 2;
  static constexpr std::array<const char*, M::kStateSize> kStateNames{"tilt1_rad",
                                                                      "tilt2_rad",
                                                                      "tilt3_rad",
                                                                      "platform_rate1_rad_s",
                                                                      "platform_rate2_rad_s",
                                                                      "platform_rate3_rad_s",
                                                                      "gyro_angle1_rad",
                                                                      "gyro_angle2_rad",
                                                                      "gyro_angle3_rad",
                                                                      "gyro_rate1_rad_s",
                                                                      "gyro_rate2_rad_s",
                                                                      "gyro_rate3_rad_s"};
  static models::FrameSample frame(const motion::EarthVehicleSample& m) {
    return frame_as_is(m.azimuth_free);
  }
  static void set_torquers(M& p, const InertialPlatformActuatorFrame& cmd) {
    p.inputs.torquer[0] = cmd.torquer1_Nm;
    p.inputs.torquer[1] = cmd.torquer2_Nm;
    p.inputs.torquer[2] = 0.0;  // azimuth: the frame has no vertical rate
  }
  static double tilt(const M::State& x, int i) { return x[M::kTilt + i]; }
  static double frame_rate(const models::FrameSample& w, int i) { return w.Omega[i]; }
  static void apparent(const M& p, double t, const M::State& x, double (&theta)[2]) {
    p.apparent_tilts(t, x, theta[0], theta[1]);
  }
  static double gyro_angle(const M::State& x, int i) { return x[M::kGyroAngle + i]; }
  static double gyro_rate(const M::State& x, int i) { return x[M::kGyroRate + i]; }
  static M::State initial(const InertialPlatformPlantParams& p, const models::FrameSample& w) {
    M::State x = M::State::Zero();
    const dynamics::Vec3 e(p.axis[0].tilt0, p.axis[1].tilt0, p.axis[2].tilt0);
    x.segment<3>(M::kTilt) = e;
    x.segment<3>(M::kPlatformRate) = w.Omega + w.Omega.cross(e);
    const std::array<double, 3> h = holding(p, x.segment<3>(M::kPlatformRate));
    const double m[3] = {h[0], h[1], h[2]};
    x.segment<3>(M::kGyroAngle) = make(p).resting_gyro_angles(x.segment<3>(M::kPlatformRate), m);
    return x;
  }
  static M make(const InertialPlatformPlantParams& p) {
    models::ThreeAxisPlatformParams q;
    for (int i = 0; i < 3; ++i) q.axis[i] = p.axis[i].params;
    q.coupling = p.coupling;
    return M(q);
  }
  // The level channels' torquers that turn the platform at ω: M = −H (ω − ε); the azimuth gyro's is 0.
  static std::array<double, 3> holding(const InertialPlatformPlantParams& p, const dynamics::Vec3& omega) {
    std::array<double, 3> m{0.0, 0.0, 0.0};
    for (int i = 0; i < 2; ++i) m[i] = -p.axis[i].params.H * (omega[i] - p.axis[i].params.drift);
    return m;
  }
};

template <>
struct PlatformAxes<models::TwoPositionGyroPlatform> {
  using M = models::TwoPositionGyroPlatform;
  static constexpr int kChannels = 2;
  static constexpr std::array<const char*, M::kStateSize> kStateNames{
      "tilt1_rad",          "tilt2_rad",          "tilt3_rad",          "platform_rate1_rad_s",
      "platform_rate2_rad_s", "platform_rate3_rad_s", "alpha_x_rad",        "beta_x_rad",
      "alpha_y_rad",        "beta_y_rad",         "alpha_x_rate_rad_s", "beta_x_rate_rad_s",
      "alpha_y_rate_rad_s", "beta_y_rate_rad_s"};
  static models::FrameSample frame(const motion::EarthVehicleSample& m) {
    return frame_as_is(m.azimuth_free);
  }
  static void set_torquers(M& p, const InertialPlatformActuatorFrame& cmd) {
    p.inputs.torquer[0] = cmd.torquer1_Nm;
    p.inputs.torquer[1] = cmd.torquer2_Nm;
    p.inputs.torquer[2] = 0.0;
  }
  static double tilt(const M::State& x, int i) { return x[M::kTilt + i]; }
  static double frame_rate(const models::FrameSample& w, int i) { return w.Omega[i]; }
  static void apparent(const M& p, double t, const M::State& x, double (&theta)[2]) {
    p.apparent_tilts(t, x, theta[0], theta[1]);
  }
  // Channel 1 is stabilized on α^Y, channel 2 on β^X (16.21).
  static double gyro_angle(const M::State& x, int i) { return x[i == 0 ? M::kAlphaY : M::kBetaX]; }
  static double gyro_rate(const M::State& x, int i) { return x[M::kGimbalRate + (i == 0 ? 2 : 1)]; }
  static M::State initial(const InertialPlatformPlantParams& p, const models::FrameSample& w) {
    M::State x = M::State::Zero();
    const dynamics::Vec3 e(p.axis[0].tilt0, p.axis[1].tilt0, p.axis[2].tilt0);
    x.segment<3>(M::kTilt) = e;
    x.segment<3>(M::kPlatformRate) = w.Omega + w.Omega.cross(e);
    const std::array<double, 3> h = PlatformAxes<models::ThreeAxisPlatform>::holding(p, x.segment<3>(3));
    const double m[3] = {h[0], h[1], h[2]};
    x.segment<4>(M::kAlphaX) = make(p).resting_gimbal_angles(m);
    return x;
  }
  static M make(const InertialPlatformPlantParams& p) {
    models::TwoPositionGyroPlatformParams q;
    for (int i = 0; i < 3; ++i) q.axis[i] = p.axis[i].params;
    return M(q);
  }
};

template <class M>
class InertialPlatformPlant {
  using Axes = PlatformAxes<M>;

 public:
  using SensorFrame = InertialPlatformSensorFrame;
  using ActuatorFrame = InertialPlatformActuatorFrame;
  using Model = M;
  using State = typename M::State;
  using Inputs = typename M::Inputs;
  static constexpr int kChannels = Axes::kChannels;  // the level channels the Schuler loops close
  enum Stream : std::uint64_t { kAccel1Stream = 1, kAccel2Stream };

  InertialPlatformPlant(const InertialPlatformPlantParams& p, const PlantTiming& t)
      : t_(t),
        model_(Axes::make(p)),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps),
        feed_(p.vehicle, t.tick_ns, &Axes::frame),
        noise_{sensors::SensorNoise({p.accel_noise_density, 0.0, 0.0}, t.tick_s()),
               sensors::SensorNoise({p.accel_noise_density, 0.0, 0.0}, t.tick_s())},
        rng_{random::SeededRng(t.seed, kAccel1Stream), random::SeededRng(t.seed, kAccel2Stream)} {
    model_.inputs.frame.hold(feed_.frame());
    x_ = Axes::initial(p, feed_.frame());
    Axes::apparent(model_, 0.0, x_, theta_start_);
    theta_mean_[0] = theta_start_[0];
    theta_mean_[1] = theta_start_[1];
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    // The integrating accelerometers' mean over the previous tick (at tick 0 the instantaneous value).
    f.theta1_rad = theta_mean_[0] + noise_[0].sample(rng_[0]) / models::kStandardGravity;
    f.gyro_angle1_rad = Axes::gyro_angle(x_, 0);
    f.gyro_rate1_rad_s = Axes::gyro_rate(x_, 0);
    if constexpr (kChannels > 1) {
      f.theta2_rad = theta_mean_[1] + noise_[1].sample(rng_[1]) / models::kStandardGravity;
      f.gyro_angle2_rad = Axes::gyro_angle(x_, 1);
      f.gyro_rate2_rad_s = Axes::gyro_rate(x_, 1);
    }
  }

  void actuate(const ActuatorFrame& cmd) { Axes::set_torquers(model_, cmd); }

  // Integrates [k, k + 1) in three parts, so that a meter can watch the integration alone: the frame's
  // motion over the tick, the platform, then the accelerometers' mean and the move to the next tick's frame.
  void begin_tick(std::int64_t tick) { feed_.begin_tick(tick, model_.inputs.frame); }
  void integrate(std::int64_t tick) { driver_.advance_tick(tick, x_); }
  void end_tick() {
    double theta_end[2];
    Axes::apparent(model_, model_.inputs.frame.t0 + model_.inputs.frame.h, x_, theta_end);
    for (int i = 0; i < 2; ++i) theta_mean_[i] = 0.5 * (theta_start_[i] + theta_end[i]);
    if (feed_.end_tick(model_.inputs.frame)) {  // a corner: the next tick starts from the right limit
      Axes::apparent(model_, model_.inputs.frame.t0, x_, theta_start_);
    } else {
      theta_start_[0] = theta_end[0];
      theta_start_[1] = theta_end[1];
    }
  }
  void advance(std::int64_t tick) {
    begin_tick(tick);
    integrate(tick);
    end_tick();
  }

  bool finite() const { return x_.allFinite(); }

  // Channel i: the platform's tilt e_i, its gyro's output angle, and the level frame's rate about the
  // channel at the current tick's start.
  double tilt_rad(int i) const { return Axes::tilt(x_, i); }
  double gyro_angle_rad(int i) const { return Axes::gyro_angle(x_, i); }
  double frame_rate_rad_s(int i) const { return Axes::frame_rate(feed_.frame(), i); }
  // The apparent tilts θ at time t, without noise [rad].
  void apparent_tilts(double t, double (&theta)[2]) const { Axes::apparent(model_, t, x_, theta); }
  const State& state() const { return x_; }
  const Model& model() const { return model_; }
  const Inputs& inputs() const { return model_.inputs; }

  static constexpr const std::array<const char*, M::kStateSize>& state_names() { return Axes::kStateNames; }
  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = M::kStateSize;
  static const char* state_name(int i) { return Axes::kStateNames[static_cast<std::size_t>(i)]; }
  double state_value(int i) const { return x_[i]; }

 private:
  PlantTiming t_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_;
  VehicleFrameFeed<models::FrameSample (*)(const motion::EarthVehicleSample&)> feed_;
  std::array<sensors::SensorNoise, 2> noise_;
  std::array<random::SeededRng, 2> rng_;
  double theta_start_[2]{0.0, 0.0};  // apparent tilt at the current tick's start (right limit) [rad]
  double theta_mean_[2]{0.0,
                        0.0};  // mean over the last completed tick (what the accelerometers report) [rad]
};

}  // namespace gyrostab::plants
