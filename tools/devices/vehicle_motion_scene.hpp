// The vehicle moving over the rotating spherical Earth (sim/motion/earth_vehicle.hpp) as the gyro
// instruments' scenes read it — [earth], [vehicle], [segment1], [segment2], ... (docs/scenes.md#vehicle-motion)
// — and the per-tick frame sampling that feeds the instruments' FrameInputs: one generator sample per tick
// (the end of tick k is the start of tick k + 1), linear in between (sim/models/gyro_in_rotating_frame.hpp).
// Start-up code (reads, validates) and the hot path (sample_tick: no heap, ~40 trig calls per tick).
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "sim/models/gyro_in_rotating_frame.hpp"
#include "sim/motion/earth_vehicle.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

inline constexpr int kMaxVehicleSegments = 32;
using VehicleGenerator = motion::EarthVehicle<kMaxVehicleSegments>;

struct VehicleMotionConfig {
  motion::EarthParams earth{};
  motion::VehicleStart start{};
  std::array<motion::ManoeuvreSegment, kMaxVehicleSegments> segments{};
  int count{0};
};

inline constexpr double kDeg = std::numbers::pi / 180.0;

// Reads [earth], [vehicle] and the consecutive [segmentN] sections (N = 1, 2, ...). `default_rotation` is the
// device's default Earth rate (0 for the book's non-rotating cases). Problems go to the reader.
inline VehicleMotionConfig read_vehicle_motion(SceneReader& r, double default_latitude_deg,
                                               double default_rotation = 7.292115e-5) {
  VehicleMotionConfig c;
  c.earth.radius = r.number("earth", "radius_m", 6.371e6, Range::positive(), "Earth radius R [m]");
  c.earth.gravity = r.number("earth", "gravity_m_s2", 9.81, Range::positive(), "gravitation g at the surface [m/s²]");
  c.earth.rotation_rate = r.number("earth", "rotation_rate_rad_s", default_rotation, Range::closed(-1e-2, 1e-2),
                                   "Earth rotation rate ω^E [rad/s] (0: non-rotating sphere)");
  c.start.latitude = kDeg * r.number("vehicle", "latitude_deg", default_latitude_deg, Range::closed(-90.0, 90.0),
                                     "start latitude φ0 [deg]");
  c.start.longitude =
      kDeg * r.number("vehicle", "longitude_deg", 0.0, Range::closed(-360.0, 360.0), "start longitude [deg]");
  c.start.heading = kDeg * r.number("vehicle", "heading_deg", 0.0, Range::closed(-360.0, 360.0),
                                    "start heading ψ0, clockwise from north [deg]");
  c.start.speed = r.number("vehicle", "speed_m_s", 0.0, Range::closed(0.0, 1e4), "start ground speed [m/s]");
  for (int k = 0; k < kMaxVehicleSegments + 1; ++k) {
    const std::string sec = "segment" + std::to_string(k + 1);
    if (!r.has_section(sec)) break;
    if (k == kMaxVehicleSegments) {
      r.fail(sec, "duration_s", "too many manoeuvre segments (at most " + std::to_string(kMaxVehicleSegments) + ")");
      break;
    }
    motion::ManoeuvreSegment& s = c.segments[static_cast<std::size_t>(k)];
    const double d = r.required(sec, "duration_s", Range::open_closed(0.0, 1e7), "segment duration [s]");
    s.duration_ns = std::isfinite(d) ? std::llround(d * 1e9) : 1;
    s.turn_rate = kDeg * r.number(sec, "turn_rate_deg_s", 0.0, Range::closed(-90.0, 90.0),
                                  "turn rate relative to the great circle, > 0 right [deg/s]");
    s.acceleration = r.number(sec, "acceleration_m_s2", 0.0, Range::closed(-100.0, 100.0),
                              "along-track acceleration [m/s²]");
    c.count = k + 1;
  }
  if (r.ok()) {
    if (const char* why = VehicleGenerator::check(c.earth, c.start, c.segments.data(), c.count)) {
      r.fail(c.count > 0 ? "segment1" : "vehicle", c.count > 0 ? "duration_s" : "speed_m_s", why);
    }
  }
  return c;
}


// nullptr if every segment corner falls on a tick boundary, else the message (scene validation).
inline const char* corners_on_ticks(const VehicleMotionConfig& c, std::int64_t tick_ns) {
  for (int k = 0; k < c.count; ++k) {
    if (c.segments[static_cast<std::size_t>(k)].duration_ns % tick_ns != 0)
      return "segment durations must be whole ticks (a manoeuvre corner inside a tick costs an O(h·Δa) error)";
  }
  return nullptr;
}

inline VehicleGenerator make_vehicle(const VehicleMotionConfig& c) {
  return VehicleGenerator(c.earth, c.start, c.segments.data(), c.count);
}

