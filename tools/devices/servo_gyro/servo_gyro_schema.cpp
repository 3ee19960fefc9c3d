// The keys of a servo gyro scene: one field table over ServoGyroScene (tools/scene/schema.hpp), the source of
// the reader, its messages and docs/scenes.md.
#include <algorithm>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/servo_gyro/servo_gyro_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/read_rk4_scene.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = ServoGyroScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicServoGyroController<firmware::posix::MonotonicClock>;

constexpr schema::Field<S> kFields[] = {
    F::number("gyro", "A", "kg m²", Range::positive(),
              "axis-1 inertia: outer + inner gimbal + rotor + oscillator at β = 0", GS_NUMBER(plant.gyro.A))
        .req(),
    F::number("gyro", "B", "kg m²", Range::positive(), "inner gimbal + rotor about axis 2",
              GS_NUMBER(plant.gyro.B))
        .req(),
    F::number("gyro", "Q", "kg m²", Range::any(), "A^R + A^J − C^J of (10.4): I(β) = A − Q sin²β; A − Q > 0",
              GS_NUMBER(plant.gyro.Q)),
    F::number("gyro", "H", "N m s", Range::positive(), "rotor spin momentum", GS_NUMBER(plant.gyro.H)).req(),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(),
              "viscous friction on axis 2 (the motor supplies it, and it is in M2)",
              GS_NUMBER(plant.gyro.d2)),
    F::number("gyro", "brake_full_Nms", "N m s/rad", Range::positive(),
              "brake on axis 2 at precession_brake = 1 (safe state); checked against the plant step",
              GS_NUMBER(plant.brake_full_Nms)),
    F::number("oscillator", "c1", "N m/rad", Range::non_negative(),
              "oscillator stiffness on axis 1 (resonance at sqrt(c1/A))", GS_NUMBER(plant.gyro.c1))
        .req(),
    F::number("oscillator", "d1", "N m s/rad", Range::non_negative(),
              "oscillator damping on axis 1 (at resonance α_A = H/d1)", GS_NUMBER(plant.gyro.d1))
        .req(),
    F::number("sensors", "drive_rate_noise_density", "rad/s/√Hz", Range::non_negative(),
              "axis-2 tachometer white noise (the rate loop's input; k_p × it is the motor torque's noise)",
              GS_NUMBER(plant.sensors.drive_rate_noise_density)),
    F::number("sensors", "drive_rate_bias", "rad/s", Range::closed(-1.0, 1.0), "axis-2 tachometer bias",
              GS_NUMBER(plant.sensors.drive_rate_bias)),
    F::number("sensors", "alpha_rate_noise_density", "rad/s/√Hz", Range::non_negative(),
              "axis-1 rate white noise (the feed-forward's input)",
              GS_NUMBER(plant.sensors.alpha_rate_noise_density)),
    F::integer("sensors", "drive_encoder_counts_per_rev", "counts/rev", 16, 1 << 30,
               "axis-2 absolute encoder resolution (single turn: β read in [−π, π))",
               GS_INTEGER(plant.sensors.drive_encoder_counts_per_rev)),
    F::integer("sensors", "alpha_encoder_counts_per_rev", "counts/rev", 16, 1 << 30,
               "axis-1 encoder resolution", GS_INTEGER(plant.sensors.alpha_encoder_counts_per_rev)),
    F::number("controller", "Omega", "rad/s", Range::closed(-1e3, 1e3), "drive rate of axis 2, β' reference",
              GS_NUMBER(controller.reference))
        .req(),
    // The tuning of firmware/control/servo_gyro_law.hpp on B β'' = M2: k_p = B ω_c gives the rate bandwidth
    // ω_c, k_i = k_p ω_c / 4 = k_p² / (4B) a double closed-loop pole at −ω_c/2.
    F::number("controller", "rate_kp", "N m s/rad", Range::positive(),
              "rate loop k_p = B ω_c (bandwidth ω_c)", GS_NUMBER(controller.law.rate_kp))
        .defaults_to([](const S& s) { return 200.0 * s.plant.gyro.B; }, "200 B (ω_c = 200 rad/s)"),
    F::number("controller", "rate_ki", "N m/rad", Range::non_negative(),
              "rate loop k_i (k_p²/(4B): double pole at −ω_c/2)", GS_NUMBER(controller.law.rate_ki))
        .defaults_to(
            [](const S& s) {
              const double kp = s.controller.law.rate_kp;
              return kp * kp / (4.0 * s.plant.gyro.B);
            },
            "rate_kp²/(4 B)"),
    F::flag("controller", "feedforward", "add the feed-forward −H cosβ α' of (14.43)",
            GS_FLAG(controller.law.feedforward)),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "motor torque limit",
              GS_NUMBER(controller.law.torque_limit_Nm))
        .req()
        .with_note("(14.43) needs ½HΩα_A(1 + \\|sin φ\\|), the spin-up B Ω/t"),
    F::number("report", "settle_s", "s", Range::non_negative(),
              "the torque and amplitude measurements start after this time", GS_NUMBER(settle_s))
        .defaults_to([](const S& s) { return std::min(15.0, 0.5 * s.loop.duration_s); },
                     "min(15, 0.5 duration_s)")
        .within([](const S& s) { return Range::closed(0.0, s.loop.duration_s); }, "0 … duration_s"),
};

