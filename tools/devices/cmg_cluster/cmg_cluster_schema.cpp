// The keys of a CMG cluster scene: one field table over CmgClusterScene (tools/scene/schema.hpp), the source
// of the reader, its messages and docs/scenes.md.
#include <cmath>
#include <sstream>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/cmg_cluster/cmg_cluster_scene.hpp"
#include "tools/loop/controller_report.hpp"
#include "tools/scene/read_rk4_scene.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using S = CmgClusterScene;
using F = schema::Fields<S>;
using Controller = firmware::BasicCmgClusterController<firmware::posix::MonotonicClock>;

constexpr std::string_view kSteering[] = {"pseudo_inverse", "singularity_robust", "generalized_singularity_robust"};

bool robust(const S& s) { return firmware::is_robust(s.controller.steering.law); }
bool generalized(const S& s) {
  return s.controller.steering.law == firmware::SteeringLaw::kGeneralizedSingularityRobust;
}

constexpr schema::Field<S> kFields[] = {
    F::number("spacecraft", "Jxx", "kg m²", Range::positive(), "inertia tensor (spacecraft + CMG units), body axes",
              GS_NUMBER(Jxx)),
    F::number("spacecraft", "Jyy", "kg m²", Range::positive(), "inertia tensor", GS_NUMBER(Jyy)),
    F::number("spacecraft", "Jzz", "kg m²", Range::positive(), "inertia tensor", GS_NUMBER(Jzz)),
    F::number("spacecraft", "Jxy", "kg m²", Range::any(), "product of inertia (tensor component)", GS_NUMBER(Jxy)),
    F::number("spacecraft", "Jxz", "kg m²", Range::any(), "product of inertia (tensor component)", GS_NUMBER(Jxz)),
    F::number("spacecraft", "Jyz", "kg m²", Range::any(), "product of inertia (tensor component)", GS_NUMBER(Jyz)),
    F::number("cmg", "h", "N m s", Range::positive(), "rotor spin momentum of each CMG (held constant)",
              GS_NUMBER(plant.model.h))
        .req(),
    F::number("cmg", "skew_deg", "deg", Range::open_closed(0.0, 90.0),
              "the four-unit pyramid's skew angle β (gimbal axis to pyramid axis z); 54.74° = arctan √2",
              GS_NUMBER(skew_rad))
        .degrees(),
    F::strings("cmg", "gimbal_axes",
               "instead of the pyramid: 1-4 gimbal axes g_i, each \"x y z\" (unit within 1e-3, then normalized)",
               GS_STRINGS(gimbal_axes)),
    F::strings("cmg", "spin_axes",
               "with gimbal_axes: the spin axes s0_i at δ_i = 0, \"x y z\", ⟂ g_i within 1e-3 (then made exact)",
               GS_STRINGS(spin_axes)),
    F::number("cmg", "gimbal_inertia", "kg m²", Range::positive(), "gimbal + rotor inertia I_g about the gimbal axis",
              GS_NUMBER(plant.model.gimbal_inertia)),
    F::number("cmg", "servo_bandwidth", "rad/s", Range::positive(),
              "gimbal rate servo: PI with both poles at −ω_s (k_p = 2 I_g ω_s, k_i = I_g ω_s²)",
              GS_NUMBER(plant.model.servo_bandwidth)),
    F::number("cmg", "torque_limit_Nm", "N m", Range::positive(), "gimbal motor torque limit",
              GS_NUMBER(plant.model.torque_limit)),
    F::number("cmg", "gimbal_friction", "N m s/rad", Range::non_negative(), "viscous friction in each gimbal bearing",
              GS_NUMBER(plant.model.gimbal_friction)),
    F::number("cmg", "delta1_deg", "deg", Range::closed(-360.0, 360.0), "initial gimbal angle δ_1",
              GS_NUMBER(plant.initial_delta[0]))
        .degrees(),
    F::number("cmg", "delta2_deg", "deg", Range::closed(-360.0, 360.0), "initial gimbal angle δ_2",
              GS_NUMBER(plant.initial_delta[1]))
        .degrees(),
    F::number("cmg", "delta3_deg", "deg", Range::closed(-360.0, 360.0), "initial gimbal angle δ_3",
              GS_NUMBER(plant.initial_delta[2]))
        .degrees(),
    F::number("cmg", "delta4_deg", "deg", Range::closed(-360.0, 360.0), "initial gimbal angle δ_4",
              GS_NUMBER(plant.initial_delta[3]))
        .degrees(),
    F::number("sensors", "rate_noise_density", "rad/s/√Hz", Range::closed(0.0, 1e-2), "body-rate white noise",
              GS_NUMBER(plant.sensors.rate_noise_density)),
    F::integer("sensors", "gimbal_encoder_counts_per_rev", "counts/rev", 16, 1 << 30,
               "absolute gimbal encoders (read in [−π, π))", GS_INTEGER(plant.sensors.gimbal_encoder_counts_per_rev)),
    F::choice("controller", "steering", kSteering,
              "`pseudo_inverse`: ν = −Aᵀ(AAᵀ)⁻¹u; `singularity_robust`: ν = −Aᵀ(AAᵀ + λI)⁻¹u, "
              "λ = λ0 exp(−μ det(AAᵀ)/h⁶); `generalized_singularity_robust`: ν = −Aᵀ(AAᵀ + λE)⁻¹u, E = I + the "
              "off-diagonal dither ε_i = ε0 sin(ωt + φ_i), φ = (0, π/2, π), t = tick · tick period",
              GS_CHOICE(controller.steering.law)),
    F::number("controller", "lambda0", "-", Range::positive(), "λ0 of the singularity-robust inverse",
              GS_NUMBER(controller.steering.lambda0))
        .when(robust, "singularity_robust, generalized_singularity_robust"),
    F::number("controller", "mu", "-", Range::non_negative(), "μ of the singularity-robust inverse",
              GS_NUMBER(controller.steering.mu))
        .when(robust, "singularity_robust, generalized_singularity_robust"),
    F::number("controller", "dither_amplitude", "-", Range{0.0, 0.5, false, true},
              "ε0 of the generalized inverse's dither; below 1/2 E stays positive definite (eigenvalues ≥ 1 − 2ε0)",
              GS_NUMBER(controller.steering.dither_amplitude))
        .when(generalized, "generalized_singularity_robust"),
    F::number("controller", "dither_frequency", "rad/s", Range::non_negative(),
              "ω of the generalized inverse's dither (ω T_c ≤ 0.5)", GS_NUMBER(controller.steering.dither_frequency))
        .when(generalized, "generalized_singularity_robust"),
    F::number("controller", "max_gimbal_rate", "rad/s", Range::closed(1e-3, 10.0),
              "gimbal rate command limit (all rates scaled by one factor)", GS_NUMBER(controller.steering.max_rate)),
    F::number("controller", "slew_deg", "deg", Range::closed(0.0, 180.0),
              "the rest-to-rest slew: the commanded attitude is this rotation about slew_axis from the start",
              GS_NUMBER(slew_rad))
        .degrees(),
    F::number("controller", "slew_axis_x", "-", Range::closed(-1.0, 1.0), "slew axis, body (normalized)",
              GS_NUMBER(slew_axis_x)),
    F::number("controller", "slew_axis_y", "-", Range::closed(-1.0, 1.0), "slew axis", GS_NUMBER(slew_axis_y)),
    F::number("controller", "slew_axis_z", "-", Range::closed(-1.0, 1.0), "slew axis", GS_NUMBER(slew_axis_z)),
    F::number("controller", "attitude_bandwidth", "rad/s", Range::positive(),
              "attitude loop ω_a: K_p,k = 2 ω_a² J_kk, K_d,k = 2 ζ ω_a J_kk", GS_NUMBER(attitude_bandwidth)),
    F::number("controller", "attitude_damping", "-", Range::closed(0.1, 10.0), "attitude loop ζ",
              GS_NUMBER(attitude_damping)),
    F::flag("controller", "feedforward", "add the gyroscopic feed-forward ω × H_total",
            GS_FLAG(controller.attitude.gyroscopic_feedforward)),
    F::number("report", "settle_band_deg", "deg", Range::open_closed(0.0, 90.0),
              "the slew is settled once the attitude error stays below this", GS_NUMBER(settle_band_rad))
        .degrees(),
    F::number("report", "near_singular_measure", "-", Range::positive(),
              "det(AAᵀ)/h⁶ below this counts as near-singular time", GS_NUMBER(near_singular_measure)),
};

