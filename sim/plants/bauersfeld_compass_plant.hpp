// The two-rotor spatial compass of Bauersfeld on a vehicle over the rotating Earth, as a scene runs it
// (Magnus §13.4, (13.40)-(13.64)): sim/models/bauersfeld_compass.hpp in inertial axes, its support point on
// the vehicle of sim/motion/earth_vehicle.hpp sampled exactly at every RK4 stage (within the segment of the
// step's start: a step ending on a manoeuvre corner sees the left limit), integrated with the scene's
// sub-steps. Start: (13.64) — on the geocentric vertical with its rate — plus the scene's tilt. The
// compass has no torquer and no brake: the controller commands nothing
// (firmware/app/free_instrument_controller.hpp).
//
// State: [a1 (3) (-), a1' (3) (1/s)], inertial axes; the azimuth axis a2 = a1'/|a1'| is held per tick
// (where a1' vanishes the book's model leaves it free). Inputs: none.
// Frames: the compass's own (tools/devices/bauersfeld_compass/bauersfeld_compass_signals.toml,
// docs/icd/bauersfeld_compass.md): in, no command; out, read against the geographic trihedron (ENU) at the
// tick (ideal pick-offs):
//   sphere_roll_rad, sphere_pitch_rad, sphere_yaw_rad = 3-2-1 angles of the sphere's axes (a3, −a2, a1)
//     against north-east-down: yaw = the azimuth error of a3, pitch = elevation of a3, roll = the tilt about a3;
//   sphere_rate_rad_s = the sphere's absolute angular velocity in those axes [rad/s];
//   delta_rad = δ = δ1 = δ2, the cases' swing (one value: the linkage holds them equal); delta_rate_rad_s = δ'
//   [rad/s].
// No random streams. Allocation-free after construction. Docs: docs/models/bauersfeld-compass.md. Oracle:
// tests/oracle/bauersfeld_compass_test.cpp; the shipped scenes sim/scenes/bauersfeld-compass-*.toml run in
// tests/determinism and tests/alloc.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "gyrostab_signals/bauersfeld_compass_frames.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/bauersfeld_compass.hpp"
#include "sim/motion/vehicle_motion.hpp"
#include "sim/oracles/bauersfeld_compass.hpp"
#include "sim/plants/plant_timing.hpp"
#include "sim/plants/sensor_frame_header.hpp"

namespace gyrostab::plants {

struct BauersfeldCompassPlantParams {
  motion::VehicleMotionParams vehicle{.start = {.latitude = std::numbers::pi / 180.0 * 50.0}};
  models::BauersfeldCompassParams compass{};
  double tilt0_east{0.0}, tilt0_north{0.0};  // initial tilt of a1 from (13.64) toward east, north [rad]
};

class BauersfeldCompassPlant {
 public:
  using SensorFrame = msg::bauersfeld_compass::SensorFrame;
  using ActuatorFrame = msg::bauersfeld_compass::ActuatorFrame;
  using Vehicle = motion::VehicleGenerator;
  using Model = models::BauersfeldCompass<models::VehicleSupport<Vehicle>>;
  using Dynamics = Model;
  using State = Model::State;
  using Vec3 = dynamics::Vec3;
  struct HeldInputs {};  // none: the support's motion is the scene's, a function of time

  BauersfeldCompassPlant(const BauersfeldCompassPlantParams& p, const PlantTiming& t)
      : p_(p),
        t_(t),
        vehicle_(motion::make_vehicle(p.vehicle)),
        model_(p.compass, models::VehicleSupport<Vehicle>{&vehicle_}),
        integ_(model_),
        driver_(integ_, t.tick_ns, t.substeps) {
    const motion::EarthVehicleSample s0 = vehicle_.sample_ns(0);
    x_ = Model::start_state(s0.p_I, s0.v_I, s0.geographic.q_IZ, p.tilt0_east, p.tilt0_north);
    a2_ = s0.geographic.q_IZ * Vec3(-1.0, 0.0, 0.0);  // west: the tuned compass's a2 at rest (δ > 0)
    observe(0);
  }
  BauersfeldCompassPlant(const BauersfeldCompassPlant&) = delete;  // the model points at vehicle_
  BauersfeldCompassPlant& operator=(const BauersfeldCompassPlant&) = delete;

