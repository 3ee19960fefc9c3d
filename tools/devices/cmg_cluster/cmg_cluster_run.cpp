// What a CMG cluster run reports: the plant of sim/plants/cmg_cluster_plant.hpp with its meters — the attitude
// error against the commanded attitude (final, and the settling time into the band), the singularity measure
// det(A Aᵀ)/h⁶ (its minimum along the run, when, and the time spent near-singular), the steering law's rate
// limiting and singular ticks, the cluster's momentum against its envelope, the inertial angular momentum's
// drift (conserved: no external torque acts) — the CSV row (the signal table's columns by name,
// tools/devices/cmg_cluster/cmg_cluster_signals.toml), the half-step error estimate, and the scene's plant and
// controller for the run modes.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/cmg_cluster_outputs.hpp"
#include "sim/analysis/half_step_window.hpp"
#include "tools/devices/cmg_cluster/cmg_cluster_scene.hpp"
#include "sim/analysis/planar_mode_fit.hpp"
#include "tools/devices/cmg_cluster/cmg_cluster_sampled.hpp"
#include "tools/devices/device_scene_of.hpp"
#include "tools/loop/error_estimate_report.hpp"

namespace gyrostab::tools {
namespace {

using Plant = plants::CmgClusterPlant;
// Compute-time counters read CLOCK_MONOTONIC; the commands do not depend on it (determinism holds).
using Controller = firmware::BasicCmgClusterController<firmware::posix::MonotonicClock>;
constexpr double kDeg = 180.0 / std::numbers::pi;

dynamics::Quat reference_of(const CmgClusterScene& s) {
  const auto& r = s.controller.reference;
  return dynamics::Quat(r.w, r.x, r.y, r.z);
}

class CmgClusterRun {
 public:
  using SensorFrame = Plant::SensorFrame;
  using ActuatorFrame = Plant::ActuatorFrame;
  using Record = msg::cmg_cluster::Record;

  explicit CmgClusterRun(const CmgClusterScene& s)
      : s_(s),
        plant_(s.plant, s.loop.plant_timing()),
        reference_(reference_of(s)),
        L0_(plant_.momentum_world()),
        window_(s.loop.ticks() / 2, std::min<std::int64_t>(s.loop.ticks() / 4, static_cast<std::int64_t>(1.0 / s.loop.tick_s()))),
        axis_(principal_slew_axis(s)),
        slew_axis_(dynamics::Vec3(s.slew_axis_x, s.slew_axis_y, s.slew_axis_z).normalized()) {
    if (axis_ >= 0) approach_.reserve(static_cast<std::size_t>(std::min<std::int64_t>(s.loop.ticks(), 10'000'000)) + 1);
    error_ = attitude_error_rad();
    min_measure_ = plant_.singularity_measure();
  }

