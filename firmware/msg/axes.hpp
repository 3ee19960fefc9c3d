// The axis indices of the signal tables' arrays (a signal with count = 3 or 2 or 4 in
// tools/devices/<device>/<device>_signals.toml), for code that indexes a typed frame's array by its axis.
#pragma once

#include <cstddef>

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

// Units of a multi-gyro cluster (a CMG cluster's single-gimbal control moment gyros).
inline constexpr std::size_t kClusterUnits = 4;

}  // namespace gyrostab::msg
