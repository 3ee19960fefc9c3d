// The templates behind check_power_stabilizer_plant (power_stabilizer_checks.hpp), instantiated per
// variant group in power_stabilizer_check_{rigid,elastic,precession}.cpp so that no file compiles for long.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "sim/drives/gimbal_drive.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_checks.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_sampled.hpp"
#include "tools/loop/controller_report.hpp"

namespace gyrostab::tools::power_stabilizer_checks {

using Base = motion::SceneBaseMotion;
using Controller = firmware::BasicPowerStabilizerController<firmware::posix::MonotonicClock>;

// The loop (14.23) / (14.29) linearised at inner-gimbal angle beta: the gyroscopic coupling H cos β and the
// outer-axis inertia I(β) (gimbal_gyro.hpp) replace H and A.
template <class Plant>
firmware::PowerStabilizerConfig loops_at(const Plant& plant, firmware::PowerStabilizerConfig l, double beta) {
  const models::GimbalGyroParams& p = plant.gyro().params();
  l.A = l.A - p.A() + p.outer_axis_inertia(beta);
  l.H = l.H * std::cos(beta);
  return l;
}

// The stability verdict of the loop as it runs: sampled at the law's period with the hold and the latency
// (power_stabilizer_sampled.hpp), at the same operating points. The firmware's start-up check is the
// continuous Hurwitz test; where the two differ the message says so: a loop the continuous test accepts but
// the sampled loop cannot hold is refused, and a refusal the sampled loop would not share is noted.
template <class Plant>
void check_sampled(SceneReader& r, PowerStabilizerScene& s, const Plant& plant, const double (&points)[2]) {
  const auto& l = s.controller.loops;
  const analysis::SampledTiming timing = power_stabilizer_timing(s);
  const char* key = s.back_emf() ? "r" : "k1";
  for (int i = 0; i < 2; ++i) {
    if (i == 1 && std::abs(points[1] - points[0]) < 1e-9) continue;
    if (!(std::abs(points[i]) < 0.5 * std::numbers::pi)) continue;  // gimbal lock: refused above
    const firmware::PowerStabilizerConfig at = loops_at(plant, l, points[i]);
    const firmware::GainCheck g = firmware::check_power_stabilizer_gains(at);
    if (g.verdict == firmware::GainCheckVerdict::kInvalidPlant || g.verdict == firmware::GainCheckVerdict::kInvalidGain ||
        g.verdict == firmware::GainCheckVerdict::kInvalidLimit)
      continue;  // refused for its parameters, not its stability
    const PowerStabilizerSampled sampled = power_stabilizer_sampled(at, timing);
    char where[120];
    std::snprintf(where, sizeof where, " (the loop at beta = %.4g deg, law every %.4g ms, latency %d tick(s))",
                  points[i] * 180.0 / std::numbers::pi, timing.period_s * 1e3, s.loop.latency_ticks);
    if (g.accepted && !sampled.roots.stable()) {
      r.fail("controller", key,
             "the sampled loop is unstable: " + analysis::sampled_instability(sampled.roots, timing, true) + where +
                 "; lower the gains or the tick, or reduce the latency");
    } else if (!g.accepted && sampled.roots.stable()) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "the sampled loop would be stable (|z| = %.6g) but the firmware's start-up check "
                    "is the continuous test and refuses these gains", sampled.roots.max_abs_z);
      r.fail("controller", key, std::string("unstable in continuous time; ") + buf + where);
    }
  }
}

// The gimbal-lock approach: the controller checks its gains at β = 0, but near β = ±90° the coupling H cos β
// that makes the loop work fades. The loop is checked at the operating points of the inner gimbal (the
// initial angle, the steady deflection (14.21)) with the same Hurwitz test; refused where it fails.
template <class Plant>
void check_operating_points(SceneReader& r, PowerStabilizerScene& s, const Plant& plant) {
  const auto& l = s.controller.loops;
  const double beta0 = s.plant.beta0;
  s.op_loops = loops_at(plant, l, beta0);
  double points[2] = {beta0, 0.0};
  const char* what[2] = {"the initial angle [initial] beta0_deg", "the steady deflection M1/k1 (14.21)"};
  const double M1 = s.plant.disturbance.M1;
  if (l.output == firmware::PowerStabilizerOutput::kTorque && l.k1 > 0.0) points[1] = M1 / l.k1;
  if (l.output == firmware::PowerStabilizerOutput::kBackEmfVoltage && l.r > 0.0) points[1] = M1 / (l.r * l.s);
  const plants::PowerDisturbance& d = s.plant.disturbance;
  const bool loaded_before = M1 != 0.0 && d.t1 < nutation_window(d, s.measure_window_s).step_s;
  s.measure_beta_rad = loaded_before && std::abs(points[1]) < 0.5 * std::numbers::pi ? points[1] : beta0;
  s.measure_loops = loops_at(plant, l, s.measure_beta_rad);
  for (int i = 0; i < 2; ++i) {
    const double beta = points[i];
    if (beta == 0.0 || (i == 1 && std::abs(beta - points[0]) < 1e-9)) continue;  // held at β0: said once
    if (!(std::abs(beta) < 0.5 * std::numbers::pi)) {
      r.fail(i == 0 ? "initial" : "disturbance", i == 0 ? "beta0_deg" : "M1_Nm",
             "the inner gimbal would reach gimbal lock (|beta| >= 90 deg) at " + std::string(what[i]));
      continue;
    }
    const firmware::GainCheck g = firmware::check_power_stabilizer_gains(loops_at(plant, l, beta));
    if (!g.accepted) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "gimbal-lock approach: at beta = %.4g deg (%s) the gyroscopic coupling falls to H cos "
                    "beta = %.4g N m s (from %.4g) and the stabilization loop is unstable there: ",
                    beta * 180.0 / std::numbers::pi, what[i], l.H * std::cos(beta), l.H);
      r.fail(i == 0 ? "initial" : "controller", i == 0 ? "beta0_deg" : (s.back_emf() ? "r" : "k1"),
             std::string(buf) + g.reason + " (gain margin there " + std::to_string(g.gain_scale_max) + ")");
    }
  }
  check_sampled(r, s, plant, points);
}

