// The keys of a directional gyro scene: one field table over DirectionalGyroScene (tools/scene/schema.hpp)
// beside the shared vehicle motion (tools/devices/vehicle_instruments/vehicle_motion_schema.hpp), the source
// of the reader, its messages and docs/scenes.md.
#include <cmath>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "tools/devices/directional_gyro/directional_gyro_scene.hpp"
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = DirectionalGyroScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicDirectionalGyroController<firmware::posix::MonotonicClock>;

constexpr schema::Field<S> kFields[] = {
    F::number("gyro", "H", "N m s", Range::positive(), "spin momentum", GS_NUMBER(plant.gyro.H)).req(),
    F::number("gyro", "alpha0_deg", "deg", Range::closed(-180.0, 180.0),
              "initial outer-gimbal angle against the case (0: rotor along the longitudinal axis)",
              GS_NUMBER(plant.alpha0))
        .degrees(),
    F::number("gyro", "beta0_deg", "deg", Range::closed(-80.0, 80.0), "initial inner-gimbal angle",
              GS_NUMBER(plant.beta0))
        .degrees(),
    F::number("gyro", "heading_error0_deg", "deg", Range::closed(-180.0, 180.0),
              "the card's misset: indicated − true heading at t = 0", GS_NUMBER(plant.heading_error0))
        .degrees(),
    F::number("sensors", "compass_noise_density", "rad/√Hz", Range::non_negative(),
              "white noise of the compass (the reference ψ_soll)", GS_NUMBER(plant.sensors.compass_noise_density)),
    F::flag("controller", "compensate", "(12.22) drift compensation on", GS_FLAG(controller.law.compensate)),
    F::number("controller", "latitude_deg", "deg", Range::closed(-85.0, 85.0),
              "latitude the compensation is set for (the instrument's latitude nut)",
              GS_NUMBER(controller.law.latitude))
        .degrees()
        .defaults_to([](const S& s) { return s.plant.vehicle.start.latitude; }, "`[vehicle] latitude_deg`"),
    F::number("controller", "speed_m_s", "m/s", Range::closed(0.0, 1e4), "ground speed the compensation is set for",
              GS_NUMBER(controller.law.speed))
        .defaults_to([](const S& s) { return s.plant.vehicle.start.speed; }, "`[vehicle] speed_m_s`"),
    F::number("controller", "heading_correction_deg_min", "°/min at 1°", Range::closed(0.0, 60.0),
              "(12.23) heading correction toward the compass, as the correction rate at 1° of error: κ = this/60 "
              "per s, time constant 1/κ (the book's practical rates 0.1 … 4 °/min); 0: off",
              GS_NUMBER(controller.law.heading_rate))
        .scaled(1.0 / 60.0),
    F::number("controller", "k", "N m/rad", Range::non_negative(),
              "(12.24) inter-gimbal correction M1 = −k β (β settles at the rate k/H; in a turn at ψ'0 its strength "
              "is c = k/(H ψ'0), (12.27)); 0: off",
              GS_NUMBER(controller.law.k)),
    F::number("controller", "turn_cutout_deg_s", "deg/s", Range::non_negative(),
              "both corrections off (not the compensation) while the turn rate reads at least this; 0: never",
              GS_NUMBER(controller.law.turn_cutout_rate))
        .degrees(),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "torquer limit",
              GS_NUMBER(controller.law.torque_limit_Nm)),
};

constexpr schema::Rule<S> kRules[] = {
    {"gyro", "H", "`[gyro]`: H > 0",
     [](const S& s) -> std::string {
       const char* why = s.plant.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"segment1", "duration_s",
     "every `[segmentN] duration_s` is a whole number of ticks (a manoeuvre corner inside a tick costs an "
     "O(h·Δa) error)",
     [](const S& s) -> std::string {
       const char* why = motion::corners_on_ticks(s.plant.vehicle, s.loop.tick_ns);
       return why != nullptr ? why : "";
     }},
    {"vehicle", "latitude_deg", "|start latitude| ≤ 85°: the heading is undefined at the poles",
     [](const S& s) -> std::string {
       return std::fabs(s.plant.vehicle.start.latitude) > 85.0 * schema::kDegree
                  ? "the heading (and (12.22)'s tan φ) is undefined near the poles: |latitude| <= 85"
                  : "";
     }},
    {"controller", "k",
     "the controller's start-up check (firmware/app/directional_gyro_controller.hpp): κT ≤ 0.5, kT/H ≤ 0.5 at "
     "the control period, the (12.22) compensation within the torque limit",
     controller_refusal<Controller, S>},
};

// What the controller takes from the scene: the law's H and the Earth, the control period.
void derive(S& s) {
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  s.controller.law.H = s.plant.gyro.H;
  s.controller.law.earth_rate = s.plant.vehicle.earth.rotation_rate;
  s.controller.law.earth_radius = s.plant.vehicle.earth.radius;
}

}  // namespace

std::unique_ptr<DeviceScene> read_directional_gyro(SceneReader& r) {
  auto s = std::make_unique<DirectionalGyroScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  read_vehicle_motion(r, s->plant.vehicle);
  schema::read(r, kFields, *s);
  derive(*s);
  schema::check(r, kRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_directional_gyro_scene(std::move(s));
}

SceneDoc directional_gyro_doc() {
  return {{schema::document(kFields), vehicle_motion_doc()}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
