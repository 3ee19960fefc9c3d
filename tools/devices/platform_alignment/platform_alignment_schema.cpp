// The keys of a platform alignment scene: one field table over PlatformAlignmentScene (tools/scene/schema.hpp),
// the source of the reader, its messages and docs/scenes.md. The latitude limit: the azimuth signal (16.52)
// is ∝ cosφ, so the azimuth loop's time constant and the heading error a gyro drift leaves both grow as
// 1/cosφ; the scene is refused beyond the latitude at which the alignment would outlast `[alignment]
// max_time_s` (tools/devices/platform_alignment/platform_alignment_closed_forms.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "tools/devices/platform_alignment/platform_alignment_scene.hpp"
#include "tools/devices/vehicle_instruments/gyro_frame_checks.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = PlatformAlignmentScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicPlatformAlignmentController<firmware::posix::MonotonicClock>;

constexpr double kDegPerHour = schema::kDegree / 3600.0;  // [rad/s] per °/h

constexpr schema::Field<S> kFields[] = {
    F::number("site", "latitude_deg", "deg", Range::closed(-90.0, 90.0), "latitude φ of the site (the plumb line's)",
              GS_NUMBER(plant.platform.latitude))
        .degrees(),
    F::number("site", "earth_rate_rad_s", "rad/s", Range::open_closed(0.0, 1e-2), "Earth rate ω^E",
              GS_NUMBER(plant.platform.earth_rate)),
    F::number("site", "gravity_m_s2", "m/s²", Range::closed(1.0, 30.0), "plumb-line gravity g",
              GS_NUMBER(plant.gravity)),
    F::number("platform", "tilt_east0_deg", "deg", Range::closed(-10.0, 10.0),
              "initial tilt θ_E about the east axis", GS_NUMBER(plant.initial.tilt_east))
        .degrees(),
    F::number("platform", "tilt_north0_deg", "deg", Range::closed(-10.0, 10.0),
              "initial tilt θ_N about the north axis", GS_NUMBER(plant.initial.tilt_north))
        .degrees(),
    F::number("platform", "heading_error0_deg", "deg", Range::closed(-179.0, 179.0),
              "initial heading error ψ (the platform's north axis, clockwise from north)",
              GS_NUMBER(plant.initial.heading_error))
        .degrees(),
    F::number("platform", "H", "N m s", Range::positive(), "torquer scale of the east and north gyros (ω = −M/H)",
              GS_NUMBER(plant.H)),
    F::number("platform", "azimuth_torquer_scale_rad_s_V", "rad/s/V", Range::positive(),
              "torquer scale K_Z of the zenith gyro (ω = K_Z u)", GS_NUMBER(plant.azimuth_torquer_scale)),
    F::number("gyros", "drift_east_deg_h", "deg/h", Range::closed(-10.0, 10.0), "drift ε_E of the east gyro",
              GS_NUMBER(plant.platform.drift[0]))
        .scaled(kDegPerHour),
    F::number("gyros", "drift_north_deg_h", "deg/h", Range::closed(-10.0, 10.0), "drift ε_N of the north gyro",
              GS_NUMBER(plant.platform.drift[1]))
        .scaled(kDegPerHour),
    F::number("gyros", "drift_zenith_deg_h", "deg/h", Range::closed(-10.0, 10.0), "drift ε_U of the zenith gyro",
              GS_NUMBER(plant.platform.drift[2]))
        .scaled(kDegPerHour),
    F::number("accelerometers", "bias_east_m_s2", "m/s²", Range::closed(-0.1, 0.1), "bias b_E of the east accelerometer",
              GS_NUMBER(plant.platform.accel_bias[0])),
    F::number("accelerometers", "bias_north_m_s2", "m/s²", Range::closed(-0.1, 0.1),
              "bias b_N of the north accelerometer", GS_NUMBER(plant.platform.accel_bias[1])),
    F::number("accelerometers", "bias_up_m_s2", "m/s²", Range::closed(-0.1, 0.1), "bias of the up accelerometer",
              GS_NUMBER(plant.platform.accel_bias[2])),
    F::number("accelerometers", "noise_density", "m/s²/√Hz", Range::closed(0.0, 0.1), "white noise of each",
              GS_NUMBER(plant.accel_noise_density)),
    F::number("base", "heading_deg", "deg", Range::closed(-360.0, 360.0),
              "the base's heading (its axis 1), clockwise from north", GS_NUMBER(plant.base.heading))
        .degrees(),
    F::number("base", "roll_amplitude_deg", "deg", Range::closed(0.0, 2.0),
              "rocking about the base's axis 1 (gusts on the parked aircraft)", GS_NUMBER(base.roll_amplitude))
        .degrees(),
    F::number("base", "roll_period_s", "s", Range::closed(0.1, 1e3), "its period", GS_NUMBER(base.roll_period_s)),
    F::number("base", "pitch_amplitude_deg", "deg", Range::closed(0.0, 2.0), "rocking about the base's axis 2",
              GS_NUMBER(base.pitch_amplitude))
        .degrees(),
    F::number("base", "pitch_period_s", "s", Range::closed(0.1, 1e3), "its period", GS_NUMBER(base.pitch_period_s)),
    F::number("base", "lever_z_m", "m", Range::closed(0.0, 20.0),
              "height of the platform above the rocking axes (its acceleration h φ'')", GS_NUMBER(base.lever_z_m)),
    F::number("base", "sway_amplitude_m", "m", Range::closed(0.0, 0.1),
              "sideways (base axis 2) displacement amplitude", GS_NUMBER(base.sway_amplitude_m)),
    F::number("base", "sway_frequency_hz", "Hz", Range::closed(1e-3, 10.0), "its frequency",
              GS_NUMBER(base.sway_frequency_hz)),
    F::number("base", "heave_amplitude_m", "m", Range::closed(0.0, 0.1), "vertical displacement amplitude",
              GS_NUMBER(base.heave_amplitude_m)),
    F::number("base", "heave_frequency_hz", "Hz", Range::closed(1e-3, 10.0), "its frequency",
              GS_NUMBER(base.heave_frequency_hz)),
    F::number("controller", "latitude_deg", "deg", Range::closed(-85.0, 85.0),
              "latitude the loops compensate the Earth rate for", GS_NUMBER(controller.law.latitude))
        .degrees()
        .defaults_to([](const S& s) { return s.plant.platform.latitude; }, "[site] latitude_deg"),
    F::number("controller", "levelling_bandwidth_rad_s", "rad/s", Range::positive(),
              "levelling loops' natural frequency ω_L", GS_NUMBER(controller.law.levelling_bandwidth)),
    F::number("controller", "levelling_damping", "", Range::open_closed(0.0, 2.0), "their damping ratio ζ",
              GS_NUMBER(controller.law.levelling_damping)),
    F::number("controller", "azimuth_time_constant_equator_s", "s", Range::positive(),
              "azimuth loop time constant τ_A0 at the equator (k_a = 1/(ω^E τ_A0); ≈ τ_A0/cosφ elsewhere)",
              GS_NUMBER(controller.law.azimuth_time_constant_equator)),
    F::number("controller", "levelling_min_s", "s", Range::non_negative(), "no azimuth phase before",
              GS_NUMBER(controller.law.levelling_min_s)),
    F::number("controller", "settle_tilt_deg", "deg", Range::closed(0.0, 1.0),
              "then switch at the end of a settle_hold_s window whose mean apparent tilts are below this (0: at "
              "levelling_min_s)",
              GS_NUMBER(controller.law.settle_tilt_rad))
        .degrees(),
    F::number("controller", "settle_hold_s", "s", Range::positive(), "the averaging window (consecutive from t = 0)",
              GS_NUMBER(controller.law.settle_hold_s)),
    F::number("controller", "torque_limit_Nm", "N m", Range::positive(), "torquer limit of the level gyros",
              GS_NUMBER(controller.law.torque_limit_Nm)),
    F::number("controller", "voltage_limit_V", "V", Range::positive(), "torquer voltage limit of the zenith gyro",
              GS_NUMBER(controller.law.voltage_limit_V)),
    F::number("alignment", "max_time_s", "s", Range::positive(), "the alignment must be done by then",
              GS_NUMBER(max_time_s)),
    F::number("alignment", "heading_tolerance_deg", "deg", Range::open_closed(0.0, 10.0),
              "aligned: the heading error ψ within ± this", GS_NUMBER(heading_tolerance))
        .degrees(),
    F::number("alignment", "tilt_tolerance_deg", "deg", Range::open_closed(0.0, 1.0),
              "… and the tilts θ_E, θ_N within ± this", GS_NUMBER(tilt_tolerance))
        .degrees(),
};