// Manoeuvre corners (segment ends) for per-tick sampling: the accelerations and rates jump at a corner, so a
// tick ending on one integrates with the LEFT limit there (VehicleGenerator::sample_left_ns) and the next tick
// starts from the right limit (sample_ns) — one extra sample per corner; otherwise RK4 errs by O(h·Δa)
// (sim/motion/earth_vehicle.hpp). corners_on_ticks() refuses corners inside a tick.
class CornerClock {
 public:
  explicit CornerClock(const VehicleMotionConfig& c);
  // True if t_ns is a corner; call with non-decreasing t_ns. O(1) amortized.
  bool corner_at(std::int64_t t_ns) {
    while (next_ < count_ && corners_[static_cast<std::size_t>(next_)] < t_ns) ++next_;
    return next_ < count_ && corners_[static_cast<std::size_t>(next_)] == t_ns;
  }

 private:
  std::array<std::int64_t, kMaxVehicleSegments> corners_{};
  int count_{0};
  int next_{0};
};

inline CornerClock::CornerClock(const VehicleMotionConfig& c) : count_(c.count) {
  std::int64_t t = 0;
  for (int k = 0; k < c.count; ++k) {
    t += c.segments[static_cast<std::size_t>(k)].duration_ns;
    corners_[static_cast<std::size_t>(k)] = t;
  }
}

// Start time of segment i (i = count: the final cruise) [ns].
inline std::int64_t segment_start_ns(const VehicleMotionConfig& c, int i) {
  std::int64_t t = 0;
  for (int k = 0; k < i && k < c.count; ++k) t += c.segments[static_cast<std::size_t>(k)].duration_ns;
  return t;
}

// The generator's specific force contains the Earth's centrifugal acceleration Ω_E × (Ω_E × r), whose
// horizontal part tilts the plumb line of a rotating SPHERE from its geocentric vertical by
// Ω_E² R sinφ cosφ / g (0.1° at 45°). On the real Earth the level surface is an ellipsoid and the plumb line is
// its normal — the vertical the book's instruments are referred to (its spherical Earth has gravity along
// the vertical). For the pendulous instruments (gyro vertical, gyrocompass) this part is removed, so the
// plumb line at rest is the frame's vertical; motion-induced terms (vehicle acceleration, Coriolis) stay.
// The platform keeps the raw f: its Schuler loop is exact relative to the geocentric vertical (the
// azimuth-free frame's horizontal f is the derivative of the absolute velocity), and it levels to that.
inline void remove_centrifugal_tilt(const motion::EarthVehicleSample& s, double earth_rate, motion::Trihedron& Z) {
  const dynamics::Vec3 w(0.0, 0.0, earth_rate);
  const dynamics::Vec3 c_I = w.cross(w.cross(s.p_I));
  const dynamics::Vec3 up_I = s.p_I.normalized();
  const dynamics::Vec3 horizontal_I = c_I - c_I.dot(up_I) * up_I;
  Z.f_Z -= Z.q_IZ.conjugate() * horizontal_I;
}
// A trihedron Z of the sample s (track, geographic) with the plumb line as its vertical at rest.
inline motion::Trihedron plumb_referred(const motion::EarthVehicleSample& s, motion::Trihedron Z, double earth_rate) {
  remove_centrifugal_tilt(s, earth_rate, Z);
  return Z;
}

// The instruments' frames from the generator's trihedra.
// Gyro vertical (forward, right, down) from the track trihedron T (forward, left, up).
inline models::FrameSample frame_forward_right_down(const motion::Trihedron& T) {
  const dynamics::Vec3 flip(1.0, -1.0, -1.0);
  return {T.w_IZ_Z.cwiseProduct(flip), T.dw_IZ_Z.cwiseProduct(flip), T.f_Z.cwiseProduct(flip)};
}
// Gyrocompass (up, east, north) from the geographic trihedron G (east, north, up).
inline models::FrameSample frame_up_east_north(const motion::Trihedron& G) {
  auto perm = [](const dynamics::Vec3& v) { return dynamics::Vec3(v.z(), v.x(), v.y()); };
  return {perm(G.w_IZ_Z), perm(G.dw_IZ_Z), perm(G.f_Z)};
}
// A trihedron as it is (T for the single-axis platform, F for the three-axis platform).
inline models::FrameSample frame_as_is(const motion::Trihedron& Z) {
  return {Z.w_IZ_Z, Z.dw_IZ_Z, Z.f_Z};
}

// A pendulous instrument's frame from a sample: its trihedron `which` (track, geographic) with the plumb line
// as the vertical at rest (plumb_referred), in the instrument's `axes` (frame_forward_right_down, ...).
struct PlumbFrame {
  motion::Trihedron motion::EarthVehicleSample::*which;
  models::FrameSample (*axes)(const motion::Trihedron&);
  double earth_rate;  // [rad/s]
  models::FrameSample operator()(const motion::EarthVehicleSample& v) const {
    return axes(plumb_referred(v, v.*which, earth_rate));
  }
};

}  // namespace gyrostab::tools
