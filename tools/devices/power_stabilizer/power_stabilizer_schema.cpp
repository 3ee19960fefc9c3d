// The keys of a power stabilizer scene: the option table (read first: the options decide the integrators and
// which keys exist), the field table, the rules between keys, and the checks that need the plant built with
// the chosen options (power_stabilizer_checks.cpp).
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "firmware/fault/sensor_ranges.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_checks.hpp"
#include "tools/devices/base_motion/base_motion_schema.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_scene.hpp"
#include "tools/loop/recorder.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = PowerStabilizerScene;
using F = schema::Fields<S>;

constexpr std::string_view kStructures[] = {"rigid", "elastic"};
constexpr std::string_view kMotors[] = {"torque", "back_emf"};
constexpr std::string_view kFidelities[] = {"full", "precession"};
constexpr std::string_view kDrives[] = {"torque", "dc_motor"};

bool back_emf(const S& s) { return s.back_emf(); }
bool torque_law(const S& s) { return !s.back_emf(); }
bool elastic(const S& s) { return s.elastic(); }
bool dc(const S& s) { return s.dc_drive(); }

constexpr schema::Field<S> kOptions[] = {
    F::choice("gyro", "structure", kStructures, "platform: rigid, or elastic shaft to the gyro (14.31)",
              GS_CHOICE(structure)),
    F::choice("gyro", "motor", kMotors,
              "axis-1 stabilization motor: torque-controlled (the law's torques act), or geared back-EMF "
              "motor with the voltage law (14.26)-(14.27)",
              GS_CHOICE(motor)),
    F::choice("gyro", "fidelity", kFidelities,
              "gyro model: full gimbal gyro (10.4), or `precession`: the reduced model P0 (10.19)-(10.22) (3 "
              "states, no nutation, rk4), run beside the full model on the same scene (report.json "
              "\"reduced_model\"); refused with `elastic`, `dc_motor`, and where ε = ω_P/ω_N ≥ 0.1 at the "
              "operating point",
              GS_CHOICE(fidelity)),
};

void set_roll_axis(S& s, std::int64_t axis) {
  s.base_roll_axis = static_cast<int>(axis);
  s.plant.base.harmonic.axis_B = axis == 1 ? dynamics::Vec3::UnitX() : dynamics::Vec3::UnitY();
}

