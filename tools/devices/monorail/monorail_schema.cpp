// The keys of a monorail scene: one field table over MonorailScene (tools/scene/schema.hpp), the source of
// the reader, its messages and docs/scenes.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "firmware/control/hurwitz.hpp"
#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/monorail/monorail_curve.hpp"
#include "tools/devices/monorail/monorail_sampled.hpp"
#include "tools/devices/monorail/monorail_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/read_rk4_scene.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = MonorailScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicMonorailController<firmware::posix::MonotonicClock>;

double never(const S&) {
  return motion::kNeverS;
}

constexpr schema::Field<S> kFields[] = {
    F::number("car", "A", "kg m²", Range::positive(), "car inertia about the rail, case upright",
              GS_NUMBER(plant.car.A))
        .req(),
    F::number("car", "c", "N m/rad", Range::positive(),
              "overturning stiffness of the whole car m g h (case upright)", GS_NUMBER(plant.car.c))
        .req(),
    F::number("gyro", "B", "kg m²", Range::positive(), "case + rotor inertia about the case axis 2",
              GS_NUMBER(plant.car.B))
        .req(),
    F::number("gyro", "Q", "kg m²", Range::any(), "A^R + A^J − C^J of (10.4): I(β) = A − Q sin²β; A − Q > 0",
              GS_NUMBER(plant.car.Q)),
    F::number("gyro", "q", "N m/rad", Range::positive(),
              "overturning stiffness of the case G s (centre of mass above axis 2)", GS_NUMBER(plant.car.q))
        .req(),
    F::number("gyro", "H", "N m s", Range::positive(), "rotor spin momentum; > sqrt(qA) + sqrt(cB) (14.4)",
              GS_NUMBER(plant.car.H))
        .req(),
    F::number("gyro", "d_mechanical", "N m s/rad", Range::non_negative(),
              "passive damper on axis 2 (the motor realises the law's d; this adds to it in the window)",
              GS_NUMBER(plant.car.d)),
    F::number("gyro", "brake_full_Nms", "N m s/rad", Range::positive(),
              "brake on axis 2 at precession_brake = 1 (safe state); checked against the plant step",
              GS_NUMBER(plant.brake_full_Nms)),
    F::number("initial", "phi0_deg", "deg", Range::closed(-30.0, 30.0),
              "initial car tilt (released from the stands)", GS_NUMBER(plant.phi0))
        .degrees(),
    F::number("initial", "beta0_deg", "deg", Range::closed(-60.0, 60.0), "initial case angle",
              GS_NUMBER(plant.beta0))
        .degrees(),
    F::number("track", "speed_m_s", "m/s", Range::closed(0.0, 150.0),
              "car speed v (centrifugal moment c v Ω3/g; curve radius v/Ω3)",
              GS_NUMBER(plant.track.speed_m_s)),
    F::number("track", "Omega3", "rad/s", Range::closed(-2.0, 2.0),
              "turning rate of the path in the curve, + in the rotor's spin sense",
              GS_NUMBER(plant.track.curve.Omega3)),
    F::number("track", "curve_start_s", "s", Range::non_negative(),
              "curve entry (start of the entry transition)", GS_NUMBER(plant.track.curve.start_s))
        .defaults_to(never, "never (no curve)"),
    F::number("track", "curve_end_s", "s", Range::non_negative(), "curve exit (start of the exit transition)",
              GS_NUMBER(plant.track.curve.end_s))
        .defaults_to(never, "never"),
    F::number("track", "transition_s", "s", Range::non_negative(),
              "entry and exit transitions: Ω3 ramps linearly (a clothoid)",
              GS_NUMBER(plant.track.curve.transition_s)),
    F::flag("track", "allow_unstable_curve", "run even if the loop of (14.6) is unstable in the curve",
            GS_FLAG(allow_unstable_curve)),
    F::number("gust", "M1", "N m", Range::closed(-1e7, 1e7),
              "side-wind roll moment on the car, + tilts to + φ", GS_NUMBER(plant.track.gust.M1)),
    F::number("gust", "start_s", "s", Range::non_negative(), "gust onset",
              GS_NUMBER(plant.track.gust.start_s))
        .defaults_to(never, "never (no gust)"),
    F::number("gust", "duration_s", "s", Range::non_negative(), "from onset to the start of the decay",
              GS_NUMBER(plant.track.gust.duration_s)),
    F::number("gust", "rise_s", "s", Range::non_negative(), "linear rise and decay time",
              GS_NUMBER(plant.track.gust.rise_s)),
    F::number("sensors", "tilt_noise_rad", "rad", Range::non_negative(),
              "car tilt (AHRS, relative to the local level) white noise, standard deviation per sample",
              GS_NUMBER(plant.sensors.tilt_noise_rad)),
    F::number("sensors", "tilt_bias_rad", "rad", Range::closed(-0.05, 0.05), "car tilt bias",
              GS_NUMBER(plant.sensors.tilt_bias_rad)),
    F::number("sensors", "tilt_rate_noise_density", "rad/s/√Hz", Range::non_negative(),
              "car roll-rate gyro white noise", GS_NUMBER(plant.sensors.tilt_rate_noise_density)),
    F::number("sensors", "case_rate_noise_density", "rad/s/√Hz", Range::non_negative(),
              "case rate gyro white noise (the law's damper input)",
              GS_NUMBER(plant.sensors.case_rate_noise_density)),
    F::number("sensors", "case_rate_bias", "rad/s", Range::closed(-0.1, 0.1), "case rate gyro bias",
              GS_NUMBER(plant.sensors.case_rate_bias)),
    F::integer("sensors", "encoder_counts_per_rev", "counts/rev", 16, 1 << 30,
               "case-angle encoder resolution", GS_INTEGER(plant.sensors.encoder_counts_per_rev)),
    F::number("controller", "k", "N m/rad", Range::any(),
              "motor gain on the car tilt, M2 = k φ − d β' (14.2); inside the gain window of (14.5)",
              GS_NUMBER(controller.law.k))
        .req(),
    F::number("controller", "d", "N m s/rad", Range::non_negative(),
              "damper realised by the motor; d + d_mechanical > 0", GS_NUMBER(controller.law.d))
        .req(),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "motor torque limit",
              GS_NUMBER(controller.law.torque_limit_Nm)),
    F::number("report", "settle_s", "s", Range::non_negative(), "tilt statistics start after this time",
              GS_NUMBER(settle_s))
        .defaults_to([](const S& s) { return std::min(10.0, 0.2 * s.loop.duration_s); },
                     "min(10, 0.2 duration_s)")
        .within([](const S& s) { return Range::closed(0.0, s.loop.duration_s); }, "0 … duration_s"),
};

