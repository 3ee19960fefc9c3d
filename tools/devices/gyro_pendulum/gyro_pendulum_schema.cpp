// The keys of a gyro pendulum scene: the field tables over GyroPendulumScene (tools/scene/schema.hpp) beside
// the shared vehicle motion (tools/devices/vehicle_instruments/vehicle_motion_schema.hpp), the source of the
// reader, its messages and docs/scenes.md. [pendulum] model is read first: it names the integrators.
#include <cmath>
#include <complex>
#include <string>

#include "firmware/fault/sensor_ranges.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/oracles/schuler_tuning.hpp"
#include "tools/devices/gyro_pendulum/gyro_pendulum_scene.hpp"
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = GyroPendulumScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicGyroPendulumController<firmware::posix::MonotonicClock>;
using Model = plants::GyroPendulumModel;
using Integrator = plants::GyroPendulumIntegrator;

constexpr std::string_view kModels[] = {"magnus", "rigid-body"};
constexpr std::string_view kStarts[] = {"equilibrium", "vertical"};
constexpr std::string_view kPivots[] = {"earth", "kepler_orbit"};

bool rigid_body(const S& s) {
  return s.plant.model == Model::kRigidBody;
}
bool kepler(const S& s) { return s.plant.pivot == plants::GyroPendulumPivot::kKeplerOrbit; }

constexpr schema::Field<S> kModelFields[] = {
    F::choice(
        "pendulum", "model", kModels,
        "`magnus`: small-angle (12.55)-(12.58) (sim/models/gyro_pendulum_magnus.hpp); `rigid-body`: the full "
        "3-D Newton–Euler body spinning at H/C (sim/models/schuler_pendulum.hpp)",
        GS_CHOICE(plant.model)),
    F::choice("vehicle", "kind", kPivots,
              "what carries the pivot: `earth` (a vehicle over the rotating Earth: [earth], [vehicle], "
              "[segmentN]) or `kepler_orbit` (free flight on a Kepler ellipse, Chelnokov §4: the [orbit] keys, "
              "sim/motion/kepler_orbit.hpp)",
              GS_CHOICE(plant.pivot)),
};

// The orbit of `[vehicle] kind = "kepler_orbit"`.
constexpr schema::Field<S> kOrbitFields[] = {
    F::number("orbit", "gm_m3_s2", "m³/s²", Range::closed(1.0, 1e21), "GM of the attracting centre",
              GS_NUMBER(plant.orbit.gm))
        .when(kepler, "kepler_orbit"),
    F::number("orbit", "semi_major_axis_m", "m", Range::closed(1.0, 1e12), "a", GS_NUMBER(plant.orbit.semi_major_axis))
        .when(kepler, "kepler_orbit"),
    F::number("orbit", "eccentricity", "", Range::closed(0.0, 0.99), "e (elliptic only)",
              GS_NUMBER(plant.orbit.eccentricity))
        .when(kepler, "kepler_orbit"),
    F::number("orbit", "inclination_deg", "deg", Range::closed(0.0, 180.0), "i", GS_NUMBER(plant.orbit.inclination))
        .degrees()
        .when(kepler, "kepler_orbit"),
    F::number("orbit", "node_deg", "deg", Range::closed(-360.0, 360.0), "right ascension of the ascending node",
              GS_NUMBER(plant.orbit.node))
        .degrees()
        .when(kepler, "kepler_orbit"),
    F::number("orbit", "perigee_deg", "deg", Range::closed(-360.0, 360.0), "argument of perigee",
              GS_NUMBER(plant.orbit.perigee))
        .degrees()
        .when(kepler, "kepler_orbit"),
    F::number("orbit", "mean_anomaly0_deg", "deg", Range::closed(-360.0, 360.0), "mean anomaly at t = 0",
              GS_NUMBER(plant.orbit.mean_anomaly0))
        .degrees()
        .when(kepler, "kepler_orbit"),
};