constexpr schema::Field<S> kFields[] = {
    F::number("gyro", "CR", "kg m²", Range::positive(), "rotor axial moment C^R", GS_NUMBER(gyro.CR)).req(),
    F::number("gyro", "AR", "kg m²", Range::positive(), "rotor transverse moment A^R; 2 A^R ≥ C^R (1.10)",
              GS_NUMBER(gyro.AR))
        .req(),
    F::number("gyro", "AJ", "kg m²", Range::non_negative(), "inner gimbal A^J", GS_NUMBER(gyro.AJ)),
    F::number("gyro", "BJ", "kg m²", Range::non_negative(), "inner gimbal B^J", GS_NUMBER(gyro.BJ)),
    F::number("gyro", "CJ", "kg m²", Range::non_negative(), "inner gimbal C^J", GS_NUMBER(gyro.CJ)),
    F::number("gyro", "AA", "kg m²", Range::non_negative(), "outer gimbal (+ platform when rigid) about axis 1",
              GS_NUMBER(gyro.AA)),
    F::number("gyro", "d1", "N m s/rad", Range::non_negative(),
              "outer bearing viscous friction (with `dc_motor` moved into the drive)", GS_NUMBER(gyro.d1)),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(),
              "inner bearing viscous friction (with `dc_motor` moved into the drive)", GS_NUMBER(gyro.d2)),
    F::number("gyro", "rpm", "rpm", Range::non_negative(),
              "rotor speed (H = C^R Ω); 0 is refused: no gyroscopic coupling, (14.23) unstable", GS_NUMBER(rpm))
        .req(),
    F::number("gyro", "s", "N m/V", Range::closed(1e-6, 1e6), "motor torque per volt at the gimbal, κ k_t/R",
              GS_NUMBER(plant.motor.s))
        .req()
        .when(back_emf, "back_emf"),
    F::number("gyro", "d", "V s/rad", Range::closed(0.0, 1e6), "motor back-EMF per gimbal rate, κ k_e",
              GS_NUMBER(plant.motor.d))
        .req()
        .when(back_emf, "back_emf"),
    F::number("gyro", "kappa", "", Range::closed(1e-3, 1e5), "motor gear ratio κ", GS_NUMBER(plant.motor.kappa))
        .when(back_emf, "back_emf"),
    F::number("gyro", "I", "kg m²", Range::closed(0.0, 1e3), "motor rotor inertia (κ²I added to A)",
              GS_NUMBER(plant.motor.I))
        .when(back_emf, "back_emf"),
    F::number("gyro", "c", "N m/rad", Range::closed(1e-3, 1e12), "shaft stiffness platform-gyro", GS_NUMBER(platform.c))
        .req()
        .when(elastic, "elastic"),
    F::number("gyro", "AP", "kg m²", Range::closed(1e-6, 1e9), "platform inertia about axis 1", GS_NUMBER(platform.AP))
        .req()
        .when(elastic, "elastic"),
    F::number("initial", "alpha0_deg", "deg", Range::closed(-180.0, 180.0), "initial outer-gimbal angle, at rest",
              GS_NUMBER(plant.alpha0))
        .degrees(),
    F::number("initial", "beta0_deg", "deg", Range::closed(-89.99, 89.99),
              "initial inner-gimbal angle, at rest; the loop (14.23) is checked there with the coupling H "
              "cos β0 (gimbal-lock approach)",
              GS_NUMBER(plant.beta0))
        .degrees(),
    F::number("base", "roll_amplitude_rad", "rad", Range::closed(0.0, 0.5), "harmonic base roll amplitude",
              GS_NUMBER(plant.base.harmonic.amplitude)),
    F::number("base", "roll_frequency_rad_s", "rad/s", Range::positive(), "base roll frequency",
              GS_NUMBER(plant.base.harmonic.frequency)),
    F::integer("base", "roll_axis", "", 1, 2, "base axis the roll is about", set_roll_axis,
               [](const S& s) -> std::int64_t { return s.base_roll_axis; }),
    F::number("disturbance", "M1_Nm", "N m", Range::closed(-1e6, 1e6), "torque step on axis 1 (platform)",
              GS_NUMBER(plant.disturbance.M1)),
    F::number("disturbance", "M1_time_s", "s", Range::non_negative(), "time of the axis-1 step",
              GS_NUMBER(plant.disturbance.t1)),
    F::number("disturbance", "M2_Nm", "N m", Range::closed(-1e6, 1e6), "torque step on axis 2",
              GS_NUMBER(plant.disturbance.M2)),
    F::number("disturbance", "M2_time_s", "s", Range::non_negative(), "time of the axis-2 step",
              GS_NUMBER(plant.disturbance.t2)),
    F::number("sensors", "rate_noise_density", "rad/s/√Hz", Range::closed(0.0, 1.0), "rate gyro white noise N",
              GS_NUMBER(plant.rate_gyro.noise.white_density)),
    F::number("sensors", "rate_bias_rad_s", "rad/s", Range::closed(-0.1, 0.1), "rate gyro constant bias",
              GS_NUMBER(plant.rate_gyro.noise.bias)),
    F::number("sensors", "rate_bandwidth_hz", "Hz", Range::closed(0.0, 1e5),
              "rate gyro −3 dB bandwidth, below the base tick's Nyquist frequency; 0: no filter",
              GS_NUMBER(rate_bandwidth_hz)),
    F::integer("sensors", "rate_filter_order", "", 1, 2, "rate gyro low-pass order", GS_INTEGER(rate_filter_order)),
    F::number("sensors", "rate_damping", "", Range::closed(0.05, 5.0), "ζ of the second-order filter",
              GS_NUMBER(rate_damping)),
    F::integer("sensors", "encoder_counts_per_rev", "counts/rev", 16, 1 << 30, "gimbal encoder (torque drive)",
               GS_INTEGER(plant.encoder_counts_per_rev)),
    F::choice("drive", "kind", kDrives,
              "gimbal drives: ideal torque motors, or `dc_motor`: DC motors with gears and current loops on "
              "both axes (not with motor = back_emf)",
              GS_CHOICE(drive)),
    F::number("drive", "R_ohm", "Ω", Range::closed(1e-4, 1e4), "winding resistance", GS_NUMBER(plant.drive.motor.R))
        .req()
        .when(dc, "dc_motor"),
    F::number("drive", "L_H", "H", Range::closed(0.0, 10.0), "winding inductance", GS_NUMBER(plant.drive.motor.L))
        .req()
        .when(dc, "dc_motor"),
    F::number("drive", "k_t_Nm_per_A", "N m/A", Range::closed(1e-5, 1e3), "torque constant (motor side)",
              GS_NUMBER(plant.drive.motor.k_t))
        .req()
        .when(dc, "dc_motor"),
    F::number("drive", "k_e_V_s_per_rad", "V s/rad", Range::closed(0.0, 1e3), "back-EMF constant",
              GS_NUMBER(plant.drive.motor.k_e))
        .when(dc, "dc_motor")
        .defaults_to([](const S& s) { return s.plant.drive.motor.k_t; }, "= k_t"),
    F::number("drive", "J_m_kg_m2", "kg m²", Range::closed(0.0, 10.0), "rotor inertia", GS_NUMBER(plant.drive.motor.J_m))
        .when(dc, "dc_motor"),
    F::number("drive", "voltage_limit_V", "V", Range::closed(0.1, 1e4), "bus limit (also the current loop's)",
              GS_NUMBER(plant.drive.motor.voltage_limit))
        .req()
        .when(dc, "dc_motor"),
    F::number("drive", "current_limit_A", "A", Range::closed(1e-3, 1e4), "current clamp (also the loop's)",
              GS_NUMBER(plant.drive.motor.current_limit))
        .req()
        .when(dc, "dc_motor"),
    F::number("drive", "gear_ratio", "", Range::closed(1.0, 1e4), "motor turns per gimbal turn N",
              GS_NUMBER(plant.drive.gear.ratio))
        .when(dc, "dc_motor"),
    F::number("drive", "gear_efficiency", "", Range::open_closed(0.0, 1.0), "η (τ/η when back-driven)",
              GS_NUMBER(plant.drive.gear.efficiency))
        .when(dc, "dc_motor"),
    F::number("drive", "gear_input_inertia_kg_m2", "kg m²", Range::closed(0.0, 10.0), "gear stages at motor speed",
              GS_NUMBER(plant.drive.gear.input_inertia))
        .when(dc, "dc_motor"),
    F::number("drive", "coulomb_Nm", "N m", Range::closed(0.0, 1e5), "bearing Coulomb friction at the axis",
              GS_NUMBER(plant.drive.friction.coulomb))
        .when(dc, "dc_motor"),
    F::number("drive", "breakaway_Nm", "N m", Range::closed(0.0, 1e5), "static friction, ≥ coulomb_Nm",
              GS_NUMBER(plant.drive.friction.breakaway))
        .when(dc, "dc_motor")
        .defaults_to([](const S& s) { return s.plant.drive.friction.coulomb; }, "= coulomb_Nm"),
    F::number("drive", "viscous_Nms", "N m s/rad", Range::closed(0.0, 1e6), "viscous friction beside [gyro] d1/d2",
              GS_NUMBER(plant.drive.friction.viscous))
        .when(dc, "dc_motor"),
    F::number("drive", "stick_velocity_rad_s", "rad/s", Range::closed(1e-12, 1.0), "Karnopp dead band",
              GS_NUMBER(plant.drive.friction.stick_velocity))
        .when(dc, "dc_motor"),
    F::integer("drive", "encoder_counts_per_rev", "counts/rev", 4, 1 << 30, "motor-side encoder",
               GS_INTEGER(plant.drive.encoder.counts_per_rev))
        .when(dc, "dc_motor"),
    F::number("drive", "current_loop_bandwidth_rad_s", "rad/s", Range::positive(),
              "firmware current-loop bandwidth, ≤ ln(4/3)/T_drive", GS_NUMBER(current_loop_bandwidth_rad_s))
        .when(dc, "dc_motor"),
    F::integer("controller", "control_divisor", "", 1, 1000, "control law every N base ticks",
               GS_INTEGER(controller.runtime.control_divisor)),
    F::integer("controller", "drive_divisor", "", 1, 1000, "current loops every N base ticks; divides control_divisor",
               GS_INTEGER(controller.runtime.drive_divisor)),
    F::number("controller", "r", "V/rad", Range::any(), "u per rad of β (14.27); refused unless r < H d/A (14.30)",
              GS_NUMBER(controller.loops.r))
        .req()
        .when(back_emf, "back_emf"),
    F::number("controller", "d_c", "V s/rad", Range::closed(0.0, 1e6), "electronic rate feedback, adds to the back-EMF d",
              GS_NUMBER(controller.loops.d_c))
        .when(back_emf, "back_emf"),
    F::number("controller", "voltage_limit_V", "V", Range::closed(0.1, 1e4), "motor voltage command saturation",
              GS_NUMBER(controller.loops.voltage_limit_V))
        .when(back_emf, "back_emf"),
    F::number("controller", "k1", "N m/rad", Range::any(), "M1 per rad of β (14.19); (14.25) checked",
              GS_NUMBER(controller.loops.k1))
        .req()
        .when(torque_law, "torque"),
    F::number("controller", "k2", "N m/rad", Range::any(), "M2 per rad of α (14.19); (14.25) checked",
              GS_NUMBER(controller.loops.k2))
        .req()
        .when(torque_law, "torque"),
    F::number("controller", "d1", "N m s/rad", Range::non_negative(), "commanded rate damping, axis 1",
              GS_NUMBER(controller.loops.d1))
        .when(torque_law, "torque"),
    F::number("controller", "d2", "N m s/rad", Range::non_negative(), "commanded rate damping, axis 2",
              GS_NUMBER(controller.loops.d2))
        .when(torque_law, "torque"),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "motor torque command saturation, both axes",
              GS_NUMBER(torque_limit_Nm))
        .when(torque_law, "torque"),
    F::number("report", "nutation_window_s", "s", Range::positive(),
              "window for the nutation measurement, from the inner-axis step (else the first disturbance step; "
              "a step at t = 0 is a load, not a step) to the next step at most",
              GS_NUMBER(measure_window_s)),
    F::number("report", "drift_period_s", "s", Range::non_negative(),
              "periodic-drift monitor: the period of the forcing (a whole number of ticks and of base roll "
              "periods); 0: off",
              GS_NUMBER(drift_period_s)),
    F::number("report", "drift_from_s", "s", Range::non_negative(),
              "start of the monitor's reference period, after the transients; + 2 periods ≤ duration_s; only "
              "with drift_period_s > 0",
              GS_NUMBER(drift_from_s)),
};

