// The keys of a spatial-compass scene: one field table over BauersfeldCompassScene (tools/scene/schema.hpp)
// beside the shared vehicle motion (tools/devices/vehicle_instruments/vehicle_motion_schema.hpp), the source
// of the reader, its messages and docs/scenes.md. The spring f is given, or set by the tuning (13.60) —
// or a chosen mistuning ratio — from H, m, s and |R^M| = R − s.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/bauersfeld_compass/bauersfeld_compass_scene.hpp"
#include "tools/devices/vehicle_instruments/gyro_frame_checks.hpp"
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = BauersfeldCompassScene;
using F = schema::Fields<S>;
using Controller = BauersfeldCompassController<firmware::posix::MonotonicClock>;

// Tolerance of `tuned = true` on H²/(f m s |R^M|) − 1: a hand-computed f with ten significant digits.
constexpr double kTunedTolerance = 1e-9;

double tuning_ratio_of(const S& s) {
  return models::bauersfeld_tuning_ratio(s.plant.compass, bauersfeld_radius_M(s));
}

constexpr schema::Field<S> kFields[] = {
    F::number("compass", "H_Nms", "N m s", Range::open_closed(0.0, 1e4), "angular momentum of each rotor",
              GS_NUMBER(plant.compass.H))
        .req(),
    F::number("compass", "m_kg", "kg", Range::open_closed(0.0, 1e4), "mass of the float sphere",
              GS_NUMBER(plant.compass.m))
        .req(),
    F::number("compass", "s_m", "m", Range::open_closed(0.0, 1.0),
              "centre of mass below the support point, along a1 (13.40)", GS_NUMBER(plant.compass.s))
        .req(),
    F::number(
        "compass", "tuning_ratio", "", Range::closed(0.5, 2.0),
        "sets f for this tuning ratio H²/(f m s R_M) when f_Nm is absent (1: tuned (13.60)); R_M = R − s",
        GS_NUMBER(tuning_ratio)),
    F::number("compass", "f_Nm", "N m", Range::positive(), "spring coefficient, M^F = f sin 2δ (13.56)",
              GS_NUMBER(plant.compass.f))
        .defaults_to(
            [](const S& s) {
              const auto& c = s.plant.compass;
              return models::bauersfeld_tuned_spring(c.H, c.m, c.s, bauersfeld_radius_M(s)) / s.tuning_ratio;
            },
            "H²/(m s R_M tuning_ratio), R_M = R − s (13.60)"),
    F::flag("compass", "tuned",
            "refuse the scene unless H² = f m s R_M (13.60) to 1e-9 (else the report gives the ratio)",
            GS_FLAG(tuned)),
    F::number("compass", "tilt0_east_deg", "deg", Range::closed(-10.0, 10.0),
              "initial tilt of a1 toward east, added to the start (13.64)", GS_NUMBER(plant.tilt0_east))
        .degrees(),
    F::number("compass", "tilt0_north_deg", "deg", Range::closed(-10.0, 10.0),
              "initial tilt of a1 toward north, added to the start (13.64)", GS_NUMBER(plant.tilt0_north))
        .degrees(),
    F::number("report", "period_threshold_rad", "rad", Range::non_negative(),
              "hysteresis of the tilt components' zero crossings (the periods)", GS_NUMBER(period_threshold)),
};

constexpr const char* kExclusiveDoc = "`[compass] f_Nm` and `tuning_ratio` exclude each other";

// An upper bound of |a1'| on the plan [rad/s]: the tuned compass's a1' is the vertical's absolute rate,
// |ω_IG horizontal| ≤ |v|/R + |ω^E| cosφ, taken at ≤ 4000 instants and at every segment's ends, plus
// its largest growth between instants, Δt (|a|/R + |ω^E| v/R); plus ω_S × the initial tilt (the swing's
// rate).
double rate_bound_on_plan(const S& s) {
  const motion::VehicleMotionParams& m = s.plant.vehicle;
  const motion::EarthParams& e = m.earth;
  const motion::VehicleGenerator v = motion::make_vehicle(m);
  const double T = s.loop.duration_s, R = e.radius, W = std::fabs(e.rotation_rate);
  const int n = 4000;
  const double dt = T / n;
  double worst = 0.0, v_max = m.start.speed, a_max = 0.0;
  const auto at = [&](const motion::EarthVehicleSample& x) {
    worst = std::max(worst, x.speed / R + W * std::cos(x.latitude));
    v_max = std::max(v_max, x.speed);
  };
  for (int k = 0; k <= n; ++k) at(v.sample(k * dt));
  for (int k = 0; k < m.count; ++k) {
    const std::int64_t t1 = motion::segment_start_ns(m, k + 1);
    at(v.sample_left_ns(t1));
    at(v.sample_ns(t1));
    a_max = std::max(a_max, std::fabs(m.segments[static_cast<std::size_t>(k)].acceleration));
  }
  const double tilt = std::hypot(s.plant.tilt0_east, s.plant.tilt0_north);
  return worst + dt * (a_max / R + W * v_max / R) +
         std::sqrt(s.plant.compass.gravity / bauersfeld_radius_M(s)) * tilt;
}