bool curve_ordered(const S& s) {
  const motion::CurveProfile& c = s.plant.track.curve;
  return !(c.end_s < c.start_s + c.transition_s);
}
bool gust_ordered(const S& s) {
  return !(s.plant.track.gust.rise_s > s.plant.track.gust.duration_s);
}
// The checks after the first three assume a physically possible car and an ordered track.
bool consistent(const S& s) {
  return s.plant.car.invalid_reason() == nullptr && curve_ordered(s) && gust_ordered(s);
}

// The loop of (14.6) at the curve's Ω3 with the firmware law: Hurwitz, or the car leaves the curve lying down
// (the continuous loop; the sampled one at 1 kHz differs by O(ω_N T)). "" or the problem.
std::string curve_problem(const S& s) {
  const models::MonorailParams& p = s.plant.car;
  const firmware::MonorailMotorParams& l = s.controller.law;
  const double W = s.plant.track.curve.Omega3, cW = p.c - p.H * W, qW = p.q - p.H * W, dt = l.d + p.d;
  const firmware::HurwitzResult h = firmware::hurwitz_quartic(
      p.A * p.B, p.A * dt, p.H * p.H - qW * p.A - cW * p.B, l.k * p.H - cW * dt, cW * qW);
  if (!std::isfinite(s.plant.track.curve.start_s) || W == 0.0 || h.stable || s.allow_unstable_curve)
    return "";
  char msg[400];
  if (p.c > p.H * W && p.H * W > p.q) {
    std::snprintf(
        msg, sizeof msg,
        "= %g: H Omega3 = %g lies between q = %g and c = %g, (14.7): the car overturns in the curve for "
        "every gain; keep |Omega3| < q/H = %g (or set allow_unstable_curve = true to watch it)",
        W, p.H * W, p.q, p.c, p.q / p.H);
  } else {
    const firmware::MonorailGainWindow w = firmware::monorail_gain_window(law_in_curve(l, W));
    std::snprintf(msg, sizeof msg,
                  "= %g: the loop of (14.6) with k = %g is unstable in the curve (window there %g < k < %g); "
                  "set allow_unstable_curve = true to run it anyway",
                  W, l.k, w.k_min, w.k_max);
  }
  return msg;
}

// The sampled verdict on the straight and in the curve: "" or the problem. The firmware's check and the
// curve rule are the continuous tests; a loop they accept that the sampled loop cannot hold is refused, and
// where they refuse but the sampled loop would be stable the message says so.
std::string sampled_problem(const S& s) {
  const analysis::SampledTiming timing = monorail_timing(s.controller, s.loop.tick_s(), s.loop.latency_ticks);
  const double W = s.plant.track.curve.Omega3;
  const bool has_curve = std::isfinite(s.plant.track.curve.start_s) && W != 0.0 && !s.allow_unstable_curve;
  std::string out;
  for (int i = 0; i < (has_curve ? 2 : 1); ++i) {
    const double Omega3 = i == 0 ? 0.0 : W;
    const MonorailSampled m = monorail_sampled(s.plant.car, s.controller, Omega3, timing);
    // The continuous verdict of (14.5) for the same loop (the check's and the curve rule's Hurwitz test).
    const bool cont = firmware::monorail_gain_window(law_in_curve(s.controller.law, Omega3)).hurwitz.stable;
    char where[96];
    std::snprintf(where, sizeof where, " (%s, law every %.4g ms, latency %d tick(s))",
                  i == 0 ? "on the straight" : "in the curve", timing.period_s * 1e3, s.loop.latency_ticks);
    if (cont && !m.roots.stable()) {
      out += (out.empty() ? "" : "; ") + std::string("the sampled loop is unstable: ") +
             analysis::sampled_instability(m.roots, timing, true) + where;
    } else if (!cont && m.roots.stable()) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "unstable in continuous time; the sampled loop would be stable (|z| = %.6g)",
                    m.roots.max_abs_z);
      out += (out.empty() ? "" : "; ") + std::string(buf) + where;
    }
  }
  return out;
}