std::string triangle(const S& s) {
  return 2.0 * s.gyro.AR >= s.gyro.CR ? "" : "rotor inertia triangle violated: need 2 A^R >= C^R (Magnus (1.10))";
}

constexpr schema::Rule<S> kRules[] = {
    {"base", "roll_amplitude_rad", "[base] roll_amplitude_rad > 0 only with [motion] kind = \"harmonic_roll\"",
     [](const S& s) -> std::string {
       return s.plant.base.harmonic.amplitude > 0.0 && s.plant.base.kind != motion::BaseMotionKind::kHarmonicRoll
                  ? "a harmonic roll and [motion] kind = \"prescribed\" or \"recorded\" both move the base: give "
                    "the roll in [motion] (prescribed) or set roll_amplitude_rad = 0"
                  : "";
     }},
    {"gyro", "fidelity", "`precession` needs `structure = \"rigid\"` (P0 has no platform-gyro shaft mode (14.31))",
     [](const S& s) -> std::string {
       return s.precession() && s.elastic()
                  ? "\"precession\" (P0) drops the gimbal inertia, so it has no platform-gyro shaft mode (14.31): use "
                    "structure = \"rigid\", or fidelity = \"full\""
                  : "";
     }},
    {"gyro", "rpm", "rpm > 0: a power stabilizer needs a spinning rotor",
     [](const S& s) -> std::string {
       return s.rpm == 0.0 ? "zero spin: without H there is no gyroscopic coupling, and the loops (14.19) are then a "
                             "circulatory coupling of two inertias that no damping stabilises (the H (k1 + "
                             "k2) term of (14.23) vanishes, D3 = -(A d2 + B d1)^2 k1 k2 < 0); a power "
                             "stabilizer needs a spinning rotor"
                           : "";
     }},
    {"gyro", "AA",
     "P = AA + CJ > 0: the outer axis keeps inertia at gimbal lock (I(β) = A cos²β + P sin²β), where (10.4) "
     "would otherwise be singular",
     [](const S& s) -> std::string {
       return s.gyro.AA + s.gyro.CJ > 0.0
                  ? ""
                  : "P = AA + CJ = 0: the outer-axis inertia I(beta) = A cos^2 beta + P sin^2 beta vanishes at gimbal "
                    "lock (beta = 90 deg) and the gimbal equations (10.4) become singular there; give the "
                    "outer gimbal or the inner gimbal's C^J some inertia (docs/models/gimbal-gyro.md: keep P "
                    "> 0)";
     }},
    {"gyro", "AR", "2 A^R ≥ C^R (the rotor's inertia triangle, Magnus (1.10))", triangle},
    {"sensors", "rate_bandwidth_hz", "the rate gyro's bandwidth lies below the Nyquist frequency of the base tick",
     [](const S& s) -> std::string {
       return s.rate_bandwidth_hz > 0.0 && !(s.rate_bandwidth_hz < 0.5 / s.loop.tick_s())
                  ? "must lie below the Nyquist frequency of the base tick, " + std::to_string(0.5 / s.loop.tick_s()) +
                        " Hz"
                  : "";
     }},
    {"drive", "breakaway_Nm", "dc_motor: breakaway_Nm ≥ coulomb_Nm",
     [](const S& s) -> std::string {
       return s.dc_drive() && s.plant.drive.friction.breakaway < s.plant.drive.friction.coulomb
                  ? "must be >= coulomb_Nm"
                  : "";
     }},
    {"drive", "kind", "dc_motor: the drive's parameters are consistent (sim/drives/gimbal_drive.hpp)",
     [](const S& s) -> std::string {
       if (!s.dc_drive()) return "";
       const char* why = drives::GimbalDrive::check(s.plant.drive);
       return why != nullptr ? why : "";
     }},
    {"drive", "kind", "`dc_motor` is not for `motor = \"back_emf\"` (that motor is itself the axis-1 drive)",
     [](const S& s) -> std::string {
       return s.dc_drive() && s.back_emf()
                  ? "[gyro] motor = \"back_emf\" is itself the axis-1 drive (voltage law (14.27)); use [drive] kind = "
                    "\"torque\""
                  : "";
     }},
    {"report", "drift_period_s", "drift_period_s is a whole number of ticks and of base roll periods",
     [](const S& s) -> std::string {
       if (!(s.drift_period_s > 0.0)) return "";
       const double n = s.drift_period_s / s.loop.tick_s();
       if (std::abs(n - std::round(n)) > 1e-9 * n) {
         return "must be a whole number of ticks (the phase must repeat exactly)";
       }
       if (s.plant.base.harmonic.amplitude > 0.0) {
         const double periods = s.drift_period_s * s.plant.base.harmonic.frequency / (2.0 * std::numbers::pi);
         if (std::abs(periods - std::round(periods)) > 1e-9 || std::round(periods) < 1.0) {
           return "must be a whole number of base roll periods 2 pi/roll_frequency_rad_s = " +
                  std::to_string(2.0 * std::numbers::pi / s.plant.base.harmonic.frequency) + " s";
         }
       }
       return "";
     }},
    {"report", "drift_from_s", "drift_from_s + 2 drift_period_s ≤ duration_s, and drift_from_s only with a period",
     [](const S& s) -> std::string {
       if (s.drift_period_s > 0.0) {
         return s.drift_from_s + 2.0 * s.drift_period_s <= s.loop.duration_s
                    ? ""
                    : "drift_from_s + 2 drift_period_s must not exceed [scene] duration_s";
       }
       return s.drift_from_s != 0.0 ? "only with drift_period_s > 0" : "";
     }},
};