// "x y z" → a vector; false when it does not parse.
bool parse_axis(const std::string& text, dynamics::Vec3& v) {
  std::istringstream in(text);
  double a = 0, b = 0, c = 0;
  if (!(in >> a >> b >> c)) return false;
  std::string rest;
  if (in >> rest) return false;
  v = {a, b, c};
  return v.allFinite();
}

// The geometry from the keys (the pyramid unless gimbal_axes is given); the problem, if any, in s.
void derive_geometry(S& s) {
  models::CmgGeometry& g = s.plant.model.geometry;
  if (s.gimbal_axes.empty() && s.spin_axes.empty()) {
    g = models::pyramid_geometry(s.skew_rad);
    return;
  }
  const std::size_t n = s.gimbal_axes.size();
  if (n < 1 || n > models::kMaxCmgs || s.spin_axes.size() != n) {
    s.geometry_problem = "gimbal_axes and spin_axes must both list 1 to 4 axes, as many of each";
    return;
  }
  g = {};
  g.count = static_cast<int>(n);
  for (std::size_t i = 0; i < n; ++i) {
    dynamics::Vec3 a, b;
    if (!parse_axis(s.gimbal_axes[i], a) || !parse_axis(s.spin_axes[i], b)) {
      s.geometry_problem = "axis " + std::to_string(i + 1) + " is not three numbers \"x y z\"";
      return;
    }
    if (std::fabs(a.norm() - 1.0) > 1e-3 || std::fabs(b.norm() - 1.0) > 1e-3 || std::fabs(a.dot(b)) > 1e-3) {
      s.geometry_problem = "axis pair " + std::to_string(i + 1) + " is not unit and orthogonal within 1e-3";
      return;
    }
    a.normalize();
    b = (b - b.dot(a) * a).normalized();
    g.gimbal_axis[i] = a;
    g.spin_axis0[i] = b;
  }
}

