// The keys of a two-rotor stabilizer scene: one field table over TwoRotorStabilizerScene
// (tools/scene/schema.hpp), the source of the reader, its messages and docs/scenes.md.
#include <cstdio>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/two_rotor_stabilizer/two_rotor_stabilizer_scene.hpp"
#include "tools/devices/two_rotor_stabilizer/two_rotor_sampled.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/read_rk4_scene.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = TwoRotorStabilizerScene;
using F = schema::Fields<S>;
using Kind = plants::TwoRotorPlantKind;
using Controller = firmware::BasicTwoRotorStabilizerController<firmware::posix::MonotonicClock>;
using plants::TwoRotorDynamics;

constexpr std::string_view kKinds[] = {"gyro_frame", "two_axis"};

bool frame(const S& s) { return s.plant.kind == Kind::kGyroFrame; }
bool two_axis(const S& s) { return s.plant.kind == Kind::kTwoAxis; }

void set_A(S& s, double v) { s.plant.frame.A = s.plant.two_axis.A = v; }
double get_A(const S& s) { return s.plant.frame.A; }
void set_B(S& s, double v) { s.plant.frame.B = s.plant.two_axis.B = v; }
double get_B(const S& s) { return s.plant.frame.B; }
void set_H(S& s, double v) { s.plant.frame.H = s.plant.two_axis.H = v; }
double get_H(const S& s) { return s.plant.frame.H; }
void set_d1(S& s, double v) { s.plant.frame.d1 = s.plant.two_axis.d1 = v; }
double get_d1(const S& s) { return s.plant.frame.d1; }
void set_d2(S& s, double v) { s.plant.frame.d2 = s.plant.two_axis.d2 = v; }
double get_d2(const S& s) { return s.plant.frame.d2; }

constexpr schema::Field<S> kFields[] = {
    F::choice("stabilizer", "kind", kKinds,
              "gyro_frame: Fig. 14.7 (one frame, two linked counter-rotating gyros); two_axis: Fig. 14.8",
              GS_CHOICE(plant.kind))
        .req(),
    F::number("gyro", "A", "kg m²", Range::positive(), "everything inside frame 1, about axis 1", set_A, get_A)
        .req(),
    F::number("gyro", "B", "kg m²", Range::positive(),
              "gyro_frame: one case + rotor about its case axis; two_axis: platform + gyros about axis 2", set_B,
              get_B)
        .req(),
    F::number("gyro", "H", "N m s", Range::positive(), "one rotor's spin momentum", set_H, get_H).req(),
    F::number("gyro", "d1", "N m s/rad", Range::non_negative(), "frame 1 bearing viscous damping", set_d1,
              get_d1),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(),
              "gyro_frame: each case bearing; two_axis: frame 2 bearing (viscous)", set_d2, get_d2),
    F::number("gyro", "J", "kg m²", Range::positive(), "one case + rotor about its case axis (J < A, B)",
              GS_NUMBER(plant.two_axis.J))
        .req()
        .when(two_axis, "two_axis"),
    F::number("gyro", "c", "N m s/rad", Range::non_negative(), "each case bearing viscous damping",
              GS_NUMBER(plant.two_axis.c))
        .when(two_axis, "two_axis"),
    F::flag("gyro", "counter_rotating", "H^II = −H^I (true, the book's) or +H^I (the comparison)",
            GS_FLAG(counter_rotating))
        .when(two_axis, "two_axis"),
    F::number("base", "Omega1", "rad/s", Range::closed(-1.0, 1.0), "constant base rate about axis 1",
              GS_NUMBER(plant.base.rate[0]))
        .when(frame, "gyro_frame"),
    F::number("base", "Omega2", "rad/s", Range::closed(-1.0, 1.0), "constant base rate about axis 2",
              GS_NUMBER(plant.base.rate[1]))
        .when(frame, "gyro_frame"),
    F::number("base", "Omega3", "rad/s", Range::closed(-1.0, 1.0), "constant base rate about axis 3",
              GS_NUMBER(plant.base.rate[2]))
        .when(frame, "gyro_frame"),
    F::integer("base", "harmonic_axis", "", 1, 3, "base axis of the harmonic rotation Φ sin(ν t)",
               GS_INTEGER(base_axis))
        .when(frame, "gyro_frame"),
    F::number("base", "harmonic_amplitude_rad", "rad", Range::closed(0.0, 0.5), "Φ",
              GS_NUMBER(plant.base.amplitude))
        .when(frame, "gyro_frame"),
    F::number("base", "harmonic_frequency_rad_s", "rad/s", Range::open_closed(0.0, 10.0), "ν",
              GS_NUMBER(plant.base.frequency))
        .when(frame, "gyro_frame"),
    F::number("disturbance", "M1_Nm", "N m", Range::closed(-1e4, 1e4), "step torque on frame 1",
              GS_NUMBER(plant.disturbance.M1_Nm)),
    F::number("disturbance", "M1_time_s", "s", Range::non_negative(), "time of the M1 step",
              GS_NUMBER(plant.disturbance.M1_time_s)),
    F::number("disturbance", "M2_Nm", "N m", Range::closed(-1e4, 1e4),
              "step torque on case I (gyro_frame) or frame 2 (two_axis)", GS_NUMBER(plant.disturbance.M2_Nm)),
    F::number("disturbance", "M2_time_s", "s", Range::non_negative(), "time of the M2 step",
              GS_NUMBER(plant.disturbance.M2_time_s)),
    F::number("controller", "k1", "N m/rad", Range::positive(), "M1^K per rad of the case angle β1",
              GS_NUMBER(controller.law.k1))
        .req(),
    F::number("controller", "dK1", "N m s/rad", Range::non_negative(), "M1^K per rad/s of the frame rate α'",
              GS_NUMBER(controller.law.dK1)),
    F::number("controller", "k2", "N m/rad", Range::positive(), "M2^K per rad of the case angle β2",
              GS_NUMBER(controller.law.k2))
        .req()
        .when(two_axis, "two_axis"),
    F::number("controller", "dK2", "N m s/rad", Range::non_negative(), "M2^K per rad/s of the frame rate γ'",
              GS_NUMBER(controller.law.dK2))
        .when(two_axis, "two_axis"),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "motor torque limit (each motor)",
              GS_NUMBER(controller.law.torque_limit_Nm)),
    F::number("report", "nutation_window_s", "s", Range::open_closed(0.0, 100.0),
              "the measured nutation is the root of a recurrence fitted to β1 over this long from 20 ms after the "
              "first disturbance step (docs/sampled-data.md)",
              GS_NUMBER(nutation_window_s)),
};

