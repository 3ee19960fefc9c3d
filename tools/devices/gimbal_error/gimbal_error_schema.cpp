// The keys of a gimbal-error scene: one field table over GimbalErrorScene (tools/scene/schema.hpp), the
// source of the reader, its messages and docs/scenes.md.
#include <cmath>
#include <numbers>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/base_motion/base_motion_schema.hpp"
#include "tools/devices/gimbal_error/gimbal_error_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = GimbalErrorScene;
using F = schema::Fields<S>;
using Controller = GimbalErrorController<firmware::posix::MonotonicClock>;

#define GS_VEHICLE_ANGLE(sec, m, symbol, about)                                                              \
  F::number(sec, "angle_deg", "deg", Range::closed(-360.0, 360.0), symbol " at t = 0 (" about ")",           \
            GS_NUMBER(m.angle))                                                                              \
      .degrees(),                                                                                            \
      F::number(sec, "rate_deg_s", "deg/s", Range::closed(-360.0, 360.0), "constant rate of " symbol,        \
                GS_NUMBER(m.rate))                                                                           \
          .degrees(),                                                                                        \
      F::number(sec, "amplitude_deg", "deg", Range::closed(0.0, 180.0),                                      \
                "amplitude of a harmonic oscillation of " symbol, GS_NUMBER(m.amplitude))                    \
          .degrees(),                                                                                        \
      F::number(sec, "period_s", "s", Range::positive(), "its period", GS_NUMBER(m.period)),                 \
      F::number(sec, "phase_deg", "deg", Range::closed(-360.0, 360.0), "its phase: a = A sin(2π t/T + phase)", \
                GS_NUMBER(m.phase))                                                                          \
          .degrees()

constexpr std::string_view kMountings[] = {"321", "312", "213", "231", "123", "132"};

constexpr schema::Field<S> kFields[] = {
    F::choice("gyro", "mounting", kMountings,
              "gyro axes along the vehicle axes 1^F, 2^F, 3^F (\"321\": rotor axis 3 along the longitudinal "
              "axis, outer gimbal axis 1 along the normal axis: the heading gyro)",
              GS_CHOICE(plant.gyro.mounting))
        .req(),
    GS_VEHICLE_ANGLE("yaw", yaw, "yaw ψ", "about the inertial axis 3"),
    GS_VEHICLE_ANGLE("pitch", pitch, "pitch ϑ", "about the yawed axis 2'"),
    GS_VEHICLE_ANGLE("roll", roll, "roll (bank) φ", "about the vehicle axis 1^F"),
};
#undef GS_VEHICLE_ANGLE

motion::PrescribedAngle<2> angle_of(const VehicleAngleKeys& k) {
  motion::PrescribedAngle<2> a;
  a.offset = k.angle;
  a.rate = k.rate;
  if (k.amplitude > 0.0) {
    a.harmonics[0] = {k.amplitude, 2.0 * std::numbers::pi / k.period, k.phase};
    a.count = 1;
  }
  return a;
}

// A bound on |w_WF_F|: the sum of the Euler rates' bounds [rad/s]; with a [motion], the largest |ω_B| sampled
// on 4096 intervals and, for a record, at its rows.
double rate_bound(const S& s) {
  double w = 0.0;
  if (s.plant.gyro.from_motion) {
    const motion::SceneBaseMotion& m = s.plant.gyro.motion;
    for (int k = 0; k <= 4096; ++k) w = std::fmax(w, m(s.loop.duration_s * k / 4096).w_B.norm());
    if (m.kind == motion::BaseMotionKind::kRecorded && m.recorded.record() != nullptr) {
      for (const dynamics::Vec3& x : m.recorded.record()->w_B) w = std::fmax(w, x.norm());
    }
    return w;
  }
  for (const VehicleAngleKeys* k : {&s.yaw, &s.pitch, &s.roll}) {
    w += std::fabs(k->rate) + k->amplitude * 2.0 * std::numbers::pi / k->period;
  }
  return w;
}

constexpr schema::Rule<S> kRules[] = {
    {"loop", "plant_substeps",
     "the plant step resolves the vehicle's rotation (RK4 on the attitude, the rate bound Σ|a'| as the "
     "frequency); the message gives the plant_substeps needed",
     [](const S& s) -> std::string {
       const double w = rate_bound(s);
       if (!(w > 0.0)) return "";
       const double h = s.loop.tick_s() / s.loop.substeps;
       const dynamics::StepCheck c =
           dynamics::check_step(dynamics::Method::kRk4, {"vehicle rotation", {0.0, w}}, h);
       return c.ok ? "" : c.message;
     }},
    {"motion", "heave_amplitude_m",
     "no translational vibration ([motion] heave/sway): the free gyro's rotor axis does not see it",
     [](const S& s) -> std::string {
       return s.plant.gyro.motion.vibration.count > 0
                  ? "a heave or sway does not move the gimbals of a free gyro; remove heave_amplitude_m / "
                    "sway_amplitude_m"
                  : "";
     }},
    {"loop", "tick_us", "the controller's start-up check (firmware/app/free_instrument_controller.hpp)",
     [](const S& s) -> std::string { return controller_refusal<Controller>(s); }},
};

// [motion] kind = "harmonic_roll" (the default): the [yaw], [pitch], [roll] generator moves the vehicle, and
// `motion` holds the same motion (one harmonic per angle) for `gyrostab motion-record`.
void derive(S& s) {
  s.plant.gyro.vehicle.yaw = angle_of(s.yaw);
  s.plant.gyro.vehicle.pitch = angle_of(s.pitch);
  s.plant.gyro.vehicle.roll = angle_of(s.roll);
  motion::SceneBaseMotion& m = s.plant.gyro.motion;
  s.plant.gyro.from_motion = m.kind != motion::BaseMotionKind::kHarmonicRoll;
  if (!s.plant.gyro.from_motion) {
    m.kind = motion::BaseMotionKind::kPrescribed;
    const auto one = [](const motion::PrescribedAngle<2>& a) {
      motion::PrescribedAngle<1> b;
      b.offset = a.offset;
      b.rate = a.rate;
      b.harmonics[0] = a.harmonics[0];
      b.count = a.count;
      return b;
    };
    m.prescribed.yaw = one(s.plant.gyro.vehicle.yaw);
    m.prescribed.pitch = one(s.plant.gyro.vehicle.pitch);
    m.prescribed.roll = one(s.plant.gyro.vehicle.roll);
  }
  s.controller.runtime.tick_period_ns = s.loop.tick_ns;
}

}  // namespace

std::unique_ptr<DeviceScene> read_gimbal_error(SceneReader& r) {
  auto s = std::make_unique<GimbalErrorScene>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  schema::read(r, kFields, *s);
  read_base_motion(r, s->plant.gyro.motion, s->loop.duration_s);
  derive(*s);
  schema::check(r, kRules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return make_gimbal_error_scene(std::move(s));
}

SceneDoc gimbal_error_doc() {
  return {{schema::document(kFields), base_motion_doc()}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
