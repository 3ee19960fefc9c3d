// The keys of a gyro vertical scene: one field table over GyroVerticalScene (tools/scene/schema.hpp) beside
// the shared vehicle motion (tools/devices/vehicle_instruments/vehicle_motion_schema.hpp), the source of the
// reader, its messages and docs/scenes.md.
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "tools/devices/gyro_vertical/gyro_vertical_scene.hpp"
#include "tools/devices/vehicle_instruments/gyro_frame_checks.hpp"
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = GyroVerticalScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicGyroVerticalController<firmware::posix::MonotonicClock>;

constexpr std::string_view kFidelities[] = {"full", "precession"};
constexpr std::string_view kCutouts[] = {"both", "axis1"};
constexpr std::string_view kFrictionModels[] = {"stick_slip", "smooth"};  // drives::CoulombModel's order

constexpr schema::Field<S> kFields[] = {
    F::choice("gyro", "fidelity", kFidelities,
              "`full`: (10.22) with nutation; `precession`: (12.35), A = B = 0 (no Coulomb friction)",
              GS_CHOICE(plant.gyro.fidelity)),
    F::number("gyro", "H", "N m s", Range::positive(), "spin momentum", GS_NUMBER(plant.gyro.gyro.H)).req(),
    F::number("gyro", "A", "kg m²", Range::positive(), "inertia about gimbal axis 1 (roll)",
              GS_NUMBER(plant.gyro.gyro.A)),
    F::number("gyro", "B", "kg m²", Range::positive(), "inertia about gimbal axis 2 (pitch)",
              GS_NUMBER(plant.gyro.gyro.B)),
    F::number("gyro", "c", "N m/rad", Range::non_negative(),
              "pendulous moment m g s, row 1 of (12.35), on the tilt from the apparent vertical",
              GS_NUMBER(plant.gyro.c)),
    F::number("gyro", "d1", "N m s/rad", Range::non_negative(),
              "viscous bearing friction axis 1, row 2; in the full form d/A must exceed the correction rate "
              "f/H, or the nutation grows (the correction is a circulatory force)",
              GS_NUMBER(plant.gyro.d1)),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(), "viscous bearing friction axis 2, row 2",
              GS_NUMBER(plant.gyro.d2)),
    F::number("gyro", "r1", "N m", Range::non_negative(),
              "Coulomb bearing friction axis 1, row 3 (full form)", GS_NUMBER(plant.gyro.r1)),
    F::number("gyro", "r2", "N m", Range::non_negative(),
              "Coulomb bearing friction axis 2, row 3 (full form)", GS_NUMBER(plant.gyro.r2)),
    F::choice(
        "gyro", "friction_model", kFrictionModels,
        "row 3 as `stick_slip` (a gimbal is held while its net torque stays within r: the dead zone of "
        "Fig. 12.12, sim/drives/gimbal_bearings.hpp) or `smooth` r sat(α'/ε) (viscous r/ε below ε: creeps "
        "through the dead zone; for comparison)",
        GS_CHOICE(plant.gyro.friction_model)),
    F::number(
        "gyro", "stick_rate", "rad/s", Range::positive(),
        "stick_slip: Karnopp dead band v_st — a gimbal slower than this may be held; at the dead zone's "
        "corner the gyro slides along the band's edge at less than v_st",
        GS_NUMBER(plant.gyro.stick_rate)),
    F::number("gyro", "coulomb_rate", "rad/s", Range::positive(),
              "smooth: rate ε below which the Coulomb torque is linear (a resolution, not physics)",
              GS_NUMBER(plant.gyro.coulomb_rate)),
    F::number("gyro", "alpha0_deg", "deg", Range::closed(-30.0, 30.0), "initial tilt about axis 1",
              GS_NUMBER(plant.alpha0))
        .degrees(),
    F::number("gyro", "beta0_deg", "deg", Range::closed(-30.0, 30.0), "initial tilt about axis 2",
              GS_NUMBER(plant.beta0))
        .degrees(),
    F::number("turn_indicator", "H", "N m s", Range::positive(), "turn indicator's spin momentum",
              GS_NUMBER(plant.turn_indicator.H)),
    F::number("turn_indicator", "B", "kg m²", Range::positive(), "its output-axis inertia",
              GS_NUMBER(plant.turn_indicator.B)),
    F::number("turn_indicator", "c2", "N m/rad", Range::positive(), "its spring (a P-gyro: > 0)",
              GS_NUMBER(plant.turn_indicator.c2)),
    F::number("turn_indicator", "d2", "N m s/rad", Range::non_negative(), "its output-axis damping",
              GS_NUMBER(plant.turn_indicator.d2)),
    F::number("sensors", "erection_noise_density", "rad/√Hz", Range::non_negative(),
              "erection sensor white noise", GS_NUMBER(plant.sensors.erection_noise_density)),
    F::number("sensors", "rate_noise_density", "rad/s/√Hz", Range::non_negative(),
              "gimbal rate pick-off white noise", GS_NUMBER(plant.sensors.rate_noise_density)),
    F::number("controller", "c1", "N m/rad", Range::non_negative(), "row 1, synthesized pendulum, axis 1",
              GS_NUMBER(controller.law.c1)),
    F::number("controller", "c2", "N m/rad", Range::non_negative(), "row 1, axis 2",
              GS_NUMBER(controller.law.c2))
        .defaults_to([](const S& s) { return s.controller.law.c1; }, "c1"),
    F::number("controller", "d1", "N m s/rad", Range::non_negative(), "row 2, viscous, axis 1",
              GS_NUMBER(controller.law.d1)),
    F::number("controller", "d2", "N m s/rad", Range::non_negative(), "row 2, axis 2",
              GS_NUMBER(controller.law.d2))
        .defaults_to([](const S& s) { return s.controller.law.d1; }, "d1"),
    F::number("controller", "r1", "N m", Range::non_negative(), "row 3, Coulomb, axis 1",
              GS_NUMBER(controller.law.r1)),
    F::number("controller", "r2", "N m", Range::non_negative(), "row 3, axis 2", GS_NUMBER(controller.law.r2))
        .defaults_to([](const S& s) { return s.controller.law.r1; }, "r1"),
    F::number("controller", "f1", "N m/rad", Range::non_negative(), "row 4, linear correction M1 = −f1 e2",
              GS_NUMBER(controller.law.f1)),
    F::number("controller", "f2", "N m/rad", Range::non_negative(), "row 4, M2 = +f2 e1",
              GS_NUMBER(controller.law.f2))
        .defaults_to([](const S& s) { return s.controller.law.f1; }, "f1"),
    F::number("controller", "g1", "N m", Range::non_negative(), "row 5, relay correction M1 = −g1 sgn e2",
              GS_NUMBER(controller.law.g1)),
    F::number("controller", "g2", "N m", Range::non_negative(), "row 5, M2 = +g2 sgn e1",
              GS_NUMBER(controller.law.g2))
        .defaults_to([](const S& s) { return s.controller.law.g1; }, "g1"),
    F::number("controller", "rate_deadband", "rad/s", Range::non_negative(), "sgn dead band of row 3",
              GS_NUMBER(controller.law.rate_deadband)),
    F::number("controller", "tilt_deadband", "rad", Range::non_negative(), "sgn dead band of row 5",
              GS_NUMBER(controller.law.tilt_deadband)),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "torquer limit",
              GS_NUMBER(controller.law.torque_limit_Nm)),
    F::number("controller", "turn_cutout_deg_s", "deg/s", Range::non_negative(),
              "correction off while the turn indicator reads at least this; 0: never",
              GS_NUMBER(controller.law.turn_cutout_rate))
        .degrees(),
    F::choice("controller", "cutout", kCutouts,
              "what the cut-out switches off: `both` torques or `axis1` (M1) only",
              GS_CHOICE(controller.law.cutout)),
};

