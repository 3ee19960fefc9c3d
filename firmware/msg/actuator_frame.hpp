// The shared ActuatorFrame of the devices that have no signal table of their own yet (sensor_frame.hpp).
// Safe state (status has FaultBit::kSafeState): every command at its table's safe value — torques, voltages and
// cluster rate commands zero, the precession brake full on — and a drive that sees the bit disables its bridge
// (zero current) whatever the other fields say.
#pragma once

#include "firmware/msg/sensor_frame.hpp"
