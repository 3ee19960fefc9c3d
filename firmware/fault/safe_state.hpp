// The safe command (docs/architecture.md, faults and safe states): every command at its signal table's safe
// value — gimbal drives at zero torque and zero voltage, cluster gimbals commanded to rest, a precession brake
// full on — and FaultBit::kSafeState in the status, so a drive disables its bridge whatever the numbers say.
// Why the brake and not a free case: a locked case turns the stabilizer into a rigid mass on the carrier
// (Magnus (14.15): the ship rolls as if unstabilized), which is safe; a free case with a spinning rotor can run
// into its end stops.
#pragma once

#include <cstddef>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/fault_bits.hpp"

namespace gyrostab::firmware {

// Every command of `command` at its safe value (the table's `safe`), the header and status untouched. O(commands).
template <msg::TypedFrame ActuatorFrame>
void set_safe_values(ActuatorFrame& command) {
  const auto specs = msg::specs_of<ActuatorFrame>();
  for (std::size_t i = 0; i < specs.size(); ++i) msg::set_signal_value(command, i, specs[i].safe);
}

// Overwrites the commands of `command` with the safe command and adds kSafeState to its status; the header
// (tick, time, sequence, sensor tick) and the other status bits are kept. O(commands).
template <msg::TypedFrame ActuatorFrame>
void command_safe_state(ActuatorFrame& command) {
  set_safe_values(command);
  command.status |= msg::bit(msg::FaultBit::kSafeState);
}

}  // namespace gyrostab::firmware