// What follows from the keys: H, the rate gyro's filter, the controller's view of the plant, and the plant as
// integrated (reflected inertias in, bearing damping of driven axes into the drives).
void derive(S& s) {
  s.plant.H = s.gyro.CR * s.rpm * 2.0 * std::numbers::pi / 60.0;
  auto& rg = s.plant.rate_gyro;
  rg.sample_period = s.loop.tick_s();
  if (s.rate_bandwidth_hz > 0.0) {
    rg.bandwidth.order =
        s.rate_filter_order == 1 ? sensors::LowpassParams::Order::kFirst : sensors::LowpassParams::Order::kSecond;
    rg.bandwidth.bandwidth_hz = s.rate_bandwidth_hz;
    rg.bandwidth.damping = s.rate_damping;
  }
  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.runtime.monitor.ranges.rotor_speed_rad_s = firmware::rotor_speed_range_for(s.rpm * 2.0 * std::numbers::pi / 60.0);
  auto& l = c.loops;
  l.H = s.plant.H;
  const double viscous = s.dc_drive() ? s.plant.drive.friction.viscous : 0.0;
  l.bearing_d1 = s.gyro.d1 + viscous;
  l.bearing_d2 = s.gyro.d2 + viscous;
  if (s.back_emf()) {
    l.output = firmware::PowerStabilizerOutput::kBackEmfVoltage;
    l.s = s.plant.motor.s;
    l.d_emf = s.plant.motor.d;
  } else {
    l.torque_limit_Nm[0] = l.torque_limit_Nm[1] = s.torque_limit_Nm;
  }
  s.plant.gyro = s.gyro;
  s.plant.platform = s.platform;
}