// The plant step against the car's fastest mode for the car `p`, from the initial state; "" or the problem.
std::string plant_step_problem(const S& s, const models::MonorailParams& p) {
  const double h_sub = s.loop.tick_s() / s.loop.substeps;
  const models::Monorail::State x0 = models::Monorail::make_state(s.plant.phi0, s.plant.beta0, 0.0, 0.0);
  const dynamics::StepCheck step = dynamics::check_step(
      dynamics::Method::kRk4, dynamics::fastest_mode(models::Monorail(p), 0.0, x0), h_sub);
  return step.ok ? "" : step.message;
}

constexpr schema::Rule<S> kRules[] = {
    {"car", "A", "the car and its gyro are physically possible: A − Q > 0 (I(β) = A − Q sin²β)",
     [](const S& s) -> std::string {
       const char* why = s.plant.car.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"track", "curve_end_s", "curve_end_s ≥ curve_start_s + transition_s (the exit starts after the entry)",
     [](const S& s) -> std::string {
       return curve_ordered(s) ? ""
                               : "must be >= curve_start_s + transition_s (the exit starts after the entry)";
     }},
    {"gust", "rise_s", "rise_s ≤ duration_s",
     [](const S& s) -> std::string { return gust_ordered(s) ? "" : "must be <= duration_s"; }},
    {"controller", "k",
     "the controller's start-up check (firmware/app/monorail_controller.hpp): a gyro strong enough for a "
     "gain window, H > sqrt(qA) + sqrt(cB) (14.4); d + d_mechanical > 0; k inside the window d(c + Aω_P²)/H "
     "< k < d(c + Aω_N²)/H of (14.5), d the total damper; the sampled damper d T/B ≤ 0.5 (the message gives "
     "the bounds)",
     [](const S& s) -> std::string {
       return consistent(s) ? controller_refusal<Controller>(s) : "";
     }},
    {"track", "Omega3",
     "with a curve, unless allow_unstable_curve: the loop of (14.6) with the firmware law is stable at the "
     "curve's Ω3 (refused in particular for (14.7) c > HΩ3 > q, where the car overturns for every gain: the "
     "message gives q/H)",
     [](const S& s) -> std::string {
       if (!consistent(s) || !Controller::check(s.controller).ok) return "";
       return curve_problem(s);
     }},
    {"controller", "k",
     "the loop as it runs — sampled at the law's period (control_divisor ticks) through the zero-order hold "
     "with latency_ticks of latency (docs/sampled-data.md) — has every root |z| < 1 on the straight and at "
     "the curve's Ω3 (unless allow_unstable_curve); the message says when the continuous verdict differs",
     [](const S& s) -> std::string {
       if (!consistent(s)) return "";
       return sampled_problem(s);
     }},
    {"loop", "plant_substeps",
     "the plant step resolves the car's fastest mode, with the law's k and d in the linearisation as passive "
     "gains (the firmware's are sampled); the message gives the plant_substeps needed",
     [](const S& s) -> std::string {
       if (!consistent(s)) return "";
       models::MonorailParams closed = s.plant.car;
       closed.k = s.controller.law.k;
       closed.d = s.controller.law.d + s.plant.car.d;
       return plant_step_problem(s, closed);
     }},
    {"gyro", "brake_full_Nms", "the plant step also resolves the case held by the safe state's brake",
     [](const S& s) -> std::string {
       if (!consistent(s)) return "";
       models::MonorailParams braked = s.plant.car;
       braked.d += s.plant.brake_full_Nms;
       const std::string why = plant_step_problem(s, braked);
       return why.empty() ? "" : "too stiff for the plant step: " + why;
     }},
};

// What the controller takes from the plant, and the rate of its loop.
void derive(S& s) {
  const models::MonorailParams& p = s.plant.car;
  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.law.A = p.A;
  c.law.B = p.B;
  c.law.c = p.c;
  c.law.q = p.q;
  c.law.H = p.H;
  c.law.d_mechanical = p.d;
}

}  // namespace

std::unique_ptr<DeviceScene> read_monorail(SceneReader& r) {
  auto s = schema::read_rk4_scene(r, kFields, derive, kRules);
  return s ? make_monorail_scene(std::move(s)) : nullptr;
}

SceneDoc monorail_doc() {
  return {{schema::document(kFields)}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
