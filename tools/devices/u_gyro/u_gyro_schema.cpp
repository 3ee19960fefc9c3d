// The keys of a U-gyro scene: one field table over UGyroScene (tools/scene/schema.hpp), the source of the
// reader, its messages and docs/scenes.md.
#include <algorithm>
#include <cmath>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/u_gyro/u_gyro_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/read_rk4_scene.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = UGyroScene;
using F = schema::Fields<S>;
using Controller = UGyroController<firmware::posix::MonotonicClock>;

constexpr schema::Field<S> kFields[] = {
    F::number("rotor", "AR", "kg m²", Range::positive(), "rotor inertia about its principal axis x",
              GS_NUMBER(plant.gyro.AR))
        .req(),
    F::number("rotor", "BR", "kg m²", Range::positive(), "rotor inertia about its principal axis y",
              GS_NUMBER(plant.gyro.BR))
        .req(),
    F::number("rotor", "CR", "kg m²", Range::positive(), "rotor inertia about the spin axis",
              GS_NUMBER(plant.gyro.CR))
        .req(),
    F::number("rotor", "spin_rad_s", "rad/s", Range::open_closed(0.0, 1e4),
              "spin rate γ', held by the spin motor (H = CR γ')", GS_NUMBER(plant.gyro.spin))
        .req(),
    F::number("frame", "AJ", "kg m²", Range::non_negative(), "frame inertia about the input axis 1",
              GS_NUMBER(plant.gyro.AJ)),
    F::number("frame", "BJ", "kg m²", Range::non_negative(), "frame inertia about the output axis 2",
              GS_NUMBER(plant.gyro.BJ))
        .req(),
    F::number("frame", "CJ", "kg m²", Range::non_negative(), "frame inertia about the spin axis 3",
              GS_NUMBER(plant.gyro.CJ)),
    F::number("frame", "c2", "N m/rad", Range::positive(), "output-axis spring (sensitivity H/c2, (15.4))",
              GS_NUMBER(plant.gyro.c2))
        .req(),
    F::number("frame", "d2", "N m s/rad", Range::non_negative(), "output-axis damper",
              GS_NUMBER(plant.gyro.d2))
        .req(),
    F::number("table", "Omega", "rad/s", Range::closed(-10.0, 10.0),
              "rate of the case about the input axis 1 from t = 0", GS_NUMBER(plant.table_rate))
        .req(),
    F::number("report", "settle_s", "s", Range::non_negative(),
              "the output's mean and twice-spin harmonic are measured after this time", GS_NUMBER(settle_s))
        .within([](const S& s) { return Range::closed(0.0, s.loop.duration_s); }, "0 … duration_s"),
};

bool possible(const S& s) { return s.plant.gyro.invalid_reason() == nullptr; }

constexpr schema::Rule<S> kRules[] = {
    {"rotor", "AR", "the rotor and frame are physically possible (the rotor's inertias form a triangle)",
     [](const S& s) -> std::string {
       const char* why = s.plant.gyro.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"loop", "plant_substeps",
     "the plant step resolves the frame's mode on the spring (mean inertia) and the twice-spin forcing; the "
     "message gives the plant_substeps needed",
     [](const S& s) -> std::string {
       if (!possible(s)) return "";
       const models::UGyroParams& g = s.plant.gyro;
       const double B = g.mean_output_inertia() + 0.5 * std::fabs(g.AR - g.BR);  // the largest I2
       const double w0 = std::sqrt(g.c2 / B), zeta = g.d2 / (2.0 * std::sqrt(g.c2 * B));
       const std::complex<double> frame =
           zeta < 1.0 ? std::complex<double>(-zeta * w0, w0 * std::sqrt(1.0 - zeta * zeta))
                      : std::complex<double>(-w0 * (zeta + std::sqrt(zeta * zeta - 1.0)), 0.0);
       const double h = s.loop.tick_s() / s.loop.substeps;
       for (const dynamics::Mode& m : {dynamics::Mode{"frame", frame}, dynamics::Mode{"twice spin", {0.0, 2.0 * g.spin}}}) {
         const dynamics::StepCheck c = dynamics::check_step(dynamics::Method::kRk4, m, h);
         if (!c.ok) return c.message;
       }
       return "";
     }},
    {"loop", "tick_us", "the controller's start-up check (firmware/app/free_instrument_controller.hpp)",
     [](const S& s) -> std::string { return controller_refusal<Controller>(s); }},
};

void derive(S& s) { s.controller.runtime.tick_period_ns = s.loop.tick_ns; }

}  // namespace

std::unique_ptr<DeviceScene> read_u_gyro(SceneReader& r) {
  auto s = schema::read_rk4_scene(r, kFields, derive, kRules);
  return s ? make_u_gyro_scene(std::move(s)) : nullptr;
}

SceneDoc u_gyro_doc() {
  return {{schema::document(kFields)}, schema::document(kRules)};
}

}  // namespace gyrostab::tools