void derive_drives(S& s) {
  if (!s.dc_drive()) return;
  const drives::GimbalDrive probe(s.plant.drive);
  const double refl = probe.reflected_inertia();
  if (s.elastic()) {
    s.plant.platform.AP += refl;
  } else {
    s.plant.gyro.AA += refl;
    s.plant.gyro.d1 = 0.0;
  }
  s.plant.gyro.BJ += refl;
  s.plant.gyro.d2 = 0.0;
  auto& dc = s.controller.drive;
  dc.enabled = true;
  for (auto& a : dc.axis) {
    const double N = s.plant.drive.gear.ratio;
    a.torque_constant_Nm_per_A = N * s.plant.drive.gear.efficiency * s.plant.drive.motor.k_t;
    a.back_emf_V_s_per_rad = N * s.plant.drive.motor.k_e;
    a.resistance_ohm = s.plant.drive.motor.R;
    a.inductance_H = s.plant.drive.motor.L;
    a.bandwidth_rad_s = s.current_loop_bandwidth_rad_s;
    a.current_limit_A = s.plant.drive.motor.current_limit;
    a.voltage_limit_V = s.plant.drive.motor.voltage_limit;
  }
}

}  // namespace

bool read_power_stabilizer_scene(SceneReader& r, PowerStabilizerScene& s) {
  schema::read(r, kOptions, s);
  // The elastic variant has no exact gyroscopic flow (power_stabilizer.hpp): RK4 only; nor has P0.
  if (s.precession() || s.elastic()) {
    s.loop = read_loop_config(r, "rk4", {"rk4"});
  } else {
    s.loop = read_loop_config(r, "gyro-exponential", {"gyro-exponential", "rk4"});
  }
  schema::read(r, kFields, s);
  read_base_motion(r, s.plant.base, s.loop.duration_s);
  derive(s);
  schema::check(r, kRules, s);
  if (r.ok()) derive_drives(s);
  r.finish();
  if (!r.ok()) return false;
  // [output] signals: refused here (by `gyrostab check` too) with the variant's valid names.
  const std::string bad = Recorder::check_signals(power_stabilizer_columns(s), s.loop.signals);
  if (!bad.empty()) r.fail("output", "signals", bad);
  return check_power_stabilizer_plant(r, s) && r.ok();
}

SceneDoc power_stabilizer_doc() {
  SceneDoc d{{schema::document(kOptions), schema::document(kFields)}, schema::document(kRules)};
  d.tables[1].title = "";
  d.tables.push_back(base_motion_doc());
  for (const std::string& rule : power_stabilizer_plant_rules()) d.rules.push_back(rule);
  return d;
}

}  // namespace gyrostab::tools
