// Status bits of the control laws and the controller runtime in ActuatorFrame::status (bits 16-31 belong to
// the laws, firmware/msg/fault_bits.hpp). One registry so that a bit means the same thing for every device:
// bits 16-20 are PowerStabilizerStatusBit (firmware/control/power_stabilizer_loops.hpp), bits 21-30 these.
// A decoder needs this file and power_stabilizer_loops.hpp to say why a law limited its command.
// Append only; never renumber.
// Docs: docs/models/README.md#firmware
#pragma once

#include <cstdint>

namespace gyrostab::firmware {

enum class LawStatusBit : std::uint32_t {
  kAxis2TorqueSaturated = 1u << 21,   // the axis-2 torque command was clipped to its limit this control tick
  kBeyondSoftLimit = 1u << 22,        // |β| is beyond the soft precession limit (restoring term active)
  kEndStopBraking = 1u << 23,         // the precession is being braked to stop at the soft limit (end stops)
  kRateLoopSaturated = 1u << 24,      // servo-gyro rate loop clipped; its integrator is held (anti-windup)
  kGimbalLockGuard = 1u << 25,        // servo gyro: |cos β| below its floor, the torque demand is limited
  kConfigRefused = 1u << 26,          // the controller's Config failed check(): the safe command, every tick
  kNonFiniteCommand = 1u << 27,       // a law produced NaN/Inf from finite inputs: safe command this tick
  kDriveVoltageSaturated = 1u << 28,  // a current loop clipped its voltage (torque_current_loop.hpp)
  kCorrectionCutOut = 1u << 29,       // gyro vertical: the turn cut-out removed correction torque (12.3.2)
  kInstrumentTorqueLimited = 1u << 30,  // gyro instrument (vertical, compass, platform): a torquer was clipped
};

constexpr std::uint32_t bit(LawStatusBit b) {
  return static_cast<std::uint32_t>(b);
}

// Every bit above (for clearing them before a law writes its own).
inline constexpr std::uint32_t kLawStatusMask = 0x3FFu << 21;

}  // namespace gyrostab::firmware
