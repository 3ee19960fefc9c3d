// The Schuler-tuned gyro pendulum (or physical pendulum, H = 0) on a vehicle manoeuvring over the rotating
// Earth as it runs in a scene — Magnus §12.3.3, (12.52)-(12.68), and Chelnokov §2. The pivot's motion comes
// from sim/motion/earth_vehicle.hpp, one sample per tick at each end (the end's LEFT limit, so a manoeuvre
// corner on a tick boundary is exact: sim/motion/corner_clock.hpp), linear in between
// (motion::SampledReference); the reference trihedron is the azimuth-free one (12.52), with the raw specific
// force (the geocentric vertical). Or, pivot = Kepler orbit (Chelnokov §4), the suspension point in free flight
// on sim/motion/kepler_orbit.hpp's ellipse, sampled the same way in its orbital trihedron (specific force
// exactly 0: the rigid body model only, the small-angle form is written for a pivot on the Earth's sphere). The pendulum, by the scene's model:
//   magnus      small-angle (12.55)-(12.58), sim/models/gyro_pendulum_magnus.hpp; integrator gyro-exponential
//               (the nutation carried exactly: h ω^N up to 0.8·2π) or rk4
//   rigid-body  the full 3-D Newton–Euler body spinning at H/C, sim/models/schuler_pendulum.hpp; integrator
//               strang / yoshida4 (exact free-body flow + pendulous/gravity-gradient kicks) or rk4
// with the scene's sub-steps; and its sensors: the case's tilt α, β from the geocentric vertical and their
// rates, with white noise (an observer's pick-off, for the monitor and the log).
// Start: on the book's steady error (12.65), z0 = −H w0/(kR), z0' = −H w0'/(kR) (or on the vertical), plus
// the scene's tilt.
//
// State: magnus [α, β (rad), α', β' (rad/s)] (z = α + iβ: small rotations of the case about F1, F2, rotor
// axis ≈ (β, −α, 1)); rigid-body [ω_IB_B (rad/s) | q_IB (x, y, z, w)]; both are kept, the scene's model
// advances. Frames: the gyro pendulum's own (tools/devices/gyro_pendulum/gyro_pendulum_signals.toml,
// docs/icd/gyro_pendulum.md): in, torque_F1_Nm, torque_F2_Nm = extra torques M1, M2 about F1, F2 [N m] (the
// monitor commands zero); out, alpha_rad, beta_rad = α, β [rad], alpha_rate_rad_s, beta_rate_rad_s = α', β'
// [rad/s], rotor_speed_rad_s = H/C [rad/s].
// Random streams of the scene seed (seeded_rng.hpp): 1, 2 the tilt pick-offs α, β; 3, 4 their rates.
// Allocation-free after construction. Docs: docs/models/gyro-pendulum.md. Oracles:
// tests/oracle/gyro_pendulum_magnus_test.cpp, schuler_pendulum_test.cpp, gyro_pendulum_cross_test.cpp (the
// models); this plant in the shipped scene through tests/determinism/scene_determinism_test.cpp and
// tests/alloc/scene_alloc_test.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/gyro_pendulum_frames.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/rotor_splitting.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gyro_pendulum_magnus.hpp"
#include "sim/models/schuler_pendulum.hpp"
#include "sim/motion/corner_clock.hpp"
#include "sim/motion/suspension_reference.hpp"
#include "sim/motion/vehicle_motion.hpp"
#include "sim/oracles/schuler_tuning.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/sensor_noise.hpp"

