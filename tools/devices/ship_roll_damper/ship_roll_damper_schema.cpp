// The keys of a ship roll damper scene: one field table over ShipRollDamperScene (tools/scene/schema.hpp),
// the source of the reader, its messages and docs/scenes.md.
#include <algorithm>
#include <cstdio>
#include <numbers>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = ShipRollDamperScene;
using F = schema::Fields<S>;
using motion::SeaKind;
using Mode = firmware::ShipRollDamperMode;

constexpr std::string_view kSeaKinds[] = {"regular", "pierson_moskowitz", "jonswap"};
constexpr std::string_view kLaws[] = {"passive", "active"};

bool regular(const S& s) { return s.plant.sea.kind == SeaKind::kRegular; }
bool irregular(const S& s) { return s.plant.sea.kind != SeaKind::kRegular; }
bool jonswap(const S& s) { return s.plant.sea.kind == SeaKind::kJonswap; }
bool passive(const S& s) { return s.controller.mode == Mode::kPassiveBrake; }
bool active(const S& s) { return s.controller.mode == Mode::kActive; }

void set_torque_limit(S& s, double v) {
  s.controller.brake.torque_limit_Nm = v;
  s.controller.active.torque_limit_Nm = v;
}

constexpr schema::Field<S> kFields[] = {
    F::number("ship", "A", "kg m²", Range::positive(), "roll inertia of ship + installation", GS_NUMBER(plant.ship.A))
        .req(),
    F::number("ship", "c", "N m/rad", Range::positive(), "roll stiffness m g GM", GS_NUMBER(plant.ship.c)).req(),
    F::number("ship", "d1", "N m s/rad", Range::non_negative(), "roll damping", GS_NUMBER(plant.ship.d1)),
    F::number("ship", "w", "", Range::non_negative(), "wall-sided coefficient BM/(2 GM); 0: constant GM",
              GS_NUMBER(plant.ship.w)),
    F::number("ship", "roll0_deg", "deg", Range::closed(-30.0, 30.0),
              "roll angle at t = 0, both ships (a roll-decay trial: with a calm sea, [sea] kind = \"regular\", E0 = 0)",
              GS_NUMBER(plant.initial_roll))
        .degrees(),
    F::number("gyro", "B", "kg m²", Range::positive(), "case + rotor inertia about the precession axis 2",
              GS_NUMBER(plant.ship.B))
        .req(),
    F::number("gyro", "Q", "kg m²", Range::any(), "A^R + A^J − C^J of (10.4); A − Q > 0", GS_NUMBER(plant.ship.Q)),
    F::number("gyro", "q", "N m/rad", Range::non_negative(),
              "pendulous stiffness of the case G s (centre of mass below axis 2)", GS_NUMBER(plant.ship.q))
        .req(),
    F::number("gyro", "d2", "N m s/rad", Range::non_negative(),
              "viscous friction of the precession bearing (the brake is the controller's)", GS_NUMBER(plant.ship.d2)),
    F::number("gyro", "H", "N m s", Range::non_negative(),
              "rotor spin momentum; 0: a gyro without spin (the active law refuses it, the passive brake runs)",
              GS_NUMBER(plant.ship.H))
        .req(),
    F::integer("gyro", "units", "", 1, 2,
               "1: one unit; 2: a counter-rotating pair with linked cases (mirror precession; B, Q, q, d2, H per unit)",
               GS_INTEGER(plant.ship.units)),
    F::number("gyro", "beta_stop_deg", "deg", Range::open_closed(0.0, 89.0), "hard end stops of the precession angle",
              GS_NUMBER(plant.ship.beta_stop))
        .degrees(),
    F::number("gyro", "stop_frequency", "rad/s", Range::positive(), "end-stop stiffness sqrt(k_s/B)",
              GS_NUMBER(plant.ship.stop_frequency)),
    F::number("gyro", "stop_damping_ratio", "", Range::non_negative(), "end-stop damping ζ_s",
              GS_NUMBER(plant.ship.stop_damping_ratio)),
    F::number("gyro", "brake_full_Nms", "N m s/rad", Range::positive(),
              "plant brake at precession_brake = 1 (the safe state locks the case)", GS_NUMBER(plant.brake_full_Nms)),
    F::choice("sea", "kind", kSeaKinds, "wave model; the keys of the other kinds are refused",
              GS_CHOICE(plant.sea.kind)),
    F::number("sea", "E0", "N m", Range::non_negative(),
              "wave moment amplitude (14.9) in beam seas at rest; × sin(heading) on the course",
              GS_NUMBER(plant.sea.wave.E0))
        .req()
        .when(regular, "regular"),
    F::number("sea", "omega", "rad/s", Range::positive(),
              "wave frequency; the ship meets it at ω − (ω²/g) U cos(heading)", GS_NUMBER(plant.sea.wave.omega))
        .req()
        .when(regular, "regular"),
    F::number("sea", "Hs", "m", Range::positive(), "significant wave height", GS_NUMBER(plant.sea.spectrum.Hs))
        .req()
        .when(irregular, "irregular"),
    F::number("sea", "Tp", "s", Range::positive(), "peak period", GS_NUMBER(plant.sea.spectrum.Tp))
        .req()
        .when(irregular, "irregular"),
    F::number("sea", "gamma", "", Range::closed(1.0, 10.0), "peak enhancement γ", GS_NUMBER(plant.sea.spectrum.gamma))
        .when(jonswap, "jonswap"),
    F::integer("sea", "components", "", 1, 256, "harmonic components (seeded phases)",
               GS_INTEGER(plant.sea.irregular.components))
        .when(irregular, "irregular"),
    F::number("sea", "kappa", "", Range::open_closed(0.0, 2.0), "effective wave-slope coefficient κ",
              GS_NUMBER(plant.sea.kappa))
        .when(irregular, "irregular"),
    F::number("course", "speed", "m/s", Range::closed(0.0, 30.0), "ship speed U through the water",
              GS_NUMBER(plant.sea.course.speed)),
    F::number("course", "heading_deg", "deg", Range::closed(-360.0, 360.0),
              "direction of travel of the waves from the bow, counterclockwise from above: 90 beam seas (from "
              "starboard), 180 head seas, 0 following seas",
              GS_NUMBER(plant.sea.course.heading))
        .degrees(),
    F::number("course", "turn_rate_deg_s", "deg/s", Range::closed(-10.0, 10.0),
              "steady yaw rate Ω3 about the upward vertical (> 0 bow to port, the rotor's sense for H > 0)",
              GS_NUMBER(plant.ship.turn_rate))
        .degrees(),
    F::number("sensors", "roll_angle_noise_rad", "rad", Range::non_negative(),
              "roll angle (AHRS) white noise, standard deviation per sample",
              GS_NUMBER(plant.sensors.roll_angle_noise_rad)),
    F::number("sensors", "roll_rate_noise_density", "rad/s/√Hz", Range::non_negative(), "roll rate gyro white noise",
              GS_NUMBER(plant.sensors.roll_rate_noise_density)),
    F::number("sensors", "roll_rate_bias", "rad/s", Range::closed(-0.1, 0.1), "roll rate gyro bias",
              GS_NUMBER(plant.sensors.roll_rate_bias)),
    F::number("sensors", "precession_rate_noise_density", "rad/s/√Hz", Range::non_negative(),
              "precession rate white noise", GS_NUMBER(plant.sensors.precession_rate_noise_density)),
    F::integer("sensors", "encoder_counts_per_rev", "counts/rev", 16, 1 << 30, "precession encoder resolution",
               GS_INTEGER(plant.sensors.encoder_counts_per_rev)),
    F::choice("controller", "law", kLaws,
              "control law: the passive brake M2 = −d2 β' (Hahnkamm), or active precession control",
              GS_CHOICE(controller.mode)),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "precession torque limit", set_torque_limit,
              [](const S& s) { return s.controller.active.torque_limit_Nm; }),
    F::number("controller", "brake_d2", "N m s/rad", Range::non_negative(),
              "brake coefficient; the minimax of (14.18) for the default ship is 4.53e4",
              GS_NUMBER(controller.brake.d2))
        .when(passive, "passive"),
    F::number("controller", "roll_rate_gain", "N m s/rad", Range::non_negative(), "M2 per rad/s of roll rate (× cos β)",
              GS_NUMBER(controller.active.roll_rate_gain))
        .when(active, "active")
        .defaults_to([](const S& s) { return s.plant.ship.total_H(); }, "H × units"),
    F::number("controller", "precession_damping", "N m s/rad", Range::positive(), "M2 per rad/s of precession rate",
              GS_NUMBER(controller.active.precession_damping))
        .when(active, "active"),
    F::number("controller", "centring_stiffness", "N m/rad", Range::non_negative(), "M2 per rad of precession angle",
              GS_NUMBER(controller.active.centring_stiffness))
        .when(active, "active"),
    F::number("controller", "soft_limit_deg", "deg", Range::open_closed(0.0, 89.0),
              "soft limit of the precession angle", GS_NUMBER(controller.active.beta_soft))
        .degrees()
        .when(active, "active"),
    F::number("controller", "soft_stiffness", "N m/rad", Range::non_negative(), "M2 per rad beyond the soft limit",
              GS_NUMBER(controller.active.soft_stiffness))
        .when(active, "active"),
    F::number("controller", "brake_deceleration", "rad/s²", Range::positive(),
              "deceleration of the end-stop braking envelope", GS_NUMBER(controller.active.brake_deceleration))
        .when(active, "active"),
    F::number("report", "settle_s", "s", Range::non_negative(), "statistics (rms, peaks) start after this time",
              GS_NUMBER(settle_s))
        .defaults_to([](const S& s) { return std::min(60.0, 0.2 * s.loop.duration_s); }, "min(60, 0.2 duration_s)")
        .within([](const S& s) { return Range::closed(0.0, s.loop.duration_s); }, "0 … duration_s"),
};