// The plant step against the fastest mode of the spacecraft with its CMGs at the initial state: with the
// rate servos holding the gimbals (the servo poles at −ω_s and the spacecraft-rotor nutation), and with the
// gimbals free (a saturated servo: the gimbals' own nutation h/sqrt(I_g J)). "" or the problem.
std::string plant_step_problem(const S& s) {
  const double h_sub = s.loop.tick_s() / s.loop.substeps;
  for (const models::GimbalDriveMode mode : {models::GimbalDriveMode::kRateServo, models::GimbalDriveMode::kTorque}) {
    models::CmgClusterParams p = s.plant.model;
    p.drive = mode;
    const models::CmgClusterSpacecraft m(p);
    const auto x0 = models::CmgClusterSpacecraft::make_state(s.plant.initial_rate, dynamics::Quat::Identity(),
                                                             s.plant.initial_delta);
    const dynamics::StepCheck step =
        dynamics::check_step(dynamics::Method::kRk4, dynamics::fastest_mode(m, 0.0, x0), h_sub);
    if (!step.ok) {
      return std::string(mode == models::GimbalDriveMode::kRateServo ? "gimbals servoed: " : "gimbals free: ") +
             step.message;
    }
  }
  return "";
}

// The generalized inverse's dither sampled too coarsely: "" or the problem.
std::string dither_problem(const S& s) {
  const double step = s.controller.steering.dither_frequency * s.controller.runtime.control_period_s();
  if (!generalized(s) || step <= firmware::kMaxDitherStep) return "";
  return "dither_frequency " + std::to_string(s.controller.steering.dither_frequency) +
         " rad/s times the control period is " + std::to_string(step) + ", above 0.5";
}

