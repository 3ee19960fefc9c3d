// The keys of an inertial platform scene: the field tables over InertialPlatformScene and, for each of the
// platform's axes, one [axisN] table over plants::PlatformAxisSetup (tools/scene/schema.hpp), beside the
// shared vehicle motion (tools/devices/vehicle_instruments/vehicle_motion_schema.hpp); the source of the
// reader, its messages and docs/scenes.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/inertial_platform/inertial_platform_scene.hpp"
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"
#include "tools/run/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = InertialPlatformScene;
using F = schema::Fields<S>;
using Axis = plants::PlatformAxisSetup;
using FA = schema::Fields<Axis>;
using Controller = firmware::BasicInertialPlatformController<firmware::posix::MonotonicClock>;

bool single_axis(const S& s) {
  return s.plant.axes == 1;
}
bool three_axes(const S& s) {
  return s.plant.axes != 1;
}

// Read first: the Earth's rate and the axes read depend on it.
constexpr schema::Field<S> kPlatformFields[] = {
    F::integer("platform", "axes", "", 1, 3, "1: single-axis (Fig. 16.9), 3: three-axis",
               GS_INTEGER(plant.axes)),
};

// The gyro drift is given in deg/h.
void set_drift(Axis& a, double v) {
  a.params.drift = v * schema::kDegree / 3600.0;
}
double get_drift(const Axis& a) {
  return a.params.drift / schema::kDegree * 3600.0;
}

// Section "axisN" stands for axis1, axis2, axis3 (replaced when read).
constexpr schema::Field<Axis> kAxisFields[] = {
    FA::number("axisN", "J", "kg m²", Range::positive(), "platform + gimbal inertia about the axis",
               GS_NUMBER(params.J))
        .with_note("`[axisN]`: N = 1 (axes = 1) or 1, 2, 3 (axes = 3)"),
    FA::number("axisN", "k", "N m/rad", Range::positive(), "stabilization servo gain M = −k β",
               GS_NUMBER(params.k)),
    FA::number("axisN", "H", "N m s", Range::positive(), "the axis gyro's spin momentum",
               GS_NUMBER(params.H)),
    FA::number("axisN", "B", "kg m²", Range::positive(), "its output-axis inertia", GS_NUMBER(params.B)),
    FA::number("axisN", "d", "N m s/rad", Range::positive(),
               "its output-axis damping (H/d = 20-80 in the book)", GS_NUMBER(params.d)),
    FA::number("axisN", "c", "N m/rad", Range::non_negative(), "its output-axis spring", GS_NUMBER(params.c)),
    FA::number("axisN", "disturbance_Nm", "N m", Range::closed(-10.0, 10.0),
               "constant torque on the platform M^S", GS_NUMBER(params.disturbance)),
    FA::number("axisN", "drift_deg_h", "deg/h", Range::closed(-100.0, 100.0), "gyro drift ε", set_drift,
               get_drift),
    FA::number("axisN", "accel_bias_m_s2", "m/s²", Range::closed(-1.0, 1.0),
               "bias of the accelerometer that senses tilt about the axis", GS_NUMBER(params.accel_bias)),
    FA::number("axisN", "tilt0_deg", "deg", Range::closed(-5.0, 5.0), "initial tilt e(0)", GS_NUMBER(tilt0))
        .degrees(),
};

constexpr schema::Field<S> kFields[] = {
    F::number("axis1", "gravity_gradient_Nm_rad", "N m/rad", Range::any(), "(3g/R)(B_p − C_p) of (16.30)",
              GS_NUMBER(plant.gravity_gradient))
        .when(single_axis, "axes = 1"),
    F::number("sensors", "accel_noise_density", "m/s²/√Hz", Range::non_negative(),
              "accelerometer white noise", GS_NUMBER(plant.accel_noise_density)),
    F::number("controller", "radius_m", "m", Range::positive(),
              "R the Schuler loop is tuned to (tuned: the Earth's)", GS_NUMBER(controller.law.radius))
        .defaults_to([](const S& s) { return s.plant.vehicle.earth.radius; }, "[earth] radius_m"),
    F::number("controller", "H", "N m s", Range::positive(), "gyro momentum the torquer scale assumes",
              GS_NUMBER(controller.law.H))
        .defaults_to([](const S& s) { return s.plant.axis[0].params.H; }, "[axis1] H"),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "torquer limit",
              GS_NUMBER(controller.law.torque_limit_Nm)),
    F::number("controller", "velocity_error1_m_s", "m/s", Range::closed(-1e3, 1e3),
              "initial velocity error of channel 1's integrator", GS_NUMBER(velocity_error0[0])),
    F::number("controller", "velocity_error2_m_s", "m/s", Range::closed(-1e3, 1e3),
              "initial velocity error of channel 2's integrator", GS_NUMBER(velocity_error0[1]))
        .when(three_axes, "axes = 3"),
    F::number("report", "extrema_sample_s", "s", Range::positive(), "sampling of the tilt for the extrema",
              GS_NUMBER(extrema_sample_s)),
    F::number("report", "extrema_hysteresis_rad", "rad", Range::non_negative(),
              "an extremum counts once the tilt has moved back by this much", GS_NUMBER(extrema_hysteresis)),
};

constexpr const char* kAxisRuleDoc =
    "each `[axisN]`: usable parameters, and a stable servo: k < d (J c + H²)/(B H) ((16.5) for c = 0)";
constexpr const char* kSingleAxisRuleDoc =
    "axes = 1, the book's non-rotating great circle (16.4.1): `[earth] rotation_rate_rad_s` = 0 (its default "
    "then) and every `[segmentN] turn_rate_deg_s` = 0";