namespace gyrostab::plants {

enum class GyroPendulumModel { kMagnus, kRigidBody };
enum class GyroPendulumIntegrator { kGyroExponential, kRk4, kStrang, kYoshida4 };
enum class GyroPendulumStart { kEquilibrium, kVertical };
enum class GyroPendulumPivot { kEarthVehicle, kKeplerOrbit };

struct GyroPendulumPlantParams {
  motion::VehicleMotionParams vehicle{.start = {.latitude = std::numbers::pi / 180.0 * 50.0}};
  GyroPendulumPivot pivot{GyroPendulumPivot::kEarthVehicle};
  motion::KeplerOrbitParams orbit{};  // pivot = kKeplerOrbit
  GyroPendulumModel model{GyroPendulumModel::kMagnus};
  GyroPendulumIntegrator integrator{GyroPendulumIntegrator::kGyroExponential};
  models::GyroPendulumMagnusParams gyro{.H = 0.0};  // no spin unless the scene gives one: a physical pendulum
  GyroPendulumStart start{GyroPendulumStart::kEquilibrium};
  double alpha0{0.0}, beta0{0.0};  // added initial tilt about F1, F2 [rad]
  double tilt_noise_density{0.0};  // tilt pick-off white noise [rad/√Hz]
  double rate_noise_density{0.0};  // tilt-rate pick-off white noise [rad/s/√Hz]
};

class GyroPendulumPlant {
 public:
  using SensorFrame = msg::gyro_pendulum::SensorFrame;
  using ActuatorFrame = msg::gyro_pendulum::ActuatorFrame;
  using Cplx = std::complex<double>;
  using Magnus = models::GyroPendulumMagnus<motion::SampledReference>;
  using Body = models::SchulerPendulum<motion::SampledReference>;
  // What the Magnus model holds over a tick (the half-step window's inputs).
  struct MagnusInputs {
    motion::SampledReference ref;
    double M1, M2;
  };
  enum Stream : std::uint64_t { kTilt1Stream = 1, kTilt2Stream, kRate1Stream, kRate2Stream };