constexpr schema::Field<S> kFields[] = {
    F::number("pendulum", "A", "kg m²", Range::positive(),
              "transverse moment of rotor + case about the pivot", GS_NUMBER(plant.gyro.A))
        .req(),
    F::number("pendulum", "C", "kg m²", Range::non_negative(),
              "axial moment of rotor + case about the pivot (`rigid-body`: C ≤ 2A, and C > 0 if H > 0)",
              GS_NUMBER(plant.gyro.C))
        .req(),
    F::number("pendulum", "m", "kg", Range::positive(), "mass", GS_NUMBER(plant.gyro.m)).req(),
    F::number("pendulum", "H", "N m s", Range::non_negative(), "rotor spin momentum (0: physical pendulum)",
              GS_NUMBER(plant.gyro.H)),
    F::flag("pendulum", "gravity_gradient",
            "include −(3g/R)(C − A) in k (12.57) (rigid-body: the torque 3(g/R) c × I c)",
            GS_FLAG(plant.gyro.gravity_gradient)),
    F::number(
        "pendulum", "s_m", "m", Range::closed(-10.0, 10.0),
        "centre of mass below the pivot; 0 or absent: tuned — the root of (12.66) for H > 0, A/(mR) (12.59) "
        "for H = 0",
        GS_NUMBER(s_given)),
    F::number("pendulum", "detuning", "", Range::closed(0.0, 100.0), "factor on s (e.g. 1.1 = 10 % mistuned)",
              GS_NUMBER(detuning)),
    F::choice(
        "pendulum", "start", kStarts,
        "`equilibrium`: z0 = −H w0/(kR), z0' = −H w0'/(kR) (the book's steady error (12.65)); `vertical`: z0 "
        "= 0",
        GS_CHOICE(plant.start)),
    F::number("pendulum", "alpha0_deg", "deg", Range::closed(-10.0, 10.0), "added initial tilt about F1",
              GS_NUMBER(plant.alpha0))
        .degrees(),
    F::number("pendulum", "beta0_deg", "deg", Range::closed(-10.0, 10.0), "added initial tilt about F2",
              GS_NUMBER(plant.beta0))
        .degrees(),
    F::number("sensors", "tilt_noise_density", "rad/√Hz", Range::non_negative(),
              "white noise on the tilt pick-offs (gimbal_angle_rad)", GS_NUMBER(plant.tilt_noise_density)),
    F::number("sensors", "rate_noise_density", "rad/s/√Hz", Range::non_negative(),
              "white noise on the tilt-rate pick-offs (gimbal_rate_rad_s)",
              GS_NUMBER(plant.rate_noise_density)),
    F::number(
        "report", "period_threshold_rad", "rad", Range::positive(),
        "hysteresis of the period meter (an upward zero crossing of Re p counts only after it was below "
        "−threshold; keeps the ≲ 2e-7 rad nutation ripple out)",
        GS_NUMBER(period_threshold)),
};