bool possible(const S& s) { return s.geometry_problem.empty() && s.plant.model.invalid_reason() == nullptr; }

constexpr schema::Rule<S> kRules[] = {
    {"cmg", "gimbal_axes", "explicit axes parse, pair up and are orthonormal pairs",
     [](const S& s) -> std::string { return s.geometry_problem; }},
    {"spacecraft", "Jxx",
     "the spacecraft is physically possible: J positive definite, its principal moments satisfy the triangle "
     "inequality, J − Σ I_g g gᵀ positive definite",
     [](const S& s) -> std::string {
       if (!s.geometry_problem.empty()) return "";
       const char* why = s.plant.model.invalid_reason();
       return why != nullptr ? why : "";
     }},
    {"controller", "slew_axis_x", "the slew axis is not zero",
     [](const S& s) -> std::string {
       return std::hypot(s.slew_axis_x, s.slew_axis_y, s.slew_axis_z) > 1e-9 ? "" : "the slew axis is zero";
     }},
    {"controller", "attitude_bandwidth",
     "the controller's start-up check (firmware/app/cmg_cluster_controller.hpp): the sampled attitude loop holds "
     "(K_d T/J ≤ 0.5, sqrt(K_p/2J) T ≤ 0.5) and its fastest rate is at most servo_bandwidth/4",
     [](const S& s) -> std::string {
       return possible(s) && dither_problem(s).empty() ? controller_refusal<Controller>(s) : "";
     }},
    {"controller", "dither_frequency", "the sampled dither is resolved: dither_frequency · control period ≤ 0.5",
     dither_problem},
    {"loop", "plant_substeps",
     "the plant step resolves the fastest mode of the spacecraft with its CMGs (servo poles, spacecraft-rotor "
     "nutation, free-gimbal nutation h/sqrt(I_g J)); the message gives the plant_substeps needed",
     [](const S& s) -> std::string { return possible(s) ? plant_step_problem(s) : ""; }},
};

// What the controller takes from the plant, and the commanded attitude.
void derive(S& s) {
  auto& m = s.plant.model;
  m.J << s.Jxx, s.Jxy, s.Jxz, s.Jxy, s.Jyy, s.Jyz, s.Jxz, s.Jyz, s.Jzz;
  derive_geometry(s);
  auto& c = s.controller;
  c.runtime.tick_period_ns = s.loop.tick_ns;
  c.array = cmg_array_of(m.geometry, m.h);
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) c.attitude.J[r][k] = m.J(r, k);
    c.attitude.kp[r] = 2.0 * s.attitude_bandwidth * s.attitude_bandwidth * m.J(r, r);
    c.attitude.kd[r] = 2.0 * s.attitude_damping * s.attitude_bandwidth * m.J(r, r);
  }
  c.attitude.servo_bandwidth = m.servo_bandwidth;
  const double n = std::hypot(s.slew_axis_x, s.slew_axis_y, s.slew_axis_z);
  if (n > 1e-9) {
    const double sh = std::sin(0.5 * s.slew_rad) / n;
    c.reference = {std::cos(0.5 * s.slew_rad), sh * s.slew_axis_x, sh * s.slew_axis_y, sh * s.slew_axis_z};
  }
}

}  // namespace

std::unique_ptr<DeviceScene> read_cmg_cluster(SceneReader& r) {
  auto s = schema::read_rk4_scene(r, kFields, derive, kRules);
  return s ? make_cmg_cluster_scene(std::move(s)) : nullptr;
}

SceneDoc cmg_cluster_doc() { return {{schema::document(kFields)}, schema::document(kRules)}; }

}  // namespace gyrostab::tools