  GyroPendulumPlant(const GyroPendulumPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        vehicle_(motion::make_vehicle(p.vehicle)),
        orbit_(p.orbit),
        magnus_(p.gyro, motion::SampledReference{}),
        body_(body_params(p.gyro), motion::SampledReference{}),
        gx_(magnus_),
        rk_magnus_(magnus_),
        strang_(body_),
        yoshida_(body_),
        rk_body_(body_),
        d_gx_(gx_, t.tick_ns, t.substeps),
        d_rk_magnus_(rk_magnus_, t.tick_ns, t.substeps),
        d_strang_(strang_, t.tick_ns, t.substeps),
        d_yoshida_(yoshida_, t.tick_ns, t.substeps),
        d_rk_body_(rk_body_, t.tick_ns, t.substeps),
        k_(p.gyro.k()),
        corners_(p.vehicle),
        noise_{sensors::SensorNoise({p.tilt_noise_density, 0.0, 0.0}, t.tick_s()),
               sensors::SensorNoise({p.tilt_noise_density, 0.0, 0.0}, t.tick_s()),
               sensors::SensorNoise({p.rate_noise_density, 0.0, 0.0}, t.tick_s()),
               sensors::SensorNoise({p.rate_noise_density, 0.0, 0.0}, t.tick_s())},
        rng_{random::SeededRng(t.seed, kTilt1Stream), random::SeededRng(t.seed, kTilt2Stream),
             random::SeededRng(t.seed, kRate1Stream), random::SeededRng(t.seed, kRate2Stream)} {
    current_ = kepler() ? orbit_sample(0) : sample(vehicle_.sample_ns(0));
    Cplx z0(p.alpha0, p.beta0), dz0(0.0, 0.0);
    if (p.start == GyroPendulumStart::kEquilibrium) {
      z0 += oracles::velocity_error(p.gyro.H, k_, p.gyro.R, {current_.v_Z.x(), current_.v_Z.y()});
      dz0 = oracles::velocity_error(p.gyro.H, k_, p.gyro.R, {current_.a_Z.x(), current_.a_Z.y()});
    }
    xm_ = Magnus::make_state(z0.real(), z0.imag(), dz0.real(), dz0.imag());
    const dynamics::Quat tilt = dynamics::Quat(Eigen::AngleAxisd(z0.real(), dynamics::Vec3::UnitX())) *
                                dynamics::Quat(Eigen::AngleAxisd(z0.imag(), dynamics::Vec3::UnitY()));
    xb_ = models::make_rigid_body_state(
        tilt.conjugate() * (current_.w_Z + dynamics::Vec3(dz0.real(), dz0.imag(), 0.0)) +
            dynamics::Vec3(0.0, 0.0, rotor_speed()),
        current_.q_IZ * tilt);
    observe();
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.alpha_rad = z_.real() + noise_[0].sample(rng_[0]);
    f.beta_rad = z_.imag() + noise_[1].sample(rng_[1]);
    f.alpha_rate_rad_s = dz_.real() + noise_[2].sample(rng_[2]);
    f.beta_rate_rad_s = dz_.imag() + noise_[3].sample(rng_[3]);
    f.rotor_speed_rad_s = rotor_speed();
  }

  void actuate(const ActuatorFrame& cmd) {
    magnus_.M1 = cmd.torque_F1_Nm;
    magnus_.M2 = cmd.torque_F2_Nm;
    body_.torque_ext_B = dynamics::Vec3(magnus_.M1, magnus_.M2, 0.0);  // small tilt: case ≈ F axes
  }

  // Integrates [k, k + 1) in three parts, so that a meter can watch the integration alone: the pivot's
  // motion over the tick (to the left limit at its end: the accelerations jump at corners), the pendulum,
  // then the move to the next tick's start (the right limit at a corner) and the case's angles there.
  void begin_tick(std::int64_t tick) {
    const std::int64_t t1_ns = (tick + 1) * t_.tick_ns;
    motion::SampledReference ref;
    ref.t0 = 1e-9 * static_cast<double>(tick * t_.tick_ns);  // = SubstepDriver's t0
    ref.h = t_.tick_s();
    ref.s0 = current_;
    ref.s1 = kepler() ? orbit_sample(t1_ns) : sample(vehicle_.sample_left_ns(t1_ns));
    if (magnus()) {
      magnus_.reference() = ref;
    } else {
      body_.reference() = ref;
    }
  }
  void integrate(std::int64_t tick) {
    using I = GyroPendulumIntegrator;
    if (magnus()) {
      if (p_.integrator == I::kRk4)
        d_rk_magnus_.advance_tick(tick, xm_);
      else
        d_gx_.advance_tick(tick, xm_);
    } else {
      if (p_.integrator == I::kRk4)
        d_rk_body_.advance_tick(tick, xb_);
      else if (p_.integrator == I::kYoshida4)
        d_yoshida_.advance_tick(tick, xb_);
      else
        d_strang_.advance_tick(tick, xb_);
    }
  }
  void end_tick(std::int64_t tick) {
    const std::int64_t t1_ns = (tick + 1) * t_.tick_ns;
    const motion::SampledReference& ref = magnus() ? magnus_.reference() : body_.reference();
    current_ = !kepler() && corners_.corner_at(t1_ns) ? sample(vehicle_.sample_ns(t1_ns)) : ref.s1;
    observe();
  }
  void advance(std::int64_t tick) {
    begin_tick(tick);
    integrate(tick);
    end_tick(tick);
  }

  bool finite() const { return magnus() ? xm_.allFinite() : xb_.allFinite(); }

  bool magnus() const { return p_.model == GyroPendulumModel::kMagnus; }
  bool kepler() const { return p_.pivot == GyroPendulumPivot::kKeplerOrbit; }
  // The case at the current tick's start: z = α + iβ [rad], z' [rad/s], and its tilt from the geocentric
  // vertical [rad] (|z| for the small-angle model, the exact angle for the rigid body).
  Cplx z() const { return z_; }
  Cplx dz() const { return dz_; }
  double tilt_rad() const { return tilt_; }
  // The pivot at the current tick's start: the reference trihedron, and the vehicle's speed, heading and
  // latitude (of the last generator sample: the left limit at a corner's tick end) [m/s, rad].
  const motion::SuspensionSample& pivot() const { return current_; }
  double speed_m_s() const { return speed_; }
  double heading_rad() const { return heading_; }
  double latitude_rad() const { return latitude_; }
  double k_Nm_per_rad() const { return k_; }  // (12.57)
  const Magnus::State& magnus_state() const { return xm_; }
  const Body::State& body_state() const { return xb_; }
  const Magnus& magnus_model() const { return magnus_; }
  MagnusInputs magnus_inputs() const { return {magnus_.reference(), magnus_.M1, magnus_.M2}; }

  // The runtime guard's names (tools/loop/state_guard.hpp): the Magnus state, then the rigid body's (only the
  // scene's model advances; the other stays at its start).
  static constexpr int kGuardedStates = Magnus::kStateSize + Body::kStateSize;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"alpha_rad",        "beta_rad",         "alpha_rate_rad_s",
                                 "beta_rate_rad_s",  "body_rate1_rad_s", "body_rate2_rad_s",
                                 "body_rate3_rad_s", "attitude_x",       "attitude_y",
                                 "attitude_z",       "attitude_w"};
    return n[i];
  }
  double state_value(int i) const { return i < Magnus::kStateSize ? xm_[i] : xb_[i - Magnus::kStateSize]; }

