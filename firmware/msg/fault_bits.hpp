// Status and fault bits carried in the `status` word of SensorFrame and ActuatorFrame (the contract).
// Why a bit set and not an enum: several causes can hold at once, and a transport (LCM, CAN) carries one
// uint32 whatever the controller's state; a decoder needs nothing but this file to say why a drive stopped.
//
// Bit positions are part of the interface contract: never renumber, only append. Bits 16-31 of
// ActuatorFrame::status are reserved for the control laws (end stops, saturation, refused gains).
#pragma once

#include <cstdint>

namespace gyrostab::msg {

// SensorFrame::status — set by the sensor side (plant sensor models or real sensor drivers).
enum class SensorStatusBit : std::uint32_t {
  kRateGyroSaturated = 1u << 0,  // a rate gyro hit its measurement range; its rate field is clipped
  kEncoderError = 1u << 1,       // an encoder lost counts (index/quadrature error); counts unreliable
  kDriveFault = 1u << 2,         // a gimbal drive reports over-current, over-temperature or a bridge fault
  kRotorSpeedInvalid = 1u << 3,  // the spin-speed pick-off has no valid reading
  // Not a sensor's: the plant's end-of-run frame (docs/protocol.md). A frame for the tick after the last, its
  // signals zero; the controller does not step on it but acknowledges it and stops.
  kEndOfRun = 1u << 31,
  // With kEndOfRun: the plant ends the run because a second source sends as this controller (a hijack,
  // hil/link/source_watch.hpp); the controller ends with the same verdict.
  kSecondSource = 1u << 30,
};

// ActuatorFrame::status — set by the controller; the fault-monitor bits (0-15) say why it is holding or safe.
enum class FaultBit : std::uint32_t {
  // Causes, one per check of the fault monitor (firmware/fault/fault_monitor.hpp):
  kSensorMissing = 1u << 0,        // no sensor frame arrived for this tick
  kSensorStale = 1u << 1,          // a frame arrived but is not new: sequence or tick not advancing, too old,
                                   // or stamped ahead of the controller's tick
  kSensorNonFinite = 1u << 2,      // a signal is NaN or ±Inf
  kSensorOutOfRange = 1u << 3,     // a signal is outside its configured range
  kSensorReportedFault = 1u << 4,  // SensorFrame::status carries a bit the configuration treats as a fault
  // States:
  kHoldingLastGood = 1u << 8,  // this command was computed from the last good frame, held (not this tick's)
  kSafeState = 1u << 9,        // safe state: precession brake engaged, every drive at zero torque;
                               // the cause bits set alongside are the latched reason
  kAwaitingFirstFrame = 1u << 10,  // start-up: no good sensor frame yet; the command is the safe command
  // Not the monitor's: the controller's acknowledgement of the plant's end-of-run frame (docs/protocol.md),
  // in an actuator frame for that frame's tick, every command at its safe value.
  kEndOfRun = 1u << 11,
};

// All cause bits (what can trip the safe state).
inline constexpr std::uint32_t kFaultCauseMask = 0x1Fu;

constexpr std::uint32_t bit(FaultBit b) {
  return static_cast<std::uint32_t>(b);
}
constexpr std::uint32_t bit(SensorStatusBit b) {
  return static_cast<std::uint32_t>(b);
}
constexpr bool has(std::uint32_t status, FaultBit b) {
  return (status & bit(b)) != 0u;
}
constexpr bool has(std::uint32_t status, SensorStatusBit b) {
  return (status & bit(b)) != 0u;
}

}  // namespace gyrostab::msg