constexpr schema::Rule<S> kRules[] = {
    {"platform", "axes", "`[platform] axes` is 1 or 3",
     [](const S& s) -> std::string { return s.plant.axes == 2 ? "must be 1 or 3" : ""; }},
};

constexpr schema::Rule<S> kLoopRules[] = {
    {"segment1", "duration_s",
     "every `[segmentN] duration_s` is a whole number of ticks (a manoeuvre corner inside a tick costs an "
     "O(h·Δa) error)",
     [](const S& s) -> std::string {
       const char* why = motion::corners_on_ticks(s.plant.vehicle, s.loop.tick_ns);
       return why != nullptr ? why : "";
     }},
    {"controller", "radius_m",
     "the controller's start-up check (firmware/app/inertial_platform_controller.hpp): the Schuler loops' "
     "sampled limits at the control period",
     controller_refusal<Controller, S>},
    {"loop", "plant_substeps",
     "RK4's plant sub-step resolves the servo modes at rest (the message gives the `plant_substeps` needed)",
     [](const S& s) -> std::string {
       const double h_sub = s.loop.tick_s() / s.loop.substeps;
       dynamics::StepCheck step;
       if (single_axis(s)) {
         models::SingleAxisPlatform m({s.plant.axis[0].params, s.plant.gravity_gradient});
         step = dynamics::check_step(
             dynamics::Method::kRk4,
             dynamics::fastest_mode(m, 0.0, models::SingleAxisPlatform::State::Zero(), "servo"), h_sub);
       } else {
         models::ThreeAxisPlatformParams p;
         for (int i = 0; i < 3; ++i) p.axis[i] = s.plant.axis[i].params;
         models::ThreeAxisPlatform m(p);
         step = dynamics::check_step(
             dynamics::Method::kRk4,
             dynamics::fastest_mode(m, 0.0, models::ThreeAxisPlatform::State::Zero(), "servo"), h_sub);
       }
       return step.ok ? "" : step.message;
     }},
};

void read_axis(SceneReader& r, int i, Axis& a) {
  const std::string section = "axis" + std::to_string(i + 1);
  std::array<schema::Field<Axis>, std::size(kAxisFields)> fields;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    fields[k] = kAxisFields[k];
    fields[k].section = section;
  }
  schema::read(r, std::span<const schema::Field<Axis>>(fields), a);
  if (const char* why = a.params.invalid_reason()) r.fail(section, "k", why);
}

// The single-axis platform is the book's case: a great circle over a non-rotating Earth.
void check_single_axis_motion(SceneReader& r, const S& s) {
  const motion::VehicleMotionParams& m = s.plant.vehicle;
  if (m.earth.rotation_rate != 0.0)
    r.fail("earth", "rotation_rate_rad_s",
           "the single-axis platform is the book's non-rotating case: must be 0");
  for (int k = 0; k < m.count; ++k)
    if (m.segments[static_cast<std::size_t>(k)].turn_rate != 0.0)
      r.fail("segment" + std::to_string(k + 1), "turn_rate_deg_s",
             "the single-axis platform follows a great circle (16.4.1): turn rates must be 0");
}

// The controller's period and channels; the extrema's sampling in ticks.
void derive(S& s) {
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  s.controller.law.enabled[1] = s.channels() > 1;
  s.extrema_every_ticks =
      std::max<int>(1, static_cast<int>(std::llround(s.extrema_sample_s / s.loop.tick_s())));
}

// The loops start on the level frame's rate at t = 0 (an ideal alignment), plus the scene's velocity error.
void derive_alignment(S& s) {
  auto& l = s.controller.law;
  const motion::EarthVehicleSample m0 = motion::make_vehicle(s.plant.vehicle).sample_ns(0);
  if (single_axis(s)) {
    l.initial_rate[0] = m0.track.w_IZ_Z.y() + s.velocity_error0[0] / l.radius;
  } else {
    for (int i = 0; i < 2; ++i)
      l.initial_rate[i] = m0.azimuth_free.w_IZ_Z[i] + s.velocity_error0[i] / l.radius;
  }
}

}  // namespace

std::unique_ptr<DeviceScene> read_inertial_platform(SceneReader& r) {
  auto s = std::make_unique<InertialPlatformScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  schema::read(r, kPlatformFields, *s);
  if (single_axis(*s)) s->plant.vehicle.earth.rotation_rate = 0.0;
  read_vehicle_motion(r, s->plant.vehicle);
  if (single_axis(*s) && r.ok()) check_single_axis_motion(r, *s);
  for (int i = 0; i < (single_axis(*s) ? 1 : 3); ++i) read_axis(r, i, s->plant.axis[i]);
  schema::read(r, kFields, *s);
  derive(*s);
  schema::check(r, kRules, *s);
  if (r.ok()) derive_alignment(*s);
  schema::check(r, kLoopRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_inertial_platform_scene(std::move(s));
}

SceneDoc inertial_platform_doc() {
  std::vector<std::string> rules = schema::document(kRules);
  rules.emplace_back(kAxisRuleDoc);
  rules.emplace_back(kSingleAxisRuleDoc);
  for (std::string& rule : schema::document(kLoopRules)) rules.push_back(std::move(rule));
  SceneDocTable table = schema::document(kPlatformFields);
  for (SceneDocRow& row : schema::document(kAxisFields).rows) table.rows.push_back(std::move(row));
  for (SceneDocRow& row : schema::document(kFields).rows) table.rows.push_back(std::move(row));
  for (SceneDocRow& row : table.rows) {
    if (row.key == "`[platform] axes`") row.range = "1, 3";
  }
  return {{table, vehicle_motion_doc()}, rules};
}

}  // namespace gyrostab::tools