  void sense(std::int64_t tick, SensorFrame& f) {
    begin_sensor_frame(f, tick, t_.tick_ns);
    f.sphere_roll_rad = reading_.roll;
    f.sphere_pitch_rad = reading_.pitch;
    f.sphere_yaw_rad = reading_.yaw;
    for (int i = 0; i < 3; ++i) f.sphere_rate_rad_s[i] = body_rate_[i];
    f.delta_rad = delta_;
    f.delta_rate_rad_s = delta_rate_;
  }

  void actuate(const ActuatorFrame&) {}

  // Integrates [k, k + 1), then reads the sphere at k + 1.
  void advance(std::int64_t tick) {
    driver_.advance_tick(tick, x_);
    observe(tick + 1);
  }

  bool finite() const { return x_.allFinite(); }

  // The sphere against the geographic trihedron at the current tick [rad].
  const models::BauersfeldReading& reading() const { return reading_; }
  double delta_rad() const { return delta_; }
  double sin_delta() const { return sin_delta_; }
  // The tuned compass's closed forms at the current tick (sim/oracles/bauersfeld_compass.hpp) [rad, -].
  double azimuth_book_rad() const { return azimuth_book_; }
  double sin_delta_book() const { return sin_delta_book_; }
  double delta_book_rad() const { return std::asin(std::fmin(1.0, sin_delta_book_)); }
  // The vehicle at the current tick [m/s, rad].
  const motion::EarthVehicleSample& motion() const { return motion_; }
  const Vec3& a2() const { return a2_; }
  const State& state() const { return x_; }
  const Dynamics& dynamics() const { return model_; }
  HeldInputs held_inputs() const { return {}; }

  // The runtime guard's names (tools/loop/state_guard.hpp).
  static constexpr int kGuardedStates = 6;
  static const char* state_name(int i) {
    constexpr const char* n[] = {"a1_x", "a1_y", "a1_z", "a1_rate_x_1_s", "a1_rate_y_1_s", "a1_rate_z_1_s"};
    return n[i];
  }
  double state_value(int i) const { return x_[i]; }

 private:
  void observe(std::int64_t tick) {
    motion_ = vehicle_.sample_ns(tick * t_.tick_ns);
    const Vec3 a1 = Model::axis(x_), w = Model::axis_rate(x_);
    a2_ = Model::azimuth_axis(x_, a2_);
    reading_ = models::bauersfeld_reading(a1, a2_, motion_.geographic.q_IZ);
    sin_delta_ = model_.sin_delta(x_);
    delta_ = model_.delta(x_);
    const Vec3& w_IG = motion_.geographic.w_IZ_Z;
    azimuth_book_ = oracles::bauersfeld_azimuth_book(w_IG);
    sin_delta_book_ = oracles::bauersfeld_sin_delta_book(w_IG, p_.compass.H, p_.compass.f);
    // δ' from (sin δ)' = H (a1'·a1'')/(2 f |a1'|); the sphere's rate: a1 × a1' across a1, a1''·a3/|a1'|
    // about it (a2 = a1'/|a1'| turns with a1'').
    const Vec3 acc = model_.acceleration({motion_.p_I, motion_.a_I}, a1, w);
    const double n = w.norm();
    const Vec3 a3 = a1.cross(a2_);
    const double spin = n > Model::kRestRate ? acc.dot(a3) / n : 0.0;
    const Vec3 omega = a1.cross(w) + spin * a1;
    body_rate_[0] = omega.dot(a3);
    body_rate_[1] = -omega.dot(a2_);
    body_rate_[2] = omega.dot(a1);
    const double cos_delta = std::cos(delta_);
    delta_rate_ = n > Model::kRestRate && cos_delta > 0.0
                      ? p_.compass.H * w.dot(acc) / (2.0 * p_.compass.f * n) / cos_delta
                      : 0.0;
  }

  const BauersfeldCompassPlantParams& p_;
  PlantTiming t_;
  Vehicle vehicle_;
  Model model_;
  dynamics::Rk4<Model> integ_;
  dynamics::SubstepDriver<dynamics::Rk4<Model>> driver_;
  State x_{State::Zero()};
  Vec3 a2_{Vec3::UnitX()};
  motion::EarthVehicleSample motion_{};
  models::BauersfeldReading reading_{};
  double sin_delta_{0.0}, delta_{0.0}, delta_rate_{0.0};
  double azimuth_book_{0.0}, sin_delta_book_{0.0};
  double body_rate_[3]{};
};

}  // namespace gyrostab::plants