  void sense(std::int64_t tick, SensorFrame& f) {
    plant_.sense(tick, f);
    // The approach, tick by tick: q, ω and the body-rate errors the law read (the noise's
    // response is simulated from the start: what the noise did before the final approach is still in it); the
    // fit uses the ticks from the first whose error is below kLinearBelowRad.
    if (axis_ < 0 || approach_.size() >= approach_.capacity()) return;
    if (approach_start_ < 0 && error_ < kLinearBelowRad) {
      approach_start_ = static_cast<std::int64_t>(approach_.size());
      approach_from_s_ = static_cast<double>(tick) * s_.loop.tick_s();
    }
    const dynamics::Quat e = reference_.conjugate() * plant_.attitude();
    const dynamics::Vec3 w = plant_.body_rate();
    const double sign = e.w() < 0.0 ? -1.0 : 1.0;
    approach_.push_back({{sign * e.vec()[0], sign * e.vec()[1], sign * e.vec()[2], w[0], w[1], w[2]},
                         {f.body_rate_rad_s[0] - w[0], f.body_rate_rad_s[1] - w[1], f.body_rate_rad_s[2] - w[2]}});
  }
  void actuate(const ActuatorFrame& cmd) {
    last_ = cmd;
    plant_.actuate(cmd);
    if ((cmd.status & firmware::bit(firmware::LawStatusBit::kRateLoopSaturated)) != 0u) ++rate_limited_ticks_;
    if ((cmd.status & firmware::bit(firmware::LawStatusBit::kGimbalLockGuard)) != 0u) ++singular_ticks_;
  }
  void advance(std::int64_t tick) {
    window_.before_tick(tick, plant_.state(), plant_.held_inputs());
    plant_.advance(tick);
    window_.after_tick(tick, plant_.state());
    ticks_ = tick + 1;
    const double t = static_cast<double>(ticks_) * s_.loop.tick_s();
    error_ = attitude_error_rad();
    if (error_ >= s_.settle_band_rad) last_outside_s_ = t;
    const double m = plant_.singularity_measure();
    if (m < min_measure_) {
      min_measure_ = m;
      min_measure_s_ = t;
    }
    if (m < s_.near_singular_measure) near_singular_ticks_ += 1;
    peak_H_ = std::max(peak_H_, plant_.cmg_momentum_body().norm());
    // The cluster's momentum along the slew axis, in magnitude: from rest the spacecraft's J ω is −H_cmg, so
    // a slew about +e drives H_cmg along −e.
    peak_H_along_ = std::max(peak_H_along_, std::fabs(plant_.cmg_momentum_body().dot(slew_axis_)));
    peak_rate_ = std::max(peak_rate_, plant_.body_rate().norm());
    for (int i = 0; i < s_.plant.model.geometry.count; ++i) {
      peak_gimbal_rate_ = std::max(peak_gimbal_rate_, std::fabs(plant_.gimbal_rate(i)));
      peak_motor_torque_ = std::max(peak_motor_torque_, std::fabs(plant_.motor_torque(i)));
    }
    drift_ = std::max(drift_, (plant_.momentum_world() - L0_).norm());
  }
  bool finite() const { return plant_.finite(); }

  static constexpr int kGuardedStates = Plant::kGuardedStates;
  static const char* state_name(int i) { return Plant::state_name(i); }
  double state_value(int i) const { return plant_.state_value(i); }

  void record(Record& r) const {
    r.attitude_error_deg = error_ * kDeg;
    const dynamics::Vec3 w = plant_.body_rate(), H = plant_.cmg_momentum_body();
    r.omega_x_rad_s = w[0];
    r.omega_y_rad_s = w[1];
    r.omega_z_rad_s = w[2];
    r.H_cmg_x_Nms = H[0];
    r.H_cmg_y_Nms = H[1];
    r.H_cmg_z_Nms = H[2];
    r.delta_1_rad = plant_.delta(0);
    r.delta_2_rad = plant_.delta(1);
    r.delta_3_rad = plant_.delta(2);
    r.delta_4_rad = plant_.delta(3);
    r.singularity_measure = plant_.singularity_measure();
    r.status_bits = static_cast<double>(last_.status);
  }