 private:
  static models::SchulerPendulumParams body_params(const models::GyroPendulumMagnusParams& g) {
    models::SchulerPendulumParams p;
    p.inertia = dynamics::Vec3(g.A, g.A, g.C > 0.0 ? g.C : g.A * 1e-9);
    p.ml = g.m * g.s;
    p.gravity_gradient = g.gravity_gradient;
    p.gradient_inertia = dynamics::Vec3(g.A, g.A, g.C);
    return p;
  }
  double rotor_speed() const { return p_.gyro.C > 0.0 ? p_.gyro.H / p_.gyro.C : 0.0; }
  motion::SuspensionSample sample(const motion::EarthVehicleSample& v) {
    speed_ = v.speed;
    heading_ = v.heading;
    latitude_ = v.latitude;
    const motion::EarthParams& e = vehicle_.earth();
    return motion::suspension_from(v.azimuth_free, e.gravity / e.radius);
  }
  // The orbit at t_ns: its orbital trihedron; speed = |v|, heading 0, latitude of the radius vector
  // (declination in the inertial frame).
  motion::SuspensionSample orbit_sample(std::int64_t t_ns) {
    const motion::KeplerSample k = orbit_.sample(1e-9 * static_cast<double>(t_ns));
    speed_ = k.v_I.norm();
    heading_ = 0.0;
    latitude_ = std::asin(std::clamp(k.p_I.z() / k.radius, -1.0, 1.0));
    return motion::suspension_from(k.orbital, orbit_.params().gm / (k.radius * k.radius * k.radius));
  }
  void observe() {
    if (magnus()) {
      z_ = Cplx(xm_[Magnus::kAlpha], xm_[Magnus::kBeta]);
      dz_ = Cplx(xm_[Magnus::kAlphaRate], xm_[Magnus::kBetaRate]);
      tilt_ = std::abs(z_);
    } else {
      double a, b;
      Body::magnus_angles(current_, xb_, a, b);
      z_ = Cplx(a, b);
      const Eigen::Map<const dynamics::Quat> q_IB(xb_.data() + Body::kAttitude);
      const dynamics::Vec3 w_rel =
          current_.q_IZ.conjugate() *
              (q_IB * dynamics::Vec3(xb_[Body::kBodyRate], xb_[Body::kBodyRate + 1], 0.0)) -
          current_.w_Z;
      dz_ = Cplx(w_rel.x(), w_rel.y());
      tilt_ = Body::tilt(current_, xb_);
    }
  }

  const GyroPendulumPlantParams& p_;
  PlantTiming t_;
  motion::VehicleGenerator vehicle_;
  motion::KeplerOrbit orbit_;
  Magnus magnus_;
  Body body_;
  dynamics::GyroscopicExponential<Magnus> gx_;
  dynamics::Rk4<Magnus> rk_magnus_;
  dynamics::RotorStrang<Body> strang_;
  dynamics::RotorYoshida4<Body> yoshida_;
  dynamics::Rk4<Body> rk_body_;
  dynamics::SubstepDriver<dynamics::GyroscopicExponential<Magnus>> d_gx_;
  dynamics::SubstepDriver<dynamics::Rk4<Magnus>> d_rk_magnus_;
  dynamics::SubstepDriver<dynamics::RotorStrang<Body>> d_strang_;
  dynamics::SubstepDriver<dynamics::RotorYoshida4<Body>> d_yoshida_;
  dynamics::SubstepDriver<dynamics::Rk4<Body>> d_rk_body_;
  double k_;
  Magnus::State xm_{Magnus::State::Zero()};
  Body::State xb_{Body::State::Zero()};
  motion::SuspensionSample current_{};
  motion::CornerClock corners_;
  std::array<sensors::SensorNoise, 4> noise_;
  std::array<random::SeededRng, 4> rng_;
  Cplx z_{0.0, 0.0}, dz_{0.0, 0.0};
  double tilt_{0.0}, speed_{0.0}, heading_{0.0}, latitude_{0.0};
};

}  // namespace gyrostab::plants
