// The manoeuvre corners (segment ends, vehicle_motion.hpp) of a per-tick sampled vehicle: the rates and
// accelerations jump at a corner, so a tick ending on one integrates with the generator's LEFT limit there
// (VehicleGenerator::sample_left_ns) and the next tick starts from the right limit (sample_ns) — one extra
// sample per corner; otherwise RK4 errs by O(h·Δa) (earth_vehicle.hpp). corners_on_ticks() refuses corners
// inside a tick. Hot path: O(1) amortized, no heap.
// Test: through the instruments' shipped scenes (tests/determinism/scene_determinism_test.cpp).
#pragma once

#include <array>
#include <cstdint>

#include "sim/motion/vehicle_motion.hpp"

namespace gyrostab::motion {

class CornerClock {
 public:
  explicit CornerClock(const VehicleMotionParams& m) : count_(m.count) {
    std::int64_t t = 0;
    for (int k = 0; k < m.count; ++k) {
      t += m.segments[static_cast<std::size_t>(k)].duration_ns;
      corners_[static_cast<std::size_t>(k)] = t;
    }
  }

  // True if t_ns is a corner; call with non-decreasing t_ns.
  bool corner_at(std::int64_t t_ns) {
    while (next_ < count_ && corners_[static_cast<std::size_t>(next_)] < t_ns) ++next_;
    return next_ < count_ && corners_[static_cast<std::size_t>(next_)] == t_ns;
  }

 private:
  std::array<std::int64_t, kMaxVehicleSegments> corners_{};
  int count_{0};
  int next_{0};
};

}  // namespace gyrostab::motion
