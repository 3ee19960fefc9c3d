// A vehicle's planned motion over the rotating spherical Earth, as a scene of the gyro instruments gives it:
// the Earth, the start and up to 32 manoeuvre segments for the generator of sim/motion/earth_vehicle.hpp
// (great-circle legs, coordinated turns, along-track accelerations; after the last segment a great-circle
// cruise at the final speed). Segments are timed in whole ns; a segment's end is a corner, where the rates
// and accelerations jump (corner_clock.hpp samples both sides of it).
// Units: SI (m, s, rad, m/s, m/s²) as in earth_vehicle.hpp. Start-up code except segment_start_ns.
// Test: tests/unit/earth_vehicle_test.cpp (the generator); the instruments' shipped scenes through
// tests/determinism/scene_determinism_test.cpp.
#pragma once

#include <array>
#include <cstdint>

#include "sim/motion/earth_vehicle.hpp"

namespace gyrostab::motion {

inline constexpr int kMaxVehicleSegments = 32;
using VehicleGenerator = EarthVehicle<kMaxVehicleSegments>;

struct VehicleMotionParams {
  EarthParams earth{};
  VehicleStart start{};
  std::array<ManoeuvreSegment, kMaxVehicleSegments> segments{};
  int count{0};  // segments in use
};

inline const char* check_vehicle_motion(const VehicleMotionParams& m) {
  return VehicleGenerator::check(m.earth, m.start, m.segments.data(), m.count);
}

inline VehicleGenerator make_vehicle(const VehicleMotionParams& m) {
  return VehicleGenerator(m.earth, m.start, m.segments.data(), m.count);
}

// nullptr if every segment corner falls on a tick boundary, else why not: a corner inside a tick costs an
// O(h·Δa) error, one on a boundary none (the tick ends on the left limit, the next starts on the right).
inline const char* corners_on_ticks(const VehicleMotionParams& m, std::int64_t tick_ns) {
  for (int k = 0; k < m.count; ++k) {
    if (m.segments[static_cast<std::size_t>(k)].duration_ns % tick_ns != 0)
      return "segment durations must be whole ticks (a manoeuvre corner inside a tick costs an O(h·Δa) "
             "error)";
  }
  return nullptr;
}

// Start time of segment i (i = count: the final cruise) [ns].
inline std::int64_t segment_start_ns(const VehicleMotionParams& m, int i) {
  std::int64_t t = 0;
  for (int k = 0; k < i && k < m.count; ++k) t += m.segments[static_cast<std::size_t>(k)].duration_ns;
  return t;
}

}  // namespace gyrostab::motion