bool possible(const S& s) {
  return (frame(s) ? s.plant.frame.invalid_reason() : s.plant.two_axis.invalid_reason()) == nullptr;
}

// The plant step against the fastest mode of the open-loop plant (nutation), "" or the problem.
std::string plant_step_problem(const S& s) {
  const TwoRotorDynamics dyn{s.plant.kind, TwoRotorDynamics::Frame(s.plant.frame, s.plant.base),
                             models::TwoRotorTwoAxis(s.plant.two_axis), s.plant.disturbance};
  const double h_sub = s.loop.tick_s() / s.loop.substeps;
  const dynamics::StepCheck step = dynamics::check_step(
      dynamics::Method::kRk4, dynamics::fastest_mode(dyn, 0.0, TwoRotorDynamics::State::Zero()), h_sub);
  return step.ok ? "" : step.message;
}

// The sampled loop's verdict: "" when stable. A loop the continuous test refuses is the start-up check's
// (rule on k1); here only the difference is added.
std::string sampled_problem(const S& s) {
  const TwoRotorSampled sampled = two_rotor_sampled(s);
  if (!sampled.roots.stable())
    return "the sampled loop is unstable: " +
           analysis::sampled_instability(sampled.roots, sampled.timing, sampled.continuous_stable) +
           "; lower the gains or the tick, or reduce the latency";
  if (!sampled.continuous_stable) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "the sampled loop would be stable (|z| = %.6g), but the firmware's start-up check "
                  "is the continuous test and refuses these gains", sampled.roots.max_abs_z);
    return buf;
  }
  return "";
}

constexpr schema::Rule<S> kRules[] = {
    {"gyro", "A", "the plant is physically possible (inertias > 0, J < A, B for two_axis, damping >= 0)",
     [](const S& s) -> std::string {
       const char* why = frame(s) ? s.plant.frame.invalid_reason() : s.plant.two_axis.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"controller", "k1",
     "the controller's start-up check (firmware/control/two_rotor_stabilizer_law.hpp): the gains lie inside "
     "the Hurwitz region of the closed loop ((TR4) for the gyro frame, P6 for two_axis); the message gives the "
     "largest stable k1 at the configured k2/k1; rate gains dK T / A ≤ 0.5",
     [](const S& s) -> std::string { return possible(s) ? controller_refusal<Controller>(s) : ""; }},
    {"loop", "plant_substeps",
     "the plant step resolves the fastest open-loop mode (nutation); the message gives the plant_substeps "
     "needed",
     [](const S& s) -> std::string { return possible(s) ? plant_step_problem(s) : ""; }},
    {"loop", "latency_ticks",
     "the loop as it runs is stable: the closed loop sampled at the law's period with the zero-order hold and "
     "the latency (docs/sampled-data.md), every |z| < 1; says so when the continuous verdict would differ",
     [](const S& s) -> std::string { return possible(s) ? sampled_problem(s) : ""; }},
};

// What the controller takes from the plant.
void derive(S& s) {
  s.plant.base.axis = s.base_axis - 1;
  s.plant.two_axis.spin_sign = s.counter_rotating ? -1.0 : 1.0;
  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  auto& l = c.law;
  l.kind = frame(s) ? firmware::TwoRotorKind::kGyroFrame : firmware::TwoRotorKind::kTwoAxis;
  l.A = s.plant.frame.A;
  l.B = s.plant.frame.B;
  l.H = s.plant.frame.H;
  l.d1 = s.plant.frame.d1;
  l.d2 = s.plant.frame.d2;
  l.J = s.plant.two_axis.J;
  l.c = s.plant.two_axis.c;
  l.spin_sign = frame(s) ? -1.0 : s.plant.two_axis.spin_sign;
  if (frame(s)) {
    l.k2 = 0.0;
    l.dK2 = 0.0;
  }
}

}  // namespace

std::unique_ptr<DeviceScene> read_two_rotor_stabilizer(SceneReader& r) {
  auto s = schema::read_rk4_scene(r, kFields, derive, kRules);
  return s ? make_two_rotor_stabilizer_scene(std::move(s)) : nullptr;
}

SceneDoc two_rotor_stabilizer_doc() {
  return {{schema::document(kFields)}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
