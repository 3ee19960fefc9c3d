// The frames the gyro instruments are referred to, from the vehicle generator's trihedra
// (sim/motion/earth_vehicle.hpp) as the FrameSample of the master equation (10.22)
// (sim/models/gyro_in_rotating_frame.hpp): absolute rate Ω [rad/s], its derivative Ω' [rad/s²] and the
// specific force f [m/s²], in the instrument's axes.
//
// The plumb line: the generator's specific force contains the Earth's centrifugal acceleration
// Ω_E × (Ω_E × r), whose horizontal part tilts the plumb line of a rotating SPHERE from its geocentric
// vertical by Ω_E² R sinφ cosφ / g (0.1° at 45°). On the real Earth the level surface is an ellipsoid and the
// plumb line is its normal — the vertical the book's instruments are referred to (its spherical Earth has
// gravity along the vertical). For the pendulous instruments (gyro vertical, gyrocompass) this part is
// removed, so the plumb line at rest is the frame's vertical; motion-induced terms (vehicle acceleration,
// Coriolis) stay. The platform keeps the raw f: its Schuler loop is exact relative to the geocentric vertical
// (the azimuth-free frame's horizontal f is the derivative of the absolute velocity), and it levels to that.
// Hot path: a few vector operations, no heap.
// Test: through the instruments' shipped scenes (tests/determinism/scene_determinism_test.cpp).
#pragma once

#include "sim/models/gyro_in_rotating_frame.hpp"
#include "sim/motion/earth_vehicle.hpp"

namespace gyrostab::plants {

// Removes the horizontal part of the Earth's centrifugal acceleration from Z's specific force.
inline void remove_centrifugal_tilt(const motion::EarthVehicleSample& s, double earth_rate,
                                    motion::Trihedron& Z) {
  const dynamics::Vec3 w(0.0, 0.0, earth_rate);
  const dynamics::Vec3 c_I = w.cross(w.cross(s.p_I));
  const dynamics::Vec3 up_I = s.p_I.normalized();
  const dynamics::Vec3 horizontal_I = c_I - c_I.dot(up_I) * up_I;
  Z.f_Z -= Z.q_IZ.conjugate() * horizontal_I;
}

// A trihedron Z of the sample s (track, geographic) with the plumb line as its vertical at rest.
inline motion::Trihedron plumb_referred(const motion::EarthVehicleSample& s, motion::Trihedron Z,
                                        double earth_rate) {
  remove_centrifugal_tilt(s, earth_rate, Z);
  return Z;
}

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

// A pendulous instrument's frame from a sample: its trihedron `which` (track, geographic) with the plumb
// line as the vertical at rest, in the instrument's `axes` (frame_forward_right_down, ...).
struct PlumbFrame {
  motion::Trihedron motion::EarthVehicleSample::*which;
  models::FrameSample (*axes)(const motion::Trihedron&);
  double earth_rate;  // [rad/s]
  models::FrameSample operator()(const motion::EarthVehicleSample& v) const {
    return axes(plumb_referred(v, v.*which, earth_rate));
  }
};

}  // namespace gyrostab::plants
