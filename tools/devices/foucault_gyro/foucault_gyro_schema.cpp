// The keys of a Foucault gyro scene: one field table over FoucaultGyroScene (tools/scene/schema.hpp), the source
// of the reader, its messages and docs/scenes.md.
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/foucault_gyro/foucault_gyro_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/read_rk4_scene.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = FoucaultGyroScene;
using F = schema::Fields<S>;
using Controller = FoucaultGyroController<firmware::posix::MonotonicClock>;
using models::FoucaultKind;

constexpr std::string_view kKinds[] = {"declinometer", "inclinometer"};

bool declinometer(const S& s) { return s.plant.gyro.kind == FoucaultKind::kDeclinometer; }
bool inclinometer(const S& s) { return s.plant.gyro.kind == FoucaultKind::kInclinometer; }

constexpr schema::Field<S> kFields[] = {
    F::choice("gyro", "kind", kKinds,
              "`declinometer` (Fig. 13.1): frame free about the vertical, rotor axis horizontal, finds north "
              "(13.2); `inclinometer` (Fig. 13.2): frame free about the east-west axis, rotor in the meridian "
              "plane, finds the Earth's axis (13.4)",
              GS_CHOICE(plant.gyro.kind)),
    F::number("gyro", "H", "N m s", Range::positive(),
              "spin momentum, held by the spin motor; its sense marks the rotor's north end", GS_NUMBER(plant.gyro.H))
        .req(),
    F::number("gyro", "J", "kg m²", Range::positive(), "frame + rotor inertia about the free axis",
              GS_NUMBER(plant.gyro.J))
        .req(),
    F::number("gyro", "J_rotor_axis", "kg m²", Range::non_negative(),
              "inertia about the rotor axis, the frame only (the rotor's axial momentum is H)",
              GS_NUMBER(plant.gyro.J_a))
        .defaults_to([](const S& s) { return s.plant.gyro.J; }, "J"),
    F::number("gyro", "J_cross", "kg m²", Range::non_negative(),
              "inertia about the third axis (free axis × rotor axis); the frame's centrifugal torque is "
              "(J_rotor_axis − J_cross) w² sin x cos x",
              GS_NUMBER(plant.gyro.J_c))
        .defaults_to([](const S& s) { return s.plant.gyro.J; }, "J (no centrifugal torque)"),
    F::number("gyro", "d", "N m s/rad", Range::non_negative(), "viscous damping on the free axis (oil, float)",
              GS_NUMBER(plant.gyro.d)),
    F::number("gyro", "alpha0_deg", "deg", Range::closed(-180.0, 180.0),
              "azimuth α of the rotor axis at release (from rest), positive from north toward west",
              GS_NUMBER(plant.angle0))
        .degrees()
        .when(declinometer, "declinometer"),
    F::number("gyro", "theta0_deg", "deg", Range::closed(-180.0, 180.0),
              "elevation ϑ of the rotor axis's north end at release (from rest)", GS_NUMBER(plant.angle0))
        .degrees()
        .when(inclinometer, "inclinometer")
        .defaults_to([](const S&) { return 0.0; }, "0 (horizontal)"),
    F::number("earth", "rotation_rate_rad_s", "rad/s", Range::open_closed(0.0, 1e-2), "Earth rate ω^E",
              GS_NUMBER(plant.gyro.earth_rate)),
    F::number("site", "latitude_deg", "deg", Range::closed(-90.0, 90.0), "latitude φ of the Earth-fixed base",
              GS_NUMBER(plant.gyro.latitude))
        .degrees(),
    F::number("report", "small_amplitude_deg", "deg", Range::open_closed(0.0, 90.0),
              "the period and decay rate are measured on the extrema whose offset from the equilibrium is "
              "below this (the pendulum's period exceeds the linear one by ≈ a²/16)",
              GS_NUMBER(small_amplitude))
        .degrees(),
    F::number("report", "settle_tolerance_arcsec", "arcsec", Range::open_closed(0.0, 3600.0),
              "settled once the offset stays within this (default: the book's 10″ of a survey compass)",
              GS_NUMBER(settle_tolerance))
        .scaled(schema::kDegree / 3600.0),
};

bool possible(const S& s) { return s.plant.gyro.invalid_reason() == nullptr; }

std::string format_g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

constexpr schema::Rule<S> kRules[] = {
    {"gyro", "H",
     "`[gyro]`: H > 0, J > 0, J_rotor_axis, J_cross ≥ 0 forming a triangle, d ≥ 0, a restoring torque at the "
     "equilibrium",
     [](const S& s) -> std::string {
       const char* why = s.plant.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"site", "latitude_deg",
     "declinometer: |latitude_deg| ≤ 85 — the directive torque H ω^E cosφ (13.2) vanishes at the pole and the "
     "period 2π sqrt(J/(H ω^E cosφ)) (13.6), with it the settling time, grows without bound",
     [](const S& s) -> std::string {
       if (!declinometer(s)) return "";
       const double lat = s.plant.gyro.latitude;
       if (std::fabs(lat) <= kDeclinometerLatitudeLimitDeg * schema::kDegree) return "";
       std::string m =
           "a declinometer has no directive torque at the pole (13.2: H ω^E cosφ) and settles ever more slowly "
           "toward it: |latitude_deg| must be <= " +
           format_g(kDeclinometerLatitudeLimitDeg);
       models::FoucaultGyroParams p = s.plant.gyro;  // H, J > 0: the rules run on valid keys only
       p.latitude = kDeclinometerLatitudeLimitDeg * schema::kDegree;
       return m + " (there the period (13.6) is already " + format_g(models::foucault_book_period(p)) + " s)";
     }},
    {"loop", "plant_substeps",
     "RK4's plant sub-step resolves the linearised modes at the equilibrium (the message gives the "
     "`plant_substeps` needed)",
     [](const S& s) -> std::string {
       if (!possible(s)) return "";
       const models::FoucaultLinear l = models::FoucaultLinear::of(s.plant.gyro);
       const double sigma = l.decay_rate(), wd2 = l.damped_rate_squared();
       const double h = s.loop.tick_s() / s.loop.substeps;
       dynamics::Mode modes[2];
       if (wd2 > 0.0) {
         modes[0] = {"oscillation", {-sigma, std::sqrt(wd2)}};
         modes[1] = modes[0];
       } else {
         modes[0] = {"slow decay", {-sigma + std::sqrt(-wd2), 0.0}};
         modes[1] = {"fast decay", {-sigma - std::sqrt(-wd2), 0.0}};
       }
       for (const dynamics::Mode& m : modes) {
         const dynamics::StepCheck c = dynamics::check_step(dynamics::Method::kRk4, m, h);
         if (!c.ok) return c.message;
       }
       return "";
     }},
    {"loop", "tick_us", "the controller's start-up check (firmware/app/free_instrument_controller.hpp)",
     [](const S& s) -> std::string { return controller_refusal<Controller>(s); }},
};

void derive(S& s) { s.controller.runtime.tick_period_ns = s.loop.tick_ns; }

}  // namespace

std::unique_ptr<DeviceScene> read_foucault_gyro(SceneReader& r) {
  auto s = schema::read_rk4_scene(r, kFields, derive, kRules);
  return s ? make_foucault_gyro_scene(std::move(s)) : nullptr;
}

SceneDoc foucault_gyro_doc() {
  return {{schema::document(kFields)}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
