// ActuatorFrame: what the controller hands the plant (or the real drives) once per controller tick — the
// command half of the interface contract (ICD). LCM and CAN carry exactly these fields (docs/architecture.md,
// messages and transports).
//
// Book symbols (Magnus ch. 14; docs/models/README.md): gimbal_torque_Nm[kAxis2] is the precession
// torque of the active ship damper and the motor torque k φ of the monorail (14.2); [kAxis1], [kAxis2] are
// M1^K, M2^K of the power stabilizer (14.19); motor_voltage_V is u of the back-EMF law (14.26)-(14.27), used
// by drives modelled with their electrics. A plant drive reads the one its scene names.
//
// Safe state (status has FaultBit::kSafeState): torques, voltages and cluster rate commands are zero, the precession brake is full
// on, and a drive that sees the bit disables its bridge (zero current) whatever the other fields say.
//
// Layout rules as for SensorFrame: trivially copyable, standard layout, no padding, fixed size; append only.
#pragma once

#include <cstdint>
#include <type_traits>

#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::msg {

struct ActuatorFrame {
  std::uint64_t tick{0};         // controller tick at which this command was computed [tick]
  std::int64_t time_ns{0};       // publish time on the controller's clock [ns]
  std::uint64_t sensor_tick{0};  // tick of the SensorFrame the command was computed from (older than `tick`
                                 // while the fault monitor holds the last good frame) [tick]
  std::uint32_t sequence{0};     // controller's frame counter: +1 per frame, wraps at 2^32 [-]
  std::uint32_t status{0};       // FaultBit set (firmware/msg/fault_bits.hpp) [bits]

  // Commanded torque on each gimbal axis, acting on the gimbal, positive about the axis [N m].
  double gimbal_torque_Nm[kGimbalAxes]{};
  // Commanded terminal voltage of each gimbal torque motor (PWM average over the tick) [V].
  double motor_voltage_V[kGimbalAxes]{};
  // Precession brake on axis 2: 0 = released, 1 = full brake (case locked to the carrier) [-].
  double precession_brake{0.0};
  // Gimbal rate command ν_c,i to each unit of a cluster (the CMG electronics close the rate loop) [rad/s].
  double cluster_rate_command_rad_s[kClusterUnits]{};
};

static_assert(std::is_trivially_copyable_v<ActuatorFrame>, "transports memcpy the contract");
static_assert(std::is_standard_layout_v<ActuatorFrame>, "transports rely on declaration-order layout");
// 8+8+8+4+4 header, 5 doubles, 4 cluster doubles: any change here is a contract change (update LCM/CAN maps too).
static_assert(sizeof(ActuatorFrame) == 32 + 5 * 8 + 4 * 8, "ActuatorFrame layout changed or gained padding");
static_assert(alignof(ActuatorFrame) == 8);

}  // namespace gyrostab::msg