template <class Motor, class Structure, class Fidelity = models::FullGimbal>
bool check_plant(SceneReader& r, PowerStabilizerScene& s) {
  using Plant = models::PowerStabilizer<Base, Motor, Structure, Fidelity>;
  Motor motor{};
  Structure structure{};
  if constexpr (Plant::kVoltageDriven) motor = s.plant.motor;
  if constexpr (Plant::kElastic) structure = s.plant.platform;
  const Plant plant(s.plant.gyro, motor, structure, s.plant.base);
  if (const char* why = plant.invalid_reason()) {
    r.fail("gyro", "CR", why);
    return false;
  }
  auto& l = s.controller.loops;
  l.A = plant.outer_axis_inertia();
  l.B = plant.gyro().params().B();
  if (const std::string why = controller_refusal<Controller>(s); !why.empty()) {
    r.fail("controller", s.back_emf() ? "r" : "k1", why);
  }
  check_operating_points(r, s, plant);
  typename Plant::State x0;
  const auto& p = s.plant;
  if constexpr (Plant::kPrecession) {
    x0 = Plant::make_state(p.alpha0, p.beta0, p.H);
  } else if constexpr (Plant::kElastic) {
    x0 = Plant::make_state(p.alpha0, p.beta0, 0, 0, p.H, p.alpha0, 0);
  } else {
    x0 = Plant::make_state(p.alpha0, p.beta0, 0, 0, p.H);
  }
  const dynamics::Mode mode = dynamics::fastest_mode(plant, 0.0, x0);
  const auto method = s.loop.integrator == "rk4" ? dynamics::Method::kRk4 : dynamics::Method::kGyroExponential;
  const double h = s.loop.tick_s() / s.loop.substeps;
  const dynamics::StepCheck step = dynamics::check_step(method, mode, h);
  if (!step.ok) r.fail("loop", "plant_substeps", step.message);
  if (s.dc_drive()) {
    const drives::GimbalDrive d(s.plant.drive);
    const double J1 = Plant::kElastic ? s.plant.platform.AP : l.A, J2 = l.B;
    const double h_max = std::min(d.max_stable_step(J1), d.max_stable_step(J2));
    if (!(h < h_max)) {
      r.fail("loop", "plant_substeps",
             "plant step " + std::to_string(h) + " s is beyond the explicit drive coupling's stable step 2J/(b + b_e) = " +
                 std::to_string(h_max) + " s (gimbal_drive.hpp): use more sub-steps");
    }
  }
  return r.ok();
}

