// The keys of a gyrocompass scene: one field table over GyrocompassScene (tools/scene/schema.hpp) beside the
// shared vehicle motion (tools/devices/vehicle_instruments/vehicle_motion_schema.hpp), the source of the
// reader, its messages and docs/scenes.md. The controller's gains may be given, or set by the book's
// tuning: c_e by Schuler tuning (13.26) for a latitude, f by a damping ratio of (13.12).
#include <algorithm>
#include <cmath>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "tools/devices/gyrocompass/gyrocompass_scene.hpp"
#include "tools/devices/vehicle_instruments/gyro_frame_checks.hpp"
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = GyrocompassScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicGyrocompassController<firmware::posix::MonotonicClock>;

constexpr std::string_view kFidelities[] = {"full", "precession"};
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

constexpr schema::Field<S> kFields[] = {
    F::choice("gyro", "fidelity", kFidelities, "`full`: (13.7) with nutation; `precession`: (13.10)/(13.22)",
              GS_CHOICE(plant.gyro.fidelity)),
    F::number("gyro", "H", "N m s", Range::positive(), "spin momentum", GS_NUMBER(plant.gyro.gyro.H)).req(),
    F::number("gyro", "A", "kg m²", Range::positive(), "inertia about the vertical axis 1",
              GS_NUMBER(plant.gyro.gyro.A)),
    F::number("gyro", "B", "kg m²", Range::positive(), "inertia about the east axis 2",
              GS_NUMBER(plant.gyro.gyro.B)),
    F::number("gyro", "c", "N m/rad", Range::non_negative(), "mechanical pendulous moment G s",
              GS_NUMBER(plant.gyro.c)),
    F::number(
        "gyro", "d1", "N m s/rad", Range::non_negative(),
        "viscous damping of the floated sphere about the vertical; in the full form with damping f > 0 the "
        "sphere needs d1 or d2, or the circulatory torque −fβ makes the nutation grow at δ/2",
        GS_NUMBER(plant.gyro.d1)),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(), "viscous damping about the east axis",
              GS_NUMBER(plant.gyro.d2))
        .defaults_to([](const S& s) { return s.plant.gyro.d1; }, "d1"),
    F::number("gyro", "swing_inertia", "kg m²", Range::non_negative(),
              "Θ_s about the rotor axis for the swing of (13.31); 0: no swing, no rolling error; needs c > 0",
              GS_NUMBER(plant.gyro.swing_inertia)),
    F::number("gyro", "alpha0_deg", "deg", Range::closed(-30.0, 30.0),
              "initial azimuth offset (from the steady state if start_settled)", GS_NUMBER(plant.alpha0))
        .degrees(),
    F::number("gyro", "beta0_deg", "deg", Range::closed(-30.0, 30.0), "initial elevation offset",
              GS_NUMBER(plant.beta0))
        .degrees(),
    F::flag("gyro", "start_settled",
            "offsets from the closed loop's steady state of the initial motion (else absolute)",
            GS_FLAG(plant.start_settled)),
    F::number("roll", "amplitude_deg", "deg", Range::closed(0.0, 45.0), "ship roll Φ (13.29)",
              GS_NUMBER(plant.gyro.roll.amplitude))
        .degrees(),
    F::number("roll", "period_s", "s", Range::closed(1.0, 100.0), "roll period 2π/ω_s",
              GS_NUMBER(plant.gyro.roll.period)),
    F::number("roll", "height_m", "m", Range::closed(0.0, 100.0),
              "compass height h above the roll axis (13.30)", GS_NUMBER(plant.gyro.roll.height)),
    F::number("sensors", "level_noise_density", "rad/√Hz", Range::non_negative(), "level sensor white noise",
              GS_NUMBER(plant.level_noise_density)),
    F::number("controller", "tune_latitude_deg", "deg", Range::closed(-80.0, 80.0),
              "set c_e so that c + c_e is Schuler-tuned (13.26) at this latitude", GS_NUMBER(tune_latitude))
        .degrees()
        .defaults_to([](const S&) { return kNone; }, "none: c_e as given"),
    F::number("controller", "c_e", "N m/rad", Range::non_negative(), "electrical pendulosity M2 = −c_e β_lvl",
              GS_NUMBER(controller.law.c_e)),
    F::number("controller", "damping_ratio", "", Range::closed(0.0, 2.0),
              "set f for this damping ratio ζ of (13.12) at the tuning (else the start) latitude",
              GS_NUMBER(damping_ratio))
        .defaults_to([](const S&) { return kNone; }, "none: f as given"),
    F::number("controller", "f", "N m/rad", Range::non_negative(), "damping M1 = −f β_lvl (13.8)",
              GS_NUMBER(controller.law.f)),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "torquer limit",
              GS_NUMBER(controller.law.torque_limit_Nm)),
    F::number("report", "extrema_sample_s", "s", Range::positive(),
              "sampling of α for the extrema (period, decay, equilibrium)", GS_NUMBER(extrema_sample_s)),
    F::number("report", "extrema_hysteresis_rad", "rad", Range::non_negative(),
              "an extremum counts once α has moved back by this much (keeps noise, nutation and a decayed "
              "oscillation out)",
              GS_NUMBER(extrema_hysteresis)),
};

// A gain is given, or set by the tuning the other key names; not both.
struct Exclusive {
  std::string_view section, given, tuned;
};
constexpr Exclusive kExclusive[] = {{"controller", "c_e", "tune_latitude_deg"},
                                    {"controller", "f", "damping_ratio"}};