std::string deg(double rad) {
  return format_3g(rad / schema::kDegree);
}
std::string seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", t);
  return buf;
}

constexpr schema::Rule<S> kRules[] = {
    {"alignment", "max_time_s", "`[alignment] max_time_s` ≤ `[scene] duration_s`",
     [](const S& s) -> std::string {
       return s.max_time_s <= s.loop.duration_s ? "" : "must not exceed [scene] duration_s";
     }},
    {"controller", "levelling_bandwidth_rad_s",
     "the controller's start-up check (firmware/app/platform_alignment_controller.hpp): the continuous azimuth "
     "loop's Hurwitz condition and the sampled levelling and azimuth loops' roots inside the unit circle at the "
     "control period and latency",
     controller_refusal<Controller, S>},
    {"site", "latitude_deg",
     "|latitude| within the latitude limit: the alignment (azimuth phase from its predicted start, the loop's "
     "slow root ∝ cosφ, the drift's heading error ε_E/(ω^E cosφ) within the tolerance) is done by `[alignment] "
     "max_time_s`; the message gives the limit",
     [](const S& s) -> std::string {
       const double lat = s.plant.platform.latitude;
       if (std::fabs(lat) <= s.latitude_limit) return "";
       const double t = oracles::alignment_time(alignment_time_inputs(s), lat);
       const std::string why =
           std::isfinite(t) ? "aligns only after " + seconds(t) + " s"
                           : "never aligns (a residual error of the drifts and biases reaches its tolerance)";
       if (s.latitude_limit < 0.0)
         return "the azimuth loop " + why + " > max_time_s even at the equator: no latitude aligns in time";
       return "beyond the latitude limit " + deg(s.latitude_limit) + " deg of this loop for max_time_s = " +
              seconds(s.max_time_s) + " s (the azimuth signal (16.52) is ∝ cos(latitude)): the azimuth loop " +
              why;
     }},
};