constexpr schema::Rule<S> kRules[] = {
    {"pendulum", "A", "`[pendulum]`: A, m > 0, C ≥ 0, every value finite",
     [](const S& s) -> std::string {
       const char* why = s.plant.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
};

constexpr schema::Rule<S> kLoopRules[] = {
    {"pendulum", "model", "kepler_orbit: `rigid-body` only (the small-angle form (12.58) is written for a pivot "
                          "on the Earth's sphere: its R and g do not describe free flight)",
     [](const S& s) -> std::string {
       return kepler(s) && !rigid_body(s) ? "[vehicle] kind = \"kepler_orbit\" needs model = \"rigid-body\"" : "";
     }},
    {"pendulum", "start", "kepler_orbit: start = \"vertical\" (the steady error (12.65) is the Earth's)",
     [](const S& s) -> std::string {
       return kepler(s) && s.plant.start != plants::GyroPendulumStart::kVertical
                  ? "[vehicle] kind = \"kepler_orbit\" needs start = \"vertical\""
                  : "";
     }},
    {"segment1", "duration_s", "kepler_orbit: no [segmentN] and [vehicle] speed_m_s = 0 (the orbit moves the pivot)",
     [](const S& s) -> std::string {
       return kepler(s) && (s.plant.vehicle.count > 0 || s.plant.vehicle.start.speed != 0.0)
                  ? "[vehicle] kind = \"kepler_orbit\": the orbit moves the pivot; remove the [segmentN] tables "
                    "and speed_m_s"
                  : "";
     }},
    {"pendulum", "C", "rigid-body: a spinning body needs C > 0 (its spin is H/C)",
     [](const S& s) -> std::string {
       const auto& g = s.plant.gyro;
       return rigid_body(s) && !(g.C > 0.0) && g.H > 0.0
                  ? "a spinning rigid body needs C > 0 (its spin is H/C)"
                  : "";
     }},
    {"pendulum", "C", "rigid-body: C ≤ 2A (the triangle inequality of a rigid body's moments)",
     [](const S& s) -> std::string {
       const auto& g = s.plant.gyro;
       return rigid_body(s) && 2.0 * g.A < g.C
                  ? "C > 2A violates the triangle inequality of a rigid body's moments"
                  : "";
     }},
    {"segment1", "duration_s",
     "every `[segmentN] duration_s` is a whole number of ticks (the per-tick sampling is exact at corners "
     "only on tick boundaries)",
     [](const S& s) -> std::string {
       const char* why = motion::corners_on_ticks(s.plant.vehicle, s.loop.tick_ns);
       return why != nullptr ? why : "";
     }},
    {"loop", "tick_us", "the controller's start-up check (firmware/app/gyro_pendulum_controller.hpp)",
     controller_refusal<Controller, S>},
    // The fastest mode: the nutation ω^N (12.61) with spin, else the pendulum's own.
    {"loop", "plant_substeps",
     "the plant sub-step resolves the fastest mode for the integrator: the nutation ω^N (12.61) with spin, "
     "else the pendulum's own frequency sqrt(k/A) (the message gives the `plant_substeps` needed)",
     [](const S& s) -> std::string {
       const auto& g = s.plant.gyro;
       if (!(g.H > 0.0 || g.k() > 0.0)) return "";
       const double h_sub = s.loop.tick_s() / s.loop.substeps;
       dynamics::Mode mode;
       if (g.H > 0.0) {
         mode.name = "nutation";
         mode.lambda = {0.0, oracles::gyro_pendulum_roots(g.A, g.H, g.k()).nutation};
       } else {
         const double k = g.k();
         mode.name = k > 0.0 ? "pendulum" : "divergence";
         mode.lambda = k > 0.0 ? std::complex<double>(0.0, std::sqrt(k / g.A))
                               : std::complex<double>(std::sqrt(-k / g.A), 0.0);
       }
       const Integrator i = s.plant.integrator;
       const dynamics::Method m = i == Integrator::kRk4        ? dynamics::Method::kRk4
                                  : i == Integrator::kStrang   ? dynamics::Method::kStrang
                                  : i == Integrator::kYoshida4 ? dynamics::Method::kYoshida4
                                                               : dynamics::Method::kGyroExponential;
       const dynamics::StepCheck step = dynamics::check_step(m, mode, h_sub);
       return step.ok ? "" : step.message;
     }},
};

// The integrator named, the Earth's R and g in the pendulum's equations, the offset s (given or tuned, times
// the detuning), the monitor's period.
void derive(S& s) {
  auto& g = s.plant.gyro;
  const std::string& in = s.loop.integrator;
  s.plant.integrator = in == "rk4"        ? Integrator::kRk4
                       : in == "strang"   ? Integrator::kStrang
                       : in == "yoshida4" ? Integrator::kYoshida4
                                          : Integrator::kGyroExponential;
  g.R = s.plant.vehicle.earth.radius;
  g.g = s.plant.vehicle.earth.gravity;
  if (std::isfinite(g.A) && std::isfinite(g.C) && std::isfinite(g.m) && std::isfinite(g.H) && g.m > 0.0) {
    s.s_tuned = g.H > 0.0 ? oracles::tuned_gyro_pendulum_offset(g.m, g.A, g.C, g.H, g.g, g.R)  // (12.66)
                          : g.A / (g.m * g.R);                                                 // (12.59)
  }
  g.s = (s.s_given != 0.0 ? s.s_given : s.s_tuned) * s.detuning;
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  if (std::isfinite(g.H) && std::isfinite(g.C) && g.C > 0.0)
    s.controller.runtime.monitor.ranges.rotor_speed_rad_s = firmware::rotor_speed_range_for(g.H / g.C);
}

}  // namespace

std::unique_ptr<DeviceScene> read_gyro_pendulum(SceneReader& r) {
  auto s = std::make_unique<GyroPendulumScene>();
  schema::read(r, kModelFields, *s);
  s->loop = rigid_body(*s) ? read_loop_config(r, "strang", {"strang", "yoshida4", "rk4"})
                           : read_loop_config(r, "gyro-exponential", {"gyro-exponential", "rk4"});
  read_vehicle_motion(r, s->plant.vehicle);
  schema::read(r, kOrbitFields, *s);
  schema::read(r, kFields, *s);
  derive(*s);
  schema::check(r, kRules, *s);
  schema::check(r, kLoopRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_gyro_pendulum_scene(std::move(s));
}

SceneDoc gyro_pendulum_doc() {
  std::vector<std::string> rules = schema::document(kRules);
  for (std::string& rule : schema::document(kLoopRules)) rules.push_back(std::move(rule));
  SceneDocTable table = schema::document(kModelFields);
  for (SceneDocRow& row : schema::document(kFields).rows) {
    if (row.key == "`[pendulum] s_m`") row.fallback = "0 (tuned)";
    table.rows.push_back(std::move(row));
  }
  for (SceneDocRow& row : schema::document(kOrbitFields).rows) table.rows.push_back(std::move(row));
  return {{table, vehicle_motion_doc()}, rules};
}

}  // namespace gyrostab::tools