constexpr schema::Rule<S> kRules[] = {
    {"compass", "H_Nms", "`[compass]`: H, f, m, s > 0 and finite",
     [](const S& s) -> std::string {
       const char* why = s.plant.compass.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"compass", "s_m", "the centre of mass lies well inside the Earth: s < 1e-3 R",
     [](const S& s) -> std::string {
       return s.plant.compass.s < 1e-3 * s.plant.vehicle.earth.radius ? "" : "s must be < 1e-3 R";
     }},
    {"compass", "tuned", "`tuned = true`: H² = f m s |R^M| (13.60) to 1e-9, |R^M| = R − s",
     [](const S& s) -> std::string {
       if (!s.tuned) return "";
       const double q = tuning_ratio_of(s);
       if (std::fabs(q - 1.0) <= kTunedTolerance) return "";
       const auto& c = s.plant.compass;
       return "tuned = true but H²/(f m s |R^M|) = " + format_3g(q) + ": the tuned spring is f = " +
              format_3g(models::bauersfeld_tuned_spring(c.H, c.m, c.s, bauersfeld_radius_M(s))) +
              " N m (13.60); leave f_Nm out to get it";
     }},
};

// Checked once the rules above hold: the bound of |a1'| on the plan needs valid parameters.
constexpr schema::Rule<S> kPlanRules[] = {
    {"compass", "H_Nms",
     "the cases' swing δ is real on the plan: H |a1'| / (2 f) < 1 with |a1'| bounded by the vertical's "
     "absolute rate (|v|/R + ω^E cosφ) plus ω_S × the initial tilt (a mistuned compass's forced swing adds "
     "to it: the report gives sin_delta_max)",
     [](const S& s) -> std::string {
       const auto& c = s.plant.compass;
       const double q = c.H * s.rate_bound / (2.0 * c.f);
       if (q < 1.0) return "";
       return "no real swing δ: H |a1'| / (2 f) reaches " + format_3g(q) + " (|a1'| up to " +
              format_3g(s.rate_bound) +
              " rad/s on this plan); raise H (tuned: sin δ = m s |R^M| |a1'| / (2 H)) "
              "or f";
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
    {"vehicle", "latitude_deg", "|start latitude| ≤ 89°: the geographic readings are undefined at a pole",
     [](const S& s) -> std::string {
       return std::fabs(s.plant.vehicle.start.latitude) > 89.0 * schema::kDegree
                  ? "the compass's readings against north are undefined at a pole: |latitude| <= 89"
                  : "";
     }},
    {"loop", "plant_substeps",
     "RK4's plant sub-step resolves the Schuler swing over the run and each turn over its segment (amplitude "
     "error ≤ 1e-6; the message gives the `plant_substeps` needed)",
     [](const S& s) -> std::string {
       const double h = s.loop.tick_s() / s.loop.substeps;
       const double ws = std::sqrt(s.plant.compass.gravity / bauersfeld_radius_M(s));
       dynamics::StepBounds b{.keep_time = s.loop.duration_s, .amplitude_tolerance = 1e-6};
       dynamics::StepCheck c = dynamics::check_step(dynamics::Method::kRk4, {"Schuler", {0.0, ws}}, h, b);
       if (!c.ok) return c.message;
       const motion::VehicleMotionParams& m = s.plant.vehicle;
       for (int k = 0; k < m.count; ++k) {
         const motion::ManoeuvreSegment& g = m.segments[static_cast<std::size_t>(k)];
         if (g.turn_rate == 0.0) continue;
         b.keep_time = 1e-9 * static_cast<double>(g.duration_ns);
         c = dynamics::check_step(dynamics::Method::kRk4, {"turn", {0.0, std::fabs(g.turn_rate)}}, h, b);
         if (!c.ok) return c.message;
       }
       return "";
     }},
    {"loop", "tick_us", "the controller's start-up check (firmware/app/free_instrument_controller.hpp)",
     [](const S& s) -> std::string { return controller_refusal<Controller>(s); }},
};

void derive(S& s) {
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  s.plant.compass.gravity = s.plant.vehicle.earth.gravity;
}

}  // namespace

std::unique_ptr<DeviceScene> read_bauersfeld_compass(SceneReader& r) {
  auto s = std::make_unique<BauersfeldCompassScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  read_vehicle_motion(r, s->plant.vehicle);
  if (r.has("compass", "f_Nm") && r.has("compass", "tuning_ratio")) {
    r.fail("compass", "f_Nm", "give either f_Nm or tuning_ratio, not both");
  }
  derive(*s);  // g before the table: f's default needs nothing else, the rules need g
  schema::read(r, kFields, *s);
  schema::check(r, kRules, *s);
  if (r.ok()) s->rate_bound = rate_bound_on_plan(*s);
  schema::check(r, kPlanRules, *s);
  schema::check(r, kLoopRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_bauersfeld_compass_scene(std::move(s));
}

SceneDoc bauersfeld_compass_doc() {
  std::vector<std::string> rules{kExclusiveDoc};
  for (std::string& rule : schema::document(kRules)) rules.push_back(std::move(rule));
  for (std::string& rule : schema::document(kPlanRules)) rules.push_back(std::move(rule));
  for (std::string& rule : schema::document(kLoopRules)) rules.push_back(std::move(rule));
  return {{schema::document(kFields), vehicle_motion_doc()}, rules};
}

}  // namespace gyrostab::tools
