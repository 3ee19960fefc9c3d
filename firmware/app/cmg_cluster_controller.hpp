// CMG cluster controller (Magnus §14.4, (14.45); the spacecraft is the gyrostat of §4.1): attitude by
// quaternion error feedback, the torque demand turned into gimbal rate commands by a steering law, inside the
// common controller runtime (fault monitor, scheduler, header, safe state: controller_runtime.hpp). The gimbal
// rate servos are in the CMG electronics, part of the plant (sim/plants/cmg_cluster_plant.hpp), as real
// clusters have them: the flight computer sends gimbal rate commands.
//
// Laws: firmware/control/attitude_quaternion_feedback.hpp (u = −K_p q_e,vec sign(q_e,0) − K_d ω + ω × H),
// firmware/control/cmg_steering.hpp (ν = −A⁺ u: pseudo-inverse, singularity-robust or generalized
// singularity-robust inverse, rate limit). The generalized inverse's dither time is t = tick · T_b, the tick of
// the sensor frame the law runs on (deterministic, the same on host and target).
// Frames: the cluster's own (tools/devices/cmg_cluster/cmg_cluster_signals.toml, docs/icd/cmg_cluster.md,
// docs/models/cmg-cluster.md#signals):
// Reads attitude_rad = the spacecraft attitude q_WB as 3-2-1 angles (roll, pitch, yaw) [rad] (star tracker;
//   rebuilt into q here, valid away from pitch ±90°); body_rate_rad_s = ω, body axes [rad/s] (gyro package);
//   delta_rad[i] = δ_i [rad] (the CMG electronics' gimbal encoders, wrapped to [−π, π)). The law does not need
//   the gimbal rates delta_rate_rad_s.
// Writes gimbal_rate_command_rad_s[i] = ν_c,i [rad/s]. The safe state's zeros command every gimbal to rest
//   (the cluster has no brake). Status: kRateLoopSaturated = the gimbal rates were scaled to max_rate;
//   kGimbalLockGuard = the pseudo-inverse met a singular configuration (det(A Aᵀ)/h⁶ ≤ singular_floor) and
//   commanded no rates — the CMG cluster's gimbal lock.
// No drive (current loops): disabled. Rates: the law every control_divisor base ticks.
// Introspection for the run report (in-process runs): last_measure() = det(A Aᵀ)/h⁶, last_lambda(),
// last_torque(k) = u_k [N m].
// Docs: docs/models/cmg-cluster.md#firmware-law
#pragma once

#include <cmath>
#include <cstdint>

#include "firmware/app/controller_runtime.hpp"
#include "firmware/control/attitude_quaternion_feedback.hpp"
#include "firmware/control/cmg_steering.hpp"
#include "firmware/control/config_check.hpp"
#include "firmware/control/law_status_bits.hpp"
#include "gyrostab_signals/cmg_cluster_frames.hpp"

namespace gyrostab::firmware {

// The frames' units (the table's count = 4).
inline constexpr int kCmgFrameUnits = static_cast<int>(sizeof(msg::cmg_cluster::SensorFrame::delta_rad) / sizeof(double));
static_assert(kMaxCmgUnits == kCmgFrameUnits &&
                  sizeof(msg::cmg_cluster::ActuatorFrame::gimbal_rate_command_rad_s) == kMaxCmgUnits * sizeof(double),
              "the law steers the frames' cluster units");

struct CmgClusterConfig {
  RuntimeConfigOf<msg::cmg_cluster::SensorFrame> runtime{};
  CmgArray array{};
  AttitudeGains attitude{};
  SteeringParams steering{};
  AttitudeQuaternion reference{};  // the commanded attitude q_WB
};

class CmgClusterLaw {
 public:
  using SensorFrame = msg::cmg_cluster::SensorFrame;
  using ActuatorFrame = msg::cmg_cluster::ActuatorFrame;

  explicit CmgClusterLaw(const CmgClusterConfig& c)
      : array_(c.array),
        gains_(c.attitude),
        steering_(c.steering),
        reference_(c.reference),
        tick_period_s_(c.runtime.tick_period_s()) {}