// The parameters each, then (once they are usable) the loop they close.
constexpr schema::Rule<S> kRules[] = {
    {"gyro", "H",
     "`[gyro]`: H > 0, A, B > 0 in the full form, the friction coefficients ≥ 0, and Coulomb friction (r1, "
     "r2) only in the full form (the precession form cannot resolve sticking)",
     [](const S& s) -> std::string {
       const char* why = s.plant.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"turn_indicator", "H", "`[turn_indicator]`: a usable rate gyro (sim/sensors/rate_integrating_gyro.hpp)",
     [](const S& s) -> std::string {
       const char* why = s.plant.turn_indicator.invalid_reason();
       return why != nullptr ? why : "";
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
    {"controller", "f1",
     "the controller's start-up check (firmware/app/gyro_vertical_controller.hpp): the sampled loop's limits "
     "of the five rows at the control period",
     controller_refusal<Controller, S>},
    // The linear rows close a loop whose nutation the precession theory does not see (model header).
    {"gyro", "d1",
     "full form: the closed loop linearized at rest has no growing mode — the correction rows are "
     "circulatory forces that feed the nutation unless the bearing damping d/A exceeds about f/H",
     [](const S& s) -> std::string {
       const auto& g = s.plant.gyro;
       const auto& l = s.controller.law;
       if (g.fidelity != models::InstrumentFidelity::kFull) return "";
       return growing_nutation(
           g.gyro, {g.c + l.c1, l.f1, -l.f2, g.c + l.c2}, g.d1 + l.d1, g.d2 + l.d2, "the correction",
           "bearing damping d1/A, d2/B must exceed about f/H = " + format_3g(l.f1 / g.gyro.H) + " /s");
     }},
    {"loop", "plant_substeps",
     "full form: RK4's plant sub-step resolves the nutation H/sqrt(AB) (the message gives the "
     "`plant_substeps` needed)",
     [](const S& s) -> std::string {
       if (s.plant.gyro.fidelity != models::InstrumentFidelity::kFull) return "";
       return long_rk4_substep(s.loop, models::GyroVertical(s.plant.gyro));
     }},
};

// What the controller and the turn indicator take from the scene: the law's H, the control period.
void derive(S& s) {
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  s.controller.law.H = s.plant.gyro.gyro.H;
  s.plant.turn_indicator.sample_period = s.loop.tick_s();
}

}  // namespace

std::unique_ptr<DeviceScene> read_gyro_vertical(SceneReader& r) {
  auto s = std::make_unique<GyroVerticalScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  read_vehicle_motion(r, s->plant.vehicle);
  schema::read(r, kFields, *s);
  derive(*s);
  schema::check(r, kRules, *s);
  schema::check(r, kLoopRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_gyro_vertical_scene(std::move(s));
}

SceneDoc gyro_vertical_doc() {
  std::vector<std::string> rules = schema::document(kRules);
  for (std::string& rule : schema::document(kLoopRules)) rules.push_back(std::move(rule));
  return {{schema::document(kFields), vehicle_motion_doc()}, rules};
}

}  // namespace gyrostab::tools
