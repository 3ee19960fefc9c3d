// The keys of a coning scene: one field table over ConingScene (tools/scene/schema.hpp), the source of the
// reader, its messages and docs/scenes.md.
#include <cmath>
#include <complex>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/base_motion/base_motion_schema.hpp"
#include "tools/devices/coning/coning_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = ConingScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicConingController<firmware::posix::MonotonicClock>;

constexpr schema::Field<S> kFields[] = {
    F::number("gyro", "H", "N m s", Range::positive(), "rotor spin momentum", GS_NUMBER(plant.platform.gyro.gyro.H))
        .req(),
    F::number("gyro", "B", "kg m²", Range::positive(), "gimbal + rotor inertia about the output axis",
              GS_NUMBER(plant.platform.gyro.gyro.B))
        .req(),
    F::number("gyro", "c2", "N m/rad", Range::non_negative(),
              "output-axis spring: > 0 a P-gyro reading (c2/H) β, 0 an I-gyro reading (d2/H) β",
              GS_NUMBER(plant.platform.gyro.gyro.c2))
        .req(),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(), "output-axis damper (> 0 for an I-gyro)",
              GS_NUMBER(plant.platform.gyro.gyro.d2))
        .req(),
    F::number("gyro", "inertia_difference", "kg m²", Range::closed(-1.0, 1.0),
              "A_g − C_g: gimbal + rotor about the effective input axis minus about the spin axis (anisoinertia)",
              GS_NUMBER(plant.platform.gyro.inertia_difference)),
    F::number("drive", "time_constant_s", "s", Range::open_closed(0.0, 1.0),
              "the geared servo's speed loop: τ_d φ'' + φ' = K_v V", GS_NUMBER(plant.platform.drive_time_constant)),
    F::number("drive", "rate_per_volt", "rad/s/V", Range::positive(), "K_v", GS_NUMBER(plant.platform.drive_rate_per_volt)),
    F::number("drive", "voltage_limit_V", "V", Range::positive(), "the drive's supply: |V| ≤ this",
              GS_NUMBER(plant.voltage_limit)),
    F::number("vibration", "amplitude_rad", "rad", Range::closed(0.0, 0.2), "angular amplitude Φ of the base",
              GS_NUMBER(plant.platform.amplitude))
        .req(),
    F::number("vibration", "frequency_hz", "Hz", Range::open_closed(0.0, 1e3), "vibration frequency ν/2π",
              GS_NUMBER(plant.platform.frequency))
        .scaled(2.0 * std::numbers::pi)
        .req(),
    F::number("vibration", "direction_deg", "deg", Range::closed(-90.0, 90.0),
              "δ: the vibration axis from the platform's axis 3 (gyro input) towards its axis 1 (gyro spin)",
              GS_NUMBER(plant.platform.direction))
        .degrees(),
    F::number("vibration", "phase_deg", "deg", Range::closed(-180.0, 180.0),
              "ε: lag of the spin-axis component; 0 planar, ±90 conical", GS_NUMBER(plant.platform.phase))
        .degrees(),
    F::number("controller", "kp", "1/s", Range::positive(), "slaving loop k_p (V = −(k_p θ + k_i ∫θ)/K_v)",
              GS_NUMBER(controller.law.kp)),
    F::number("controller", "ki", "1/s²", Range::non_negative(), "slaving loop k_i (k_p²/4: a double pole at k_p/2)",
              GS_NUMBER(controller.law.ki))
        .defaults_to([](const S& s) { return 0.25 * s.controller.law.kp * s.controller.law.kp; }, "kp²/4"),
    F::number("report", "settle_s", "s", Range::non_negative(), "the platform's drift is measured after this time",
              GS_NUMBER(settle_s))
        .within([](const S& s) { return Range::closed(0.0, s.loop.duration_s); }, "0 … duration_s"),
};

bool possible(const S& s) { return s.plant.platform.gyro.invalid_reason() == nullptr; }