  void control(const SensorFrame& in, ActuatorFrame& cmd) {
    const AttitudeQuaternion q = quaternion_from_euler321(in.attitude_rad[0], in.attitude_rad[1], in.attitude_rad[2]);
    const double* w = in.body_rate_rad_s;
    const double* delta = in.delta_rad;
    double H[3];
    for (int k = 0; k < 3; ++k) H[k] = gains_.J[k][0] * w[0] + gains_.J[k][1] * w[1] + gains_.J[k][2] * w[2];
    if (gains_.gyroscopic_feedforward) {
      const CmgAxes ax = cmg_axes(array_, delta);
      for (int i = 0; i < array_.count; ++i) {
        for (int k = 0; k < 3; ++k) H[k] += array_.h * ax.s[i][k];
      }
    }
    attitude_torque(gains_, attitude_error(reference_, q), w, H, torque_);
    const double t = static_cast<double>(in.tick) * tick_period_s_;
    const SteeringOutput o = steer_cmg(array_, steering_, delta, torque_, t);
    measure_ = o.measure;
    lambda_ = o.lambda;
    for (int i = 0; i < kMaxCmgUnits; ++i) cmd.gimbal_rate_command_rad_s[i] = o.rate[i];
    if (o.rate_limited) cmd.status |= bit(LawStatusBit::kRateLoopSaturated);
    if (o.singular) cmd.status |= bit(LawStatusBit::kGimbalLockGuard);
  }
  void reset() {}  // stateless: the command follows from the frame
  void set_reference(const AttitudeQuaternion& q) { reference_ = q; }
  double last_measure() const { return measure_; }
  double last_lambda() const { return lambda_; }
  double last_torque(int k) const { return torque_[k]; }

 private:
  CmgArray array_;
  AttitudeGains gains_;
  SteeringParams steering_;
  AttitudeQuaternion reference_;
  double tick_period_s_;
  double torque_[3]{};
  double measure_{0.0};
  double lambda_{0.0};
};

template <MonotonicClock Clock = NullClock>
class BasicCmgClusterController : public ControllerRuntime<CmgClusterLaw, Clock> {
  using Base = ControllerRuntime<CmgClusterLaw, Clock>;

 public:
  using Config = CmgClusterConfig;

  static ConfigCheck check(const Config& c) {
    const ConfigCheck r = check_runtime(c.runtime, DriveConfig{}, 0u);
    if (!r.ok) return r;
    const AttitudeQuaternion& q = c.reference;
    const double n = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    if (!(std::fabs(n - 1.0) < 1e-9)) return ConfigCheck::refused("cmg cluster: the reference quaternion must be unit", n);
    if (c.array.count > kCmgFrameUnits) {
      return ConfigCheck::refused("cmg cluster: the frames carry at most 4 gimbals", c.array.count);
    }
    if (is_robust(c.steering.law) && !(c.steering.lambda0 > 0.0)) {
      return ConfigCheck::refused("cmg cluster: the singularity-robust inverse needs lambda0 > 0", c.steering.lambda0);
    }
    if (c.steering.law == SteeringLaw::kGeneralizedSingularityRobust &&
        c.steering.dither_frequency * c.runtime.control_period_s() > kMaxDitherStep) {
      return ConfigCheck::refused("cmg cluster: the sampled dither needs dither_frequency * T_c <= 0.5",
                                  c.steering.dither_frequency, 0.0, kMaxDitherStep / c.runtime.control_period_s());
    }
    const ConfigCheck s = check_cmg_steering(c.array, c.steering);
    if (!s.ok) return s;
    return check_attitude_gains(c.attitude, c.runtime.control_period_s());
  }

  explicit BasicCmgClusterController(const Config& c, Clock clock = Clock{})
      : Base(c.runtime, DriveConfig{}, 0u, CmgClusterLaw(c), check(c), clock) {}
};

using CmgClusterController = BasicCmgClusterController<>;

}  // namespace gyrostab::firmware
