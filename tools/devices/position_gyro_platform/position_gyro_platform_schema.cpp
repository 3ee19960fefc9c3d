// The keys of a position-gyro platform scene: one field table over PositionGyroPlatformScene
// (tools/scene/schema.hpp), the source of the reader, its messages and docs/scenes.md.
#include <algorithm>
#include <cmath>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/position_gyro_platform/position_gyro_platform_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/read_rk4_scene.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = PositionGyroPlatformScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicPositionGyroPlatformController<firmware::posix::MonotonicClock>;

Range within_run(const S& s) { return Range::closed(0.0, s.loop.duration_s); }

constexpr schema::Field<S> kFields[] = {
    F::number("platform", "Theta", "kg m²", Range::positive(), "platform inertia Θ about axis 1",
              GS_NUMBER(plant.platform.Theta)),
    F::number("platform", "d_base", "N m s/rad", Range::non_negative(),
              "bearing friction on the base: carries d_base φ' of the base's roll onto the platform",
              GS_NUMBER(plant.platform.d_base)),
    F::number("gyro", "A", "kg m²", Range::positive(), "outer gimbal with inner gimbal and rotor about axis 1",
              GS_NUMBER(plant.platform.A)),
    F::number("gyro", "B", "kg m²", Range::positive(), "inner gimbal with rotor about axis 2",
              GS_NUMBER(plant.platform.B)),
    F::number("gyro", "H", "N m s", Range::positive(), "spin momentum", GS_NUMBER(plant.platform.H)),
    F::number("gyro", "d1", "N m s/rad", Range::non_negative(),
              "damping of the platform against the outer gimbal", GS_NUMBER(plant.platform.d1)),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(), "damping of the inner gimbal axis",
              GS_NUMBER(plant.platform.d2)),
    F::number("disturbance", "torque_Nm", "N m", Range::closed(-100.0, 100.0),
              "disturbance torque M1^SP on the platform, stepped on and held", GS_NUMBER(plant.disturbance_Nm)),
    F::number("disturbance", "start_s", "s", Range::non_negative(), "time of the step",
              GS_NUMBER(disturbance_start_s))
        .within(within_run, "0 … duration_s"),
    F::number("base", "amplitude_deg", "deg", Range::closed(0.0, 30.0), "base roll φ = φ0 sin(ω_b t): φ0",
              GS_NUMBER(plant.base_amplitude_rad))
        .degrees(),
    F::number("base", "frequency_hz", "Hz", Range::closed(0.0, 50.0), "ω_b/2π", GS_NUMBER(plant.base_frequency_hz)),
    F::number("sensors", "pickoff_noise_density", "rad/√Hz", Range::non_negative(),
              "white noise of the pick-off δ − α", GS_NUMBER(plant.pickoff_noise_density)),
    F::number("controller", "k", "N m/rad", Range::positive(), "amplifier gain M1^KP = −k(δ − α)",
              GS_NUMBER(controller.law.k)),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "platform torquer limit",
              GS_NUMBER(controller.law.torque_limit_Nm)),
    F::number("controller", "gyro_torque_limit_Nm", "N m", Range::positive(), "gyro torquer limit",
              GS_NUMBER(controller.law.gyro_torque_limit_Nm)),
    F::number("controller", "slew_rate_deg_s", "deg/s", Range::closed(-90.0, 90.0),
              "commanded platform rate ω_cmd: M2^K = −H ω_cmd (16.7)", GS_NUMBER(controller.law.slew_rate_rad_s))
        .degrees(),
    F::number("controller", "slew_start_s", "s", Range::non_negative(), "start of the slew",
              GS_NUMBER(slew_start_s))
        .within(within_run, "0 … duration_s"),
    F::number("controller", "slew_duration_s", "s", Range::non_negative(), "length of the slew",
              GS_NUMBER(slew_duration_s)),
    F::number("report", "fit_delay_s", "s", Range::non_negative(),
              "the inner gimbal angle's extrema (the decay fit) count from this long after the disturbance step (the faster mode gone)",
              GS_NUMBER(fit_delay_s)),
    F::number("report", "lag_window_s", "s", Range::positive(),
              "the lag and the slew rate are means over this long before the slew's start and end",
              GS_NUMBER(lag_window_s)),
};

bool possible(const S& s) { return s.plant.platform.invalid_reason() == nullptr; }

constexpr schema::Rule<S> kRules[] = {
    {"gyro", "H", "usable parameters (Θ, A, B, H > 0; d1, d2, d_base ≥ 0)",
     [](const S& s) -> std::string {
       const char* why = s.plant.platform.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"controller", "k",
     "the controller's start-up check (firmware/control/position_gyro_platform_law.hpp): d1, d2 not both 0 "
     "(undamped: at best marginal, (16.8)); the continuous loop Hurwitz-stable — a gain inside the unstable "
     "band k− < k < k+ of (16.9) is refused with the band's edges; the sampled loop (zero-order hold, control "
     "period, latency_ticks) stable: spectral radius of its discrete closed loop < 1",
     [](const S& s) -> std::string { return possible(s) ? controller_refusal<Controller>(s) : ""; }},
    {"controller", "slew_duration_s", "the slew ends within the run (slew_start_s + slew_duration_s ≤ duration_s)",
     [](const S& s) -> std::string {
       return s.slew_start_s + s.slew_duration_s <= s.loop.duration_s + 1e-9 ? ""
                                                                              : "the slew must end within the run";
     }},
    {"loop", "plant_substeps",
     "RK4's plant sub-step resolves the closed loop's fastest mode (the analog loop at k; the message gives the "
     "`plant_substeps` needed)",
     [](const S& s) -> std::string {
       if (!possible(s)) return "";
       const models::PositionGyroPlatformAnalog m(s.plant.platform, s.controller.law.k);
       const dynamics::StepCheck step = dynamics::check_step(
           dynamics::Method::kRk4,
           dynamics::fastest_mode(m, 0.0, models::PositionGyroPlatform::State::Zero(), "platform"),
           s.loop.tick_s() / s.loop.substeps);
       return step.ok ? "" : step.message;
     }},
};

std::uint64_t ticks_of(const S& s, double t) {
  return static_cast<std::uint64_t>(std::llround(t / s.loop.tick_s()));
}

// The controller's period, latency and plant; the schedule in ticks.
void derive(S& s) {
  firmware::PositionGyroPlatformConfig& c = s.controller;
  const models::PositionGyroPlatformParams& p = s.plant.platform;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.law.plant = {p.Theta, p.A, p.B, p.H, p.d1, p.d2};
  c.law.latency_ticks = static_cast<std::uint32_t>(std::max(0, s.loop.latency_ticks));
  c.law.slew_start_tick = ticks_of(s, s.slew_start_s);
  c.law.slew_stop_tick = ticks_of(s, s.slew_start_s + s.slew_duration_s);
  s.plant.disturbance_tick = static_cast<std::int64_t>(ticks_of(s, s.disturbance_start_s));
}

}  // namespace

std::unique_ptr<DeviceScene> read_position_gyro_platform(SceneReader& r) {
  auto s = schema::read_rk4_scene(r, kFields, derive, kRules);
  return s ? make_position_gyro_platform_scene(std::move(s)) : nullptr;
}

SceneDoc position_gyro_platform_doc() {
  return {{schema::document(kFields)}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