constexpr const char* kExclusiveDoc =
    "`[controller] c_e` and `tune_latitude_deg` exclude each other, as do `f` and `damping_ratio`";

bool tuned(const S& s) {
  return std::isfinite(s.tune_latitude);
}
// The latitude the gains are set for: the tuning's, else the start's [rad].
double design_latitude(const S& s) {
  return tuned(s) ? s.tune_latitude : s.plant.vehicle.start.latitude;
}

constexpr schema::Rule<S> kRules[] = {
    {"gyro", "H", "`[gyro]`: H > 0, A, B > 0 in the full form, c, d1, d2 ≥ 0; the swing needs c > 0",
     [](const S& s) -> std::string {
       const char* why = s.plant.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"controller", "tune_latitude_deg",
     "tuned: the mechanical pendulosity c does not exceed the tuned c + c_e",
     [](const S& s) -> std::string {
       return !tuned(s) || s.controller.law.c_e >= 0.0
                  ? ""
                  : "the mechanical pendulosity c already exceeds the tuned value";
     }},
    {"gyro", "c", "the compass has a pendulous moment: c + c_e > 0",
     [](const S& s) -> std::string {
       return s.plant.gyro.c + s.controller.law.c_e > 0.0
                  ? ""
                  : "the compass needs a pendulous moment: c + c_e > 0";
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
    {"controller", "f",
     "the controller's start-up check (firmware/app/gyrocompass_controller.hpp): the sampled loop's limits "
     "of f and c_e at the control period",
     controller_refusal<Controller, S>},
    {"vehicle", "latitude_deg",
     "|start latitude| ≤ 85°: a gyrocompass has no directive torque near the poles (13.6)",
     [](const S& s) -> std::string {
       return std::fabs(s.plant.vehicle.start.latitude) > 85.0 * schema::kDegree
                  ? "a gyrocompass has no directive torque near the poles (13.6): |latitude| <= 85"
                  : "";
     }},
    // The damping torque −f β is circulatory and can make the nutation grow (model header).
    {"gyro", "d1",
     "full form: the closed loop linearized at rest at the start latitude has no growing mode (the nutation)",
     [](const S& s) -> std::string {
       const auto& g = s.plant.gyro;
       const auto& l = s.controller.law;
       if (g.fidelity != models::InstrumentFidelity::kFull) return "";
       const double H = g.gyro.H,
                    wh = s.plant.vehicle.earth.rotation_rate * std::cos(s.plant.vehicle.start.latitude);
       return growing_nutation(
           g.gyro, {H * wh, l.f, 0.0, H * wh + g.c + l.c_e}, g.d1, g.d2, "the damping torque",
           "give the sphere viscous damping d1, d2 (d/A well above f/H = " + format_3g(l.f / H) + " /s)");
     }},
    {"loop", "plant_substeps",
     "RK4's plant sub-step resolves the compass's fastest mode at rest at the design latitude (the message "
     "gives the `plant_substeps` needed)",
     [](const S& s) -> std::string {
       const double we = s.plant.vehicle.earth.rotation_rate, lat = design_latitude(s);
       models::Gyrocompass m(s.plant.gyro);
       m.inputs.frame.hold({dynamics::Vec3(we * std::sin(lat), 0.0, we * std::cos(lat)),
                            dynamics::Vec3::Zero(), dynamics::Vec3(s.plant.vehicle.earth.gravity, 0.0, 0.0)});
       return long_rk4_substep(s.loop, m);
     }},
};

// The controller's gains (given, or tuned), its H and period; the plant's g and the gains of its settled
// start; the extrema's sampling in ticks.
void derive(S& s) {
  auto& g = s.plant.gyro;
  auto& l = s.controller.law;
  const motion::EarthParams& e = s.plant.vehicle.earth;
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  l.H = g.gyro.H;
  g.gravity = e.gravity;
  if (tuned(s)) {
    l.c_e =
        firmware::schuler_tuned_pendulosity(l.H, s.tune_latitude, e.gravity, e.radius, e.rotation_rate) - g.c;
  }
  if (std::isfinite(s.damping_ratio)) {
    l.f = firmware::gyrocompass_damping_for_ratio(l.H, g.c + l.c_e, design_latitude(s), s.damping_ratio,
                                                  e.rotation_rate);
  }
  s.plant.law_f = l.f;
  s.plant.law_c_e = l.c_e;
  s.extrema_every_ticks =
      std::max<int>(1, static_cast<int>(std::llround(s.extrema_sample_s / s.loop.tick_s())));
}

}  // namespace

std::unique_ptr<DeviceScene> read_gyrocompass(SceneReader& r) {
  auto s = std::make_unique<GyrocompassScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  read_vehicle_motion(r, s->plant.vehicle);
  schema::read(r, kFields, *s);
  for (const Exclusive& x : kExclusive) {
    if (r.has(x.section, x.given) && r.has(x.section, x.tuned)) {
      r.fail(x.section, x.given,
             "give either " + std::string(x.given) + " or " + std::string(x.tuned) + ", not both");
    }
  }
  derive(*s);
  schema::check(r, kRules, *s);
  schema::check(r, kLoopRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_gyrocompass_scene(std::move(s));
}

SceneDoc gyrocompass_doc() {
  std::vector<std::string> rules{kExclusiveDoc};
  for (std::string& rule : schema::document(kRules)) rules.push_back(std::move(rule));
  for (std::string& rule : schema::document(kLoopRules)) rules.push_back(std::move(rule));
  return {{schema::document(kFields), vehicle_motion_doc()}, rules};
}

}  // namespace gyrostab::tools
