// The safe command (docs/architecture.md, faults and safe states): precession brake full on, every gimbal
// drive at zero torque and zero voltage, every cluster gimbal commanded to rest, and FaultBit::kSafeState in the status so a drive disables its
// bridge whatever the numbers say. Why the brake and not a free case: a locked case turns the stabilizer into
// a rigid mass on the carrier (Magnus (14.15): the ship rolls as if unstabilized), which is safe; a free case
// with a spinning rotor can run into its end stops.
#pragma once

#include <cstddef>

#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/fault_bits.hpp"

namespace gyrostab::firmware {

// Overwrites the commands of `command` with the safe command and adds kSafeState to its status; the header
// (tick, time, sequence, sensor tick) and the other status bits are kept. O(1).
constexpr void command_safe_state(msg::ActuatorFrame& command) {
  for (std::size_t i = 0; i < msg::kGimbalAxes; ++i) {
    command.gimbal_torque_Nm[i] = 0.0;
    command.motor_voltage_V[i] = 0.0;
  }
  for (std::size_t i = 0; i < msg::kClusterUnits; ++i) command.cluster_rate_command_rad_s[i] = 0.0;
  command.precession_brake = 1.0;
  command.status |= msg::bit(msg::FaultBit::kSafeState);
}

}  // namespace gyrostab::firmware