// The gyro's output-axis mode: B λ² + d2 λ + c2 = 0 (the faster root), or −d2/B for an I-gyro.
std::complex<double> gyro_mode(const sensors::SingleAxisGyroParams& g) {
  const std::complex<double> disc = std::sqrt(std::complex<double>(g.d2 * g.d2 - 4.0 * g.B * g.c2, 0.0));
  return (-g.d2 - disc) / (2.0 * g.B);
}

constexpr schema::Rule<S> kRules[] = {
    {"gyro", "c2", "the gyro is a P-gyro (c2 > 0) or an I-gyro (c2 = 0, d2 > 0)",
     [](const S& s) -> std::string {
       const char* why = s.plant.platform.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"loop", "plant_substeps",
     "the plant step resolves the gyro's output-axis mode, the drive's lag and the vibration; the message gives "
     "the plant_substeps needed",
     [](const S& s) -> std::string {
       if (!possible(s)) return "";
       const models::ConingPlatformParams& p = s.plant.platform;
       const double h = s.loop.tick_s() / s.loop.substeps;
       for (const dynamics::Mode& m : {dynamics::Mode{"gyro output axis", gyro_mode(p.gyro.gyro)},
                                       dynamics::Mode{"drive", {-1.0 / p.drive_time_constant, 0.0}},
                                       dynamics::Mode{"vibration", {0.0, p.frequency}}}) {
         const dynamics::StepCheck c = dynamics::check_step(dynamics::Method::kRk4, m, h);
         if (!c.ok) return c.message;
       }
       return "";
     }},
    {"vibration", "frequency_hz",
     "at least 10 ticks per vibration period (the drift is measured over whole periods of ticks)",
     [](const S& s) -> std::string {
       const double ticks = 2.0 * std::numbers::pi / (s.plant.platform.frequency * s.loop.tick_s());
       if (ticks >= 10.0) return "";
       return "frequency_hz gives " + std::to_string(ticks) + " ticks per period, below 10: lower it or tick_us";
     }},
    {"motion", "heave_amplitude_m",
     "no translational vibration ([motion] heave/sway): the platform and its gyro read angular rates only",
     [](const S& s) -> std::string {
       return s.plant.base.vibration.count > 0
                  ? "the coning platform reads angular rates only: a heave or sway does not reach it; remove "
                    "heave_amplitude_m / sway_amplitude_m"
                  : "";
     }},
    {"loop", "tick_us", "the controller's start-up check (firmware/control/coning_null_law.hpp: Routh with the "
                        "drive lag, k_p max(T, τ_d) ≤ 0.5)",
     [](const S& s) -> std::string { return controller_refusal<Controller>(s); }},
};

// What the law takes from the plant: the reading's scale and kind, the drive.
void derive(S& s) {
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  // [motion] kind = "harmonic_roll" (or no [motion]): the platform's own vibration generator moves the base.
  s.plant.from_motion = true;
  if (s.plant.base.kind == motion::BaseMotionKind::kHarmonicRoll) {
    const int vibration = s.plant.base.vibration.count;  // kept for the rule that refuses it
    s.plant.base = models::ConingPlatform::generated(s.plant.platform);
    s.plant.base.vibration.count = vibration;
  }
  const sensors::SingleAxisGyroParams& g = s.plant.platform.gyro.gyro;
  firmware::ConingNullParams& law = s.controller.law;
  law.integrating = !(g.c2 > 0.0);
  law.scale = (law.integrating ? g.d2 : g.c2) / g.H;
  law.rate_per_volt = s.plant.platform.drive_rate_per_volt;
  law.drive_time_constant = s.plant.platform.drive_time_constant;
  law.voltage_limit = s.plant.voltage_limit;
}

}  // namespace

std::unique_ptr<DeviceScene> read_coning(SceneReader& r) {
  auto s = std::make_unique<ConingScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  schema::read(r, kFields, *s);
  read_base_motion(r, s->plant.base, s->loop.duration_s);
  derive(*s);
  schema::check(r, kRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_coning_scene(std::move(s));
}

SceneDoc coning_doc() { return {{schema::document(kFields), base_motion_doc()}, schema::document(kRules)}; }

}  // namespace gyrostab::tools