// The plant step against the fastest mode (oscillator or nutation) of the gyro driven at β' = Ω, with the
// bearing's friction plus `brake` on axis 2; "" or the problem.
std::string plant_step_problem(const S& s, double brake) {
  models::ServoGyroParams g = s.plant.gyro;
  g.d2 += brake;
  const double h_sub = s.loop.tick_s() / s.loop.substeps;
  const models::ServoGyro::State x0 = models::ServoGyro::make_state(0.0, 0.0, 0.0, s.controller.reference);
  const dynamics::StepCheck step = dynamics::check_step(
      dynamics::Method::kRk4, dynamics::fastest_mode(models::ServoGyro(g), 0.0, x0), h_sub);
  return step.ok ? "" : step.message;
}

// The checks after the first one assume a physically possible gyro.
bool possible(const S& s) {
  return s.plant.gyro.invalid_reason() == nullptr;
}

constexpr schema::Rule<S> kRules[] = {
    {"gyro", "A", "the gyro is physically possible: A − Q > 0 (I(β) = A − Q sin²β)",
     [](const S& s) -> std::string {
       const char* why = s.plant.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"controller", "rate_kp",
     "the controller's start-up check (firmware/app/servo_gyro_controller.hpp): the PI rate loop holds at "
     "the control period T, k_p T/B ≤ 0.5",
     [](const S& s) -> std::string {
       return possible(s) ? controller_refusal<Controller>(s) : "";
     }},
    {"loop", "plant_substeps",
     "the plant step resolves the gyro's fastest mode (oscillator or nutation) at β' = Ω; the message gives "
     "the plant_substeps needed",
     [](const S& s) -> std::string { return possible(s) ? plant_step_problem(s, 0.0) : ""; }},
    {"gyro", "brake_full_Nms", "the plant step also resolves the gyro held by the safe state's brake",
     [](const S& s) -> std::string {
       if (!possible(s)) return "";
       const std::string why = plant_step_problem(s, s.plant.brake_full_Nms);
       return why.empty() ? "" : "too stiff for the plant step: " + why;
     }},
};

// What the controller takes from the plant, and the rate of its loop.
void derive(S& s) {
  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.reference_kind = firmware::ServoGyroReference::kRate;
  c.law.B = s.plant.gyro.B;
  c.law.H = s.plant.gyro.H;
}

}  // namespace

std::unique_ptr<DeviceScene> read_servo_gyro(SceneReader& r) {
  auto s = schema::read_rk4_scene(r, kFields, derive, kRules);
  return s ? make_servo_gyro_scene(std::move(s)) : nullptr;
}

SceneDoc servo_gyro_doc() {
  return {{schema::document(kFields)}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