// fidelity = "precession": where P0 holds (ε = ω_P/ω_N ≪ 1, no gimbal lock, no drive on a gimbal axis:
// docs/models/gimbal-gyro.md#precession-model-p0), the expected error, and the full model's loop for the
// comparison run (the sub-steps its own step validation needs: the step ratio ≈ 1/ε is P0's saving).
template <class Motor>
bool check_reduced(SceneReader& r, PowerStabilizerScene& s) {
  if (s.dc_drive()) {
    r.fail("drive", "kind",
           "fidelity = \"precession\" (P0) drops the gimbal inertia that a drive on a gimbal axis acts on "
           "(the drive's stick and its stable step need it): use [drive] kind = \"torque\", or fidelity = "
           "\"full\"");
    return false;
  }
  if (!check_plant<Motor, models::RigidStructure, models::PrecessionOnly>(r, s)) return false;
  using Full = models::PowerStabilizer<Base, Motor, models::RigidStructure, models::FullGimbal>;
  Motor motor{};
  if constexpr (Full::kVoltageDriven) motor = s.plant.motor;
  const Full full(s.plant.gyro, motor, {}, s.plant.base);
  const auto& l = s.controller.loops;
  const auto& dist = s.plant.disturbance;
  const bool torque = l.output == firmware::PowerStabilizerOutput::kTorque;
  // Worst operating point for P0: the larger |β| of the initial angle and the steady deflection.
  const double beta_ss = torque ? (l.k1 > 0 ? dist.M1 / l.k1 : 0.0) : dist.M1 / (l.r * l.s);
  const double beta_op = std::max(std::abs(s.plant.beta0), std::abs(beta_ss));
  const firmware::PowerStabilizerConfig lo = loops_at(full, l, beta_op);
  const double B = l.B, A = lo.A, He = lo.H;
  const double omega_N = He / std::sqrt(A * B);
  // The slow roots of (14.23) → precession theory (14.24): λ = −k1/H, −k2/H; of (14.29): −r s/H.
  const double omega_P = torque ? std::max(std::abs(l.k1), std::abs(l.k2)) / He : l.r * l.s / He;
  const double eps = omega_P / omega_N;
  constexpr double kEpsMax = 0.1;
  if (!(eps < kEpsMax)) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "the precession model P0 does not hold here: eps = omega_P/omega_N = %.3g (omega_P = %.4g "
                  "rad/s, omega_N = %.4g rad/s at beta = %.4g deg%s) is not << 1 (refused at eps >= %.2g; "
                  "P0's error is O(eps), docs/models/gimbal-gyro.md)%s",
                  eps, omega_P, omega_N, beta_op * 180.0 / std::numbers::pi,
                  beta_op > 1.0 ? ", near gimbal lock where P0 is singular: H cos beta -> 0" : "", kEpsMax,
                  beta_op > 1.0 ? "; use fidelity = \"full\"" : "; use fidelity = \"full\" or a faster rotor");
    r.fail("gyro", "fidelity", buf);
    return false;
  }
  // A torque step M on an astatic gyro: the torqued axis offsets by ≤ 2 M I_other/H², the other axis errs by
  // ≤ M/(H ω_N); the O(ε) error of the slow (precession) response, ε · M/k = M/(H ω_N) per step, adds to both.
  // A base turning with angular acceleration Ω̇ acts like a torque I_i |Ω̇_i| on axis i (Φ ν² for a roll
  // Φ sin νt).
  const dynamics::Vec3 base_accel = s.plant.base.peak_angular_accel_B(s.loop.duration_s);
  const double M1 = std::abs(dist.M1) + A * base_accel.x(), M2 = std::abs(dist.M2) + B * base_accel.y();
  const double cross = (M1 + M2) / (He * omega_N);
  const double a_bound = 2.0 * M1 * B / (He * He) + cross;
  const double b_bound = 2.0 * M2 * A / (He * He) + cross;
  s.reduced_expected = {{"model", "precession (engineering) theory P0, (10.19)-(10.22)"},
                        {"full_model", "gimbal gyro (10.4), nutation resolved"},
                        {"epsilon", eps},
                        {"omega_P_rad_s", omega_P},
                        {"omega_N_rad_s", omega_N},
                        {"nutation_over_precession", 1.0 / eps},
                        {"operating_point_beta_rad", beta_op},
                        {"torque_step_alpha_offset_bound_rad", 2.0 * M1 * B / (He * He)},
                        {"torque_step_beta_offset_bound_rad", 2.0 * M2 * A / (He * He)},
                        {"precession_error_bound_rad", cross},
                        {"alpha_rad_bound", a_bound},
                        {"beta_rad_bound", b_bound},
                        {"bounds_from", "docs/models/gimbal-gyro.md#precession-model-p0: |alpha| <= 2MB/H^2, "
                                        "|beta - Mt/H| <= M/(H omega_N); relative error O(eps) of the "
                                        "precession response"}};
  // The full model's loop: its default integrator, with the sub-steps its step validation asks for.
  s.full_loop = s.loop;
  s.full_loop.integrator = "gyro-exponential";
  const dynamics::Mode mode =
      dynamics::fastest_mode(full, 0.0, Full::make_state(s.plant.alpha0, s.plant.beta0, 0, 0, s.plant.H));
  const dynamics::StepCheck step = dynamics::check_step(dynamics::Method::kGyroExponential, mode, s.loop.tick_s());
  s.full_loop.substeps = std::max(1, step.substeps_needed);
  if (s.full_loop.substeps > 100000) {
    r.fail("gyro", "fidelity", "the full model for the comparison would need more than 100000 sub-steps: " + step.message);
  }
  s.reduced_expected["full_model_plant_substeps"] = s.full_loop.substeps;
  s.reduced_expected["reduced_model_plant_substeps"] = s.loop.substeps;
  return r.ok();
}

}  // namespace gyrostab::tools::power_stabilizer_checks