using Controller = firmware::BasicShipRollDamperController<firmware::posix::MonotonicClock>;

constexpr schema::Rule<S> kRules[] = {
    {"ship", "A", "the ship and gyro are physically possible: A − Q > 0 (I(β) = A − Q sin²β), stops in (0, 90°)",
     [](const S& s) -> std::string {
       const char* why = s.plant.ship.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"sea", "Hs", "irregular: the spectrum is usable (Hs, Tp give a peak frequency inside the sea's band)",
     [](const S& s) -> std::string {
       if (regular(s)) return "";
       motion::WaveSpectrumParams sp = s.plant.sea.spectrum;
       sp.kind = s.plant.sea.spectrum_kind();
       const char* why = motion::WaveSpectrum::check(sp);
       return why != nullptr ? why : "";
     }},
    {"course", "turn_rate_deg_s",
     "a turn against the rotor's sense stays above the bound Ω3 > −(q + k_c)/H, where the case's stiffness "
     "q + k_c + HΩ3 (k_c the active law's centring stiffness) turns negative and the case capsizes against "
     "its stop (docs/models/ship-roll-damper.md#turning); a twin pair has no bound",
     [](const S& s) -> std::string {
       const double bound = s.plant.ship.turn_rate_bound(active(s) ? s.controller.active.centring_stiffness : 0.0);
       if (s.plant.ship.turn_rate == 0.0 || s.plant.ship.turn_rate > bound) return "";
       char m[256];
       std::snprintf(m, sizeof m,
                     "turn rate %.4g deg/s is at or beyond the bound %.4g deg/s = -(q + k_c)/H, where the "
                     "case's stiffness q + k_c + H*Omega3 is negative: the case capsizes (turn slower, turn the "
                     "other way, raise the centring stiffness, or use units = 2)",
                     s.plant.ship.turn_rate * 180.0 / std::numbers::pi, bound * 180.0 / std::numbers::pi);
       return m;
     }},
    {"controller", "law",
     "the controller's start-up check (firmware/app/ship_roll_damper_controller.hpp): the sampled loop's "
     "limits for the brake or the active law at the control period",
     controller_refusal<Controller, S>},
};

// What the controller takes from the plant, and the rate of its loop.
void derive(S& s) {
  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.brake.B = s.plant.ship.total_B();
  c.active.B = s.plant.ship.total_B();
  c.active.H = s.plant.ship.total_H();
  c.active.beta_stop = s.plant.ship.beta_stop;
}

}  // namespace

bool read_ship_roll_damper_scene(SceneReader& r, ShipRollDamperScene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  schema::read(r, kFields, s);
  derive(s);
  schema::check(r, kRules, s);
  r.finish();
  return r.ok();
}

std::unique_ptr<DeviceScene> read_ship_roll_damper(SceneReader& r) {
  auto s = std::make_unique<ShipRollDamperScene>();
  if (!read_ship_roll_damper_scene(r, *s)) return nullptr;
  return make_ship_roll_damper_scene(std::move(s));
}

SceneDoc ship_roll_damper_doc() {
  return {{schema::document(kFields)}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
