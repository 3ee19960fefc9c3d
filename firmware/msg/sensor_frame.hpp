// SensorFrame: what the plant (or the real sensors) hands the controller once per controller tick — the
// sensor half of the interface contract (ICD). LCM and CAN carry exactly these fields (docs/architecture.md,
// messages and transports).
//
// One frame serves every shipped device; a device fills the signals it has and leaves the rest zero.
// Book symbols (Magnus ch. 14; docs/models/README.md) map onto the fields as follows:
//
//   device                      carrier_angle / carrier_rate      gimbal_angle / gimbal_rate    drives
//   ship roll damper (14.8)     [kRoll] = φ ship roll, φ'         [kAxis2] = β precession, β'  —
//   power stabilizer (14.20)    [kRoll] = platform φ (14.31); rates [kAxis1] = α, [kAxis2] = β  motor current
//   monorail (14.2)             [kRoll] = φ car tilt, φ'          [kAxis2] = β gyro case, β'   motor current
//   servo gyro (14.41)          carrier rates (14.45)             [kAxis1] = α, [kAxis2] = β   motor current
//   CMG cluster (14.45)         attitude (3-2-1), body rates      cluster_gimbal_angle/rate = δ_i, δ_i'
//   gimbal drive (any device)   —                                 encoder_count, rotor_speed  motor_current_A
//
// Axis 2 is the axis the book calls "2" (the precession / case axis, angle β) in every device of ch. 14, so a
// single-gimbal device uses index kAxis2, not 0.
//
// Why doubles: the plant and the host controller compute in double, and in-process, lockstep-LCM and
// lockstep-CAN runs must be bit-identical (docs/architecture.md, the loop). On a Cortex-M4F double arithmetic
// is software; a CAN frame map scales these to integers anyway (hil/can/frame_map.hpp).
//
// Layout rules (checked below and in tests/unit/contract_test.cpp): trivially copyable, standard layout,
// every member naturally aligned with no padding, fixed size. Append fields only at the end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace gyrostab::msg {

// Indices into the carrier arrays: the carrier is the body the gyro stabilizes or rides on (ship hull,
// monorail car, stabilized platform). Axes: 1 longitudinal (roll), 2 transverse (pitch), 3 normal (yaw).
inline constexpr std::size_t kRoll = 0;
inline constexpr std::size_t kPitch = 1;
inline constexpr std::size_t kYaw = 2;
inline constexpr std::size_t kCarrierAxes = 3;

// Indices into the gimbal arrays (Magnus ch. 10, 14): axis 1 = outer gimbal, angle α; axis 2 = inner gimbal
// or gyro case, angle β (the precession angle of the ship damper and the monorail).
inline constexpr std::size_t kAxis1 = 0;
inline constexpr std::size_t kAxis2 = 1;
inline constexpr std::size_t kGimbalAxes = 2;

// Units of a multi-gyro cluster (a CMG cluster's single-gimbal control moment gyros, each with its own gimbal
// electronics): the cluster's gimbals have their own fields, so the two axes above keep their meaning.
inline constexpr std::size_t kClusterUnits = 4;

struct SensorFrame {
  std::uint64_t tick{0};           // controller tick this frame belongs to [tick]
  std::int64_t time_ns{0};         // publish time on the plant's clock [ns]
  std::int64_t sample_time_ns{0};  // when the signals were sampled (≤ time_ns by the sensor latency) [ns]
  std::uint32_t sequence{0};       // publisher's frame counter: +1 per frame, wraps at 2^32 [-]
  std::uint32_t status{0};         // SensorStatusBit set (firmware/msg/fault_bits.hpp) [bits]

  // Carrier attitude relative to the local level: roll φ, pitch θ, yaw ψ (3-2-1 Tait-Bryan) [rad].
  double carrier_angle_rad[kCarrierAxes]{};
  // Angular velocity of the carrier relative to inertial space, in carrier axes (w_WC_C) [rad/s]; for the
  // small-angle devices of ch. 14, carrier_rate_rad_s[kRoll] = φ'.
  double carrier_rate_rad_s[kCarrierAxes]{};
  // Gimbal angles relative to their neutral position: [kAxis1] = α, [kAxis2] = β [rad].
  double gimbal_angle_rad[kGimbalAxes]{};
  // Gimbal angular rates relative to the carrier: [kAxis1] = α', [kAxis2] = β' [rad/s].
  double gimbal_rate_rad_s[kGimbalAxes]{};
  // Measured winding current of the torque motor on each gimbal axis (positive = positive torque) [A].
  double motor_current_A[kGimbalAxes]{};
  // Spin speed of the rotor relative to the innermost gimbal (angular momentum H ≈ C · rotor_speed) [rad/s].
  double rotor_speed_rad_s{0.0};
  // Raw gimbal encoder counts, motor side (before the gear), wrapping at 2^32 [counts].
  std::int32_t encoder_count[kGimbalAxes]{};
  // Gimbal angle δ_i of each unit of a cluster (the unit's absolute encoder, in [−π, π)) [rad].
  double cluster_gimbal_angle_rad[kClusterUnits]{};
  // Gimbal rate δ_i' of each unit of a cluster, relative to the carrier (the unit's rate loop feedback) [rad/s].
  double cluster_gimbal_rate_rad_s[kClusterUnits]{};
};

static_assert(std::is_trivially_copyable_v<SensorFrame>, "transports memcpy the contract");
static_assert(std::is_standard_layout_v<SensorFrame>, "transports rely on declaration-order layout");
// 8+8+8+4+4 header, 13 doubles, 2 int32, 8 cluster doubles: any change here is a contract change (update LCM/CAN
// maps too).
static_assert(sizeof(SensorFrame) == 32 + 13 * 8 + 2 * 4 + 8 * 8, "SensorFrame layout changed or gained padding");
static_assert(alignof(SensorFrame) == 8);

}  // namespace gyrostab::msg