  nlohmann::json figures() const {
    const auto& g = s_.plant.model.geometry;
    const double h = s_.plant.model.h;
    const double tick = s_.loop.tick_s();
    const double duration = static_cast<double>(ticks_) * tick;
    const bool settled = last_outside_s_ < duration;
    dynamics::Vec3 axis(s_.slew_axis_x, s_.slew_axis_y, s_.slew_axis_z);
    axis.normalize();
    constexpr const char* kLaw[] = {"pseudo_inverse", "singularity_robust", "generalized_singularity_robust"};
    nlohmann::json f = {{"steering", kLaw[static_cast<int>(s_.controller.steering.law)]},
            {"slew_deg", s_.slew_rad * kDeg},
            {"final_attitude_error_deg", error_ * kDeg},
            {"settle_band_deg", s_.settle_band_rad * kDeg},
            {"settling_time_s", settled ? nlohmann::json(last_outside_s_) : nlohmann::json(nullptr)},
            {"min_singularity_measure", min_measure_},
            {"min_singularity_measure_at_s", min_measure_s_},
            {"singularity_measure_at_zero_momentum", g.singularity_measure(std::array<double, 4>{}.data())},
            {"near_singular_time_s", static_cast<double>(near_singular_ticks_) * tick},
            {"near_singular_measure", s_.near_singular_measure},
            {"rate_limited_ticks", rate_limited_ticks_},
            {"singular_ticks", singular_ticks_},
            {"peak_cmg_momentum_Nms", peak_H_},
            {"envelope_along_slew_axis_Nms", h * g.envelope_extent(axis)},
            {"peak_cmg_momentum_along_slew_axis_Nms", peak_H_along_},
            {"envelope_along_slew_axis_closed_form_Nms", envelope_closed_form(axis)},
            {"envelope_reached_rel_error",
             envelope_closed_form(axis).is_number()
                 ? nlohmann::json(peak_H_along_ / envelope_closed_form(axis).get<double>() - 1.0)
                 : nlohmann::json(nullptr)},
            {"pyramid_internal_singularity_Nms",
             s_.gimbal_axes.empty() ? nlohmann::json(2.0 * h * std::cos(s_.skew_rad)) : nlohmann::json(nullptr)},
            {"envelope_x_Nms", h * g.envelope_extent(dynamics::Vec3::UnitX())},
            {"envelope_y_Nms", h * g.envelope_extent(dynamics::Vec3::UnitY())},
            {"envelope_z_Nms", h * g.envelope_extent(dynamics::Vec3::UnitZ())},
            {"peak_body_rate_rad_s", peak_rate_},
            {"peak_gimbal_rate_rad_s", peak_gimbal_rate_},
            {"peak_gimbal_motor_torque_Nm", peak_motor_torque_},
            {"momentum_drift_Nms", drift_},
            {"ticks", ticks_}};
    attitude_loop_figures(f);
    return f;
  }

  // The pyramid's envelope along a principal direction, docs/models/cmg-cluster.md#momentum-envelope: along
  // x or y 2h(1 + cos β) (two CMGs at sin β from the direction, two across it), along z 4h sin β; null for
  // another direction or a cluster given by its axes.
  nlohmann::json envelope_closed_form(const dynamics::Vec3& e) const {
    if (!s_.gimbal_axes.empty()) return nullptr;
    const double h = s_.plant.model.h, b = s_.skew_rad;
    const dynamics::Vec3 a = e.cwiseAbs();
    if (a.x() == 1.0 || a.y() == 1.0) return 2.0 * h * (1.0 + std::cos(b));
    if (a.z() == 1.0) return 4.0 * h * std::sin(b);
    return nullptr;
  }

  // report.json "error_estimate": up to 1 s from the middle of the run.
  nlohmann::json error_estimate() const {
    const auto apply = [](Plant::Dynamics& m, const Plant::HeldInputs& in) {
      for (int i = 0; i < models::kMaxCmgs; ++i) m.inputs.rate_command[i] = in.rate_command[i];
    };
    return error_estimate_json<Plant::Model::kStateSize>(
        window_.estimate<dynamics::Rk4>(plant_.dynamics(), apply, s_.loop.tick_ns, s_.loop.substeps, 4),
        {"omega_x_rad_s", "omega_y_rad_s", "omega_z_rad_s", "q_x", "q_y", "q_z", "q_w", "delta_1_rad", "delta_2_rad",
         "delta_3_rad", "delta_4_rad", "delta_rate_1_rad_s", "delta_rate_2_rad_s", "delta_rate_3_rad_s",
         "delta_rate_4_rad_s", "servo_integral_1_rad", "servo_integral_2_rad", "servo_integral_3_rad",
         "servo_integral_4_rad"},
        "momentum_drift_Nms in the figures: the inertial angular momentum (no external torque)");
  }