// The levelling phase's predicted length: levelling_min_s, or the envelope e^{−ζω_L t}/sqrt(1 − ζ²) of the
// largest initial tilt down to the settle threshold, plus a window, rounded up to the window's end.
double predicted_switch(const S& s) {
  const auto& l = s.controller.law;
  if (l.settle_tilt_rad <= 0.0) return l.levelling_min_s;
  const double tilt0 = std::max(std::fabs(s.plant.initial.tilt_east), std::fabs(s.plant.initial.tilt_north));
  const double z = l.levelling_damping, w = l.levelling_bandwidth;
  const double rate = z < 1.0 ? z * w : w * (z - std::sqrt(z * z - 1.0));
  const double amp = z < 1.0 ? tilt0 / std::sqrt(1.0 - z * z) : tilt0;
  const double settle = amp > l.settle_tilt_rad ? std::log(amp / l.settle_tilt_rad) / rate : 0.0;
  const double w_s = l.settle_hold_s;
  return w_s * std::ceil(std::max(l.levelling_min_s, settle + w_s) / w_s - 1e-9);
}

void build_base(S& s) {
  auto& b = s.plant.base;
  const auto harmonic = [](motion::PrescribedAngle<1>& a, double amplitude, double period) {
    a.count = 0;
    if (amplitude > 0.0) {
      a.harmonics[0] = {amplitude, 2.0 * std::numbers::pi / period, 0.0};
      a.count = 1;
    }
  };
  harmonic(b.rocking.roll, s.base.roll_amplitude, s.base.roll_period_s);
  harmonic(b.rocking.pitch, s.base.pitch_amplitude, s.base.pitch_period_s);
  b.rocking.lever_arm_B = {0.0, 0.0, s.base.lever_z_m};
  int n = 0;
  if (s.base.sway_amplitude_m > 0.0)
    b.vibration.harmonics[n++] = {{0.0, s.base.sway_amplitude_m, 0.0}, 2.0 * std::numbers::pi * s.base.sway_frequency_hz, 0.0};
  if (s.base.heave_amplitude_m > 0.0)
    b.vibration.harmonics[n++] = {{0.0, 0.0, s.base.heave_amplitude_m}, 2.0 * std::numbers::pi * s.base.heave_frequency_hz, 0.0};
  b.vibration.count = n;
}

// The controller's period, latency, Earth rate and torquer scales from the plant and the loop; the latitude
// limit of the scene's loop.
void derive(S& s) {
  auto& l = s.controller.law;
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
  l.latency_periods = s.loop.latency_ticks;
  l.earth_rate = s.plant.platform.earth_rate;
  l.gravity_scale = plants::kAlignmentGravityScale;
  l.H = s.plant.H;
  l.azimuth_torquer_scale = s.plant.azimuth_torquer_scale;
  build_base(s);
  s.predicted_switch_s = predicted_switch(s);
}

}  // namespace

oracles::AlignmentTimeInputs alignment_time_inputs(const PlatformAlignmentScene& s) {
  oracles::AlignmentTimeInputs in;
  in.loop = s.controller.law;
  in.platform = s.plant.platform;
  in.gravity = s.plant.gravity;
  in.heading_error0 = s.plant.initial.heading_error;
  in.heading_tolerance = s.heading_tolerance;
  in.tilt_tolerance = s.tilt_tolerance;
  in.switch_time = s.predicted_switch_s;
  return in;
}

std::unique_ptr<DeviceScene> read_platform_alignment(SceneReader& r) {
  auto s = std::make_unique<PlatformAlignmentScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  s->max_time_s = s->loop.duration_s;
  schema::read(r, kFields, *s);
  derive(*s);
  if (r.ok()) {
    s->latitude_limit = oracles::latitude_limit(alignment_time_inputs(*s), s->max_time_s, s->plant.platform.latitude);
  }
  schema::check(r, kRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_platform_alignment_scene(std::move(s));
}

SceneDoc platform_alignment_doc() {
  SceneDocTable table = schema::document(kFields);
  for (SceneDocRow& row : table.rows) {
    if (row.key == "`[alignment] max_time_s`") row.fallback = "`[scene] duration_s`";
  }
  return {{table}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
