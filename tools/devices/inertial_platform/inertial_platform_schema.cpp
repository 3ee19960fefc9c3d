// The keys of an inertial platform scene: the field tables over InertialPlatformScene and, for each of the
// platform's axes, one [axisN] table over plants::PlatformAxisSetup (tools/scene/schema.hpp), beside the
// shared vehicle motion (tools/devices/vehicle_instruments/vehicle_motion_schema.hpp); the source of the
// reader, its messages and docs/scenes.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/models/inertial_platform_stability.hpp"
#include "tools/devices/inertial_platform/inertial_platform_scene.hpp"
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"
#include "tools/loop/controller_report.hpp"
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
bool position_gyros(const S& s) {
  return three_axes(s) && s.plant.gyros == plants::PlatformGyros::kTwoPosition;
}
bool integrating_gyros(const S& s) {
  return three_axes(s) && s.plant.gyros == plants::PlatformGyros::kThreeIntegrating;
}

// The three-axis platform of the scene, whichever gyros hold it: f(model) with its parameters.
template <class F>
auto with_three_axis_model(const S& s, F&& f) {
  if (position_gyros(s)) {
    models::TwoPositionGyroPlatformParams p;
    for (int i = 0; i < 3; ++i) p.axis[i] = s.plant.axis[i].params;
    return f(models::TwoPositionGyroPlatform(p), p);
  }
  models::ThreeAxisPlatformParams p;
  for (int i = 0; i < 3; ++i) p.axis[i] = s.plant.axis[i].params;
  p.coupling = s.plant.coupling;
  return f(models::ThreeAxisPlatform(p), p);
}

// Read first: the Earth's rate and the axes read depend on it.
constexpr schema::Field<S> kPlatformFields[] = {
    F::integer("platform", "axes", "", 1, 3, "1: single-axis (Fig. 16.9), 3: three-axis",
               GS_INTEGER(plant.axes)),
};

constexpr std::string_view kGyros[] = {"three_integrating", "two_position"};
constexpr std::string_view kCouplings[] = {"full", "decoupled"};

// Read after `axes`.
constexpr schema::Field<S> kVariantFields[] = {
    F::choice("platform", "gyros", kGyros,
              "three_integrating: three rate-integrating gyros (Fig. 16.4, (16.11)-(16.13)); two_position: two "
              "two-degree-of-freedom gyros, X spinning along axis 1, Y along axis 2 (Fig. 16.5, (16.19)-(16.21))",
              GS_CHOICE(plant.gyros))
        .when(three_axes, "axes = 3"),
    F::choice("platform", "coupling", kCouplings,
              "full: the cross terms of (16.11)-(16.12); decoupled: three independent single-axis servos (the "
              "large-H/d limit, the cross terms are ≈ 2d/H: 4 % at H/d = 50)",
              GS_CHOICE(plant.coupling))
        .when(integrating_gyros, "gyros = three_integrating"),
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
        .with_note("`[axisN]`: N = 1 (axes = 1) or 1, 2, 3 (axes = 3); two position gyros: gyro Y (channel 1) "
                   "takes H, B (both gimbal axes), d, c of `[axis1]`, gyro X (channel 2) those of `[axis2]`; "
                   "`[axis3]` gives J, k, the disturbance and the azimuth drift (both rotors) only"),
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
    "each `[axisN]`: usable parameters; axes = 1: a stable servo, k < d (J c + H²)/(B H) ((16.5) for c = 0)";
constexpr const char* kSingleAxisRuleDoc =
    "axes = 1, the book's non-rotating great circle (16.4.1): `[earth] rotation_rate_rad_s` = 0 (its default "
    "then) and every `[segmentN] turn_rate_deg_s` = 0";

constexpr schema::Rule<S> kRules[] = {
    {"platform", "axes", "`[platform] axes` is 1 or 3",
     [](const S& s) -> std::string { return s.plant.axes == 2 ? "must be 1 or 3" : ""; }},
    {"axis1", "k",
     "axes = 3: the platform's servo modes, all three axes together with their cross terms (the roots of "
     "(16.14): 9th order for integrating gyros, 11th for position gyros, sim/models/inertial_platform_stability.hpp), "
     "have negative real parts — gains each axis alone would take ((16.5)) can be unstable when coupled",
     [](const S& s) -> std::string {
       if (!three_axes(s)) return "";
       for (const plants::PlatformAxisSetup& a : s.plant.axis)
         if (a.params.invalid_parameters() != nullptr) return "";  // reported with the axis
       const models::ServoStability st = with_three_axis_model(s, []<class M, class P>(const M&, const P& p) {
         return models::servo_stability<M>(p);
       });
       if (st.stable) return "";
       char buf[320];
       std::snprintf(buf, sizeof buf,
                     "the platform's servo is unstable with its cross-coupling: root %.4g %+.4gi /s (real part "
                     "must be < 0); lower the gains k of `[axisN]`, or raise H or d",
                     st.worst.real(), st.worst.imag());
       return buf;
     }},
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
         step = with_three_axis_model(s, [&]<class M, class P>(const M& m, const P&) {
           return dynamics::check_step(dynamics::Method::kRk4,
                                       dynamics::fastest_mode(m, 0.0, M::State::Zero(), "servo"), h_sub);
         });
       }
       return step.ok ? "" : step.message;
     }},
};

// i < 0: the single axis (as axis1).
void read_axis(SceneReader& r, int i, Axis& a) {
  const std::string section = "axis" + std::to_string(i < 0 ? 1 : i + 1);
  std::array<schema::Field<Axis>, std::size(kAxisFields)> fields;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    fields[k] = kAxisFields[k];
    fields[k].section = section;
  }
  schema::read(r, std::span<const schema::Field<Axis>>(fields), a);
  // Three axes: the whole platform's stability is a rule (kRules), the single-axis bound is not the test.
  const char* why = i < 0 ? a.params.invalid_reason() : a.params.invalid_parameters();
  if (why != nullptr) r.fail(section, "k", why);
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
  schema::read(r, kVariantFields, *s);
  if (single_axis(*s)) read_axis(r, -1, s->plant.axis[0]);
  else for (int i = 0; i < 3; ++i) read_axis(r, i, s->plant.axis[i]);
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
  for (SceneDocRow& row : schema::document(kVariantFields).rows) table.rows.push_back(std::move(row));
  for (SceneDocRow& row : schema::document(kAxisFields).rows) table.rows.push_back(std::move(row));
  for (SceneDocRow& row : schema::document(kFields).rows) table.rows.push_back(std::move(row));
  for (SceneDocRow& row : table.rows) {
    if (row.key == "`[platform] axes`") row.range = "1, 3";
  }
  return {{table, vehicle_motion_doc()}, rules};
}

}  // namespace gyrostab::tools