 private:
  // 0.1°: over the window the gimbals still turn (the steering's Jacobian, and the other pairs' output
  // directions the modal filter nulls, with them), by an amount ∝ the error where it opens. The fitted ω_n
  // against the sampled pair, from 2°, 1°, 0.5°, 0.25°, 0.125°, 0.1°: slew −2.1e-3, −8.4e-4, −3.1e-4, −1.2e-4,
  // −8.2e-5, −5.4e-5; singularity-robust (coupled) −1.4e-3, +1.5e-3, +1.9e-3, +1.4e-3, +8.0e-4, +7.1e-4.
  static constexpr double kLinearBelowRad = 0.0017453292519943296;
  // Below this share of the slew axis's motion the pair is measured through the modal filter in earnest
  // (cmg_cluster_sampled.hpp): 0.996 and 0.981 on the slew and pseudo-inverse scenes, 0.60 where the
  // singularity-robust scenes end.
  static constexpr double kSinglePairShare = 0.95;
  struct ApproachSample {
    double y[6];     // q (the error quaternion's vector part), ω [-, rad/s]
    double v[3];     // body-rate errors read [rad/s]
  };
  // The slew axis's index when it is a principal axis of the spacecraft (one body axis, J diagonal), else −1.
  static int principal_slew_axis(const CmgClusterScene& s) {
    const double a[3] = {s.slew_axis_x, s.slew_axis_y, s.slew_axis_z};
    const Eigen::Matrix3d& J = s.plant.model.J;
    if (J(0, 1) != 0.0 || J(0, 2) != 0.0 || J(1, 2) != 0.0 || s.controller.runtime.control_divisor != 1) return -1;
    int k = -1;
    for (int i = 0; i < 3; ++i) {
      if (a[i] == 0.0) continue;
      if (k >= 0) return -1;
      k = i;
    }
    return k;
  }
  // The attitude pair about the slew axis (cmg_cluster_sampled.hpp), predicted where the run ends, and
  // measured: the noise's response through the sampled loop taken off the recorded approach, the modal
  // filter's y = W (q, ω) (the other pairs' output directions nulled), the planar recurrence of y fitted to
  // means over 1/(50 ω_a) (planar_mode_fit.hpp).
  void attitude_loop_figures(nlohmann::json& f) const {
    if (axis_ < 0) {
      f["attitude_loop"] = "not computed: the slew axis is not a principal axis, or the law runs below the tick rate";
      return;
    }
    const double tick = s_.loop.tick_s(), t_end = static_cast<double>(ticks_) * tick;
    const CmgClusterSampled p = cmg_cluster_sampled(s_, plant_.state(), t_end, axis_);
    const analysis::PairShape design = analysis::pair_shape(p.design[0], p.design[1]);
    const analysis::PairShape sampled = analysis::pair_shape(p.sampled[0], p.sampled[1]);
    f["attitude_natural_frequency_rad_s_predicted"] = design.natural_frequency;
    f["attitude_damping_ratio_predicted"] = design.damping_ratio;
    f["attitude_natural_frequency_rad_s_predicted_sampled"] = sampled.natural_frequency;
    f["attitude_damping_ratio_predicted_sampled"] = sampled.damping_ratio;
    f["sampled_loop_max_abs_z"] = p.roots.max_abs_z;
    f["attitude_pair_share"] = p.share;
    if (p.share < kSinglePairShare) {
      f["attitude_loop"] = "the gimbal configuration couples the axes: another attitude pair carries part of the slew "
                           "axis's motion; the fit sees this pair through the modal filter (the other pairs' output "
                           "directions nulled)";
    }
    f["attitude_window_from_s"] = approach_start_ < 0 ? nlohmann::json(nullptr) : nlohmann::json(approach_from_s_);
    f["attitude_natural_frequency_rad_s"] = nullptr;
    f["attitude_damping_ratio"] = nullptr;
    const auto every = std::max<std::int64_t>(1, static_cast<std::int64_t>(1.0 / (50.0 * s_.attitude_bandwidth) / tick));
    analysis::PlanarModeFit fit(approach_from_s_, t_end + 1.0, tick * static_cast<double>(every));
    const int L = s_.loop.latency_ticks;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(CmgClusterSampled::kN);
    std::vector<Eigen::Vector4d> pipe(static_cast<std::size_t>(L) + 1, Eigen::Vector4d::Zero());
    double sq = 0.0, sw = 0.0, noise_max = 0.0;
    for (std::size_t j = 0; j < approach_.size(); ++j) {
      const ApproachSample& a = approach_[j];
      const auto jj = static_cast<std::int64_t>(j);
      if (approach_start_ >= 0 && jj >= approach_start_) {
        Eigen::Matrix<double, 6, 1> yn;
        yn << 0.5 * x[3], 0.5 * x[4], 0.5 * x[5], x[0], x[1], x[2];
        const Eigen::Vector2d filtered = p.filter * (Eigen::Map<const Eigen::Matrix<double, 6, 1>>(a.y) - yn);
        noise_max = std::max({noise_max, std::fabs(yn[axis_]), std::fabs(yn[3 + axis_])});
        sq += filtered[0];
        sw += filtered[1];
        if ((jj - approach_start_ + 1) % every == 0) {
          fit.add(approach_from_s_ + static_cast<double>(jj - approach_start_) * tick, sq / static_cast<double>(every),
                  sw / static_cast<double>(every));
          sq = sw = 0.0;
        }
      }
      const Eigen::Vector3d v(a.v[0], a.v[1], a.v[2]);
      pipe[j % pipe.size()] = p.Kx * x + p.Kv * v;
      const Eigen::Vector4d applied = j >= static_cast<std::size_t>(L) ? pipe[(j - static_cast<std::size_t>(L)) % pipe.size()]
                                                                      : Eigen::Vector4d::Zero();
      x = p.Phi * x + p.Gamma * applied;
    }
    f["attitude_noise_response_max"] = noise_max;
    f["attitude_fit_samples"] = fit.samples();
    if (!fit.valid()) return;
    const analysis::PlanarModeFit::Pair q = fit.pair();
    const analysis::PairShape got = analysis::pair_shape(q.first, q.second);
    f["attitude_natural_frequency_rad_s"] = got.natural_frequency;
    f["attitude_damping_ratio"] = got.damping_ratio;
  }

