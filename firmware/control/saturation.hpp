// Symmetric saturation of a command, with a flag saying whether it bit: the one place the control laws
// clip torques, so every law reports its saturation the same way (LawStatusBit, law_status_bits.hpp).
// Units: whatever the command's unit is (N m, V, rad/s). O(1), no state.
// Docs: docs/models/README.md#firmware
#pragma once

namespace gyrostab::firmware {

struct Clipped {
  double value{0.0};    // the command after clipping [unit of the command]
  bool clipped{false};  // |input| exceeded the limit
};

// Clips x to [−limit, limit] (limit > 0). NaN passes through unclipped (comparisons with NaN are false);
// the controller runtime catches a non-finite command.
constexpr Clipped clip_symmetric(double x, double limit) {
  if (x > limit) return {limit, true};
  if (x < -limit) return {-limit, true};
  return {x, false};
}

}  // namespace gyrostab::firmware