  double attitude_error_rad() const {
    const dynamics::Quat e = reference_.conjugate() * plant_.attitude();
    return 2.0 * std::atan2(e.vec().norm(), std::fabs(e.w()));
  }

  const CmgClusterScene& s_;
  Plant plant_;
  dynamics::Quat reference_;
  dynamics::Vec3 L0_;
  ActuatorFrame last_{};
  double error_{0.0};
  double last_outside_s_{0.0};
  double min_measure_{0.0}, min_measure_s_{0.0};
  std::int64_t near_singular_ticks_{0}, rate_limited_ticks_{0}, singular_ticks_{0}, ticks_{0};
  double peak_H_along_{0.0};  // max |H_cmg · e| over the run [N m s]
  double peak_H_{0.0}, peak_rate_{0.0}, peak_gimbal_rate_{0.0}, peak_motor_torque_{0.0}, drift_{0.0};
  analysis::HalfStepWindow<Plant::Dynamics, Plant::HeldInputs> window_;
  int axis_;
  dynamics::Vec3 slew_axis_;  // unit
  std::vector<ApproachSample> approach_;
  std::int64_t approach_start_{-1};
  double approach_from_s_{0.0};
};

struct CmgClusterTraits {
  using Scene = CmgClusterScene;
  using Binding = CmgClusterRun;
  using Controller = tools::Controller;
  // The gimbal rate commands' limit is the steering's rate limit.
  static hil::ActuatorLimits actuator_limits(const Scene& s) {
    msg::cmg_cluster::ActuatorFrame l = hil::ActuatorLimits::unlimited<msg::cmg_cluster::ActuatorFrame>();
    for (double& r : l.gimbal_rate_command_rad_s) r = s.controller.steering.max_rate * (1.0 + 1e-9);
    return hil::ActuatorLimits::of(l);
  }
  static nlohmann::json limits(const Scene& s) {
    return {{"max_gimbal_rate_rad_s", s.controller.steering.max_rate},
            {"settle_band_deg", s.settle_band_rad * kDeg},
            {"near_singular_measure", s.near_singular_measure}};
  }
};

}  // namespace

std::unique_ptr<DeviceScene> make_cmg_cluster_scene(std::unique_ptr<CmgClusterScene> s) {
  return std::make_unique<DeviceSceneOf<CmgClusterTraits>>(std::move(s));
}

}  // namespace gyrostab::tools
