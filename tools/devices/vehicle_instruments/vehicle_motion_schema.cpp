// The vehicle motion's field tables: [earth] and [vehicle] over motion::VehicleMotionParams, and one
// [segmentN] table read for N = 1, 2, ... while the section exists.
#include "tools/devices/vehicle_instruments/vehicle_motion_schema.hpp"

#include <array>
#include <cmath>
#include <string>

#include "tools/scene/schema.hpp"

namespace gyrostab::tools {
namespace {

using M = motion::VehicleMotionParams;
using F = schema::Fields<M>;
using Segment = motion::ManoeuvreSegment;
using FS = schema::Fields<Segment>;

constexpr schema::Field<M> kFields[] = {
    F::number("earth", "radius_m", "m", Range::positive(), "Earth radius R", GS_NUMBER(earth.radius)),
    F::number("earth", "gravity_m_s2", "m/s²", Range::positive(),
              "Newtonian attraction g = GM/R² at the surface", GS_NUMBER(earth.gravity)),
    F::number("earth", "rotation_rate_rad_s", "rad/s", Range::closed(-1e-2, 1e-2),
              "Earth rate ω^E (0: non-rotating sphere)", GS_NUMBER(earth.rotation_rate)),
    F::number("vehicle", "latitude_deg", "deg", Range::closed(-90.0, 90.0), "start latitude φ0 (geocentric)",
              GS_NUMBER(start.latitude))
        .degrees(),
    F::number("vehicle", "longitude_deg", "deg", Range::closed(-360.0, 360.0), "start longitude",
              GS_NUMBER(start.longitude))
        .degrees(),
    F::number("vehicle", "heading_deg", "deg", Range::closed(-360.0, 360.0),
              "start heading ψ0, clockwise from north", GS_NUMBER(start.heading))
        .degrees(),
    F::number("vehicle", "speed_m_s", "m/s", Range::closed(0.0, 1e4), "start ground speed",
              GS_NUMBER(start.speed)),
};

// The file gives seconds; the generator counts whole ns (a non-finite value is refused by the reader).
void set_duration(Segment& s, double v) {
  s.duration_ns = std::isfinite(v) ? std::llround(v * 1e9) : 1;
}
double get_duration(const Segment& s) {
  return 1e-9 * static_cast<double>(s.duration_ns);
}

// Section "segmentN" stands for segment1, segment2, ... (replaced when read).
constexpr schema::Field<Segment> kSegmentFields[] = {
    FS::number("segmentN", "duration_s", "s", Range::open_closed(0.0, 1e7), "segment duration (whole ticks)",
               set_duration, get_duration)
        .req(),
    FS::number("segmentN", "turn_rate_deg_s", "deg/s", Range::closed(-90.0, 90.0),
               "turn rate relative to the great circle, > 0 right", GS_NUMBER(turn_rate))
        .degrees(),
    FS::number("segmentN", "acceleration_m_s2", "m/s²", Range::closed(-100.0, 100.0),
               "along-track acceleration (the speed must stay ≥ 0)", GS_NUMBER(acceleration)),
};

constexpr const char* kNote =
    "The instruments on a vehicle (`gyro_vertical`, `gyrocompass`, `inertial_platform`, `gyro_pendulum`, "
    "`bauersfeld_compass`) "
    "ride on a vehicle moving over the rotating spherical Earth: sim/motion/earth_vehicle.hpp (great-circle "
    "legs, coordinated turns, along-track accelerations; exact closed forms), planned by `[earth]`, "
    "`[vehicle]` and the consecutive sections `[segment1]`, `[segment2]`, … (at most 32; after the last one "
    "the vehicle cruises on a great circle at its final speed). A segment turns or accelerates, not both. "
    "Segment durations must be whole ticks: the rates and accelerations jump at a segment's end (a corner), "
    "and the plants integrate each tick with the generator's left limit at its end and start the next tick "
    "from the right limit (sim/motion/corner_clock.hpp; an O(h·Δa) error otherwise). Between the two samples "
    "of a tick the frame's motion is linear (sim/plants/vehicle_frame_feed.hpp).\n\nThe pendulous "
    "instruments (gyro vertical, gyrocompass) see the specific force without the horizontal part of the "
    "Earth's centrifugal acceleration (sim/plants/instrument_frames.hpp): on the real, ellipsoidal Earth the "
    "plumb line is the level surface's normal, the vertical the book refers them to; motion-induced terms "
    "(accelerations, Coriolis) stay. The inertial platform and the gyro pendulum keep the raw specific force "
    "and refer to the geocentric vertical; so does the spatial compass (`bauersfeld_compass`: the absolute "
    "acceleration and the book's central gravity, the generator sampled exactly at every RK4 stage).";

}  // namespace

void read_vehicle_motion(SceneReader& r, motion::VehicleMotionParams& m) {
  schema::read(r, kFields, m);
  constexpr int kMax = motion::kMaxVehicleSegments;
  for (int k = 0; k < kMax + 1; ++k) {
    const std::string section = "segment" + std::to_string(k + 1);
    if (!r.has_section(section)) break;
    if (k == kMax) {
      r.fail(section, "duration_s", "too many manoeuvre segments (at most " + std::to_string(kMax) + ")");
      break;
    }
    std::array<schema::Field<Segment>, std::size(kSegmentFields)> fields;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      fields[i] = kSegmentFields[i];
      fields[i].section = section;
    }
    schema::read(r, std::span<const schema::Field<Segment>>(fields), m.segments[static_cast<std::size_t>(k)]);
    m.count = k + 1;
  }
  if (r.ok()) {
    if (const char* why = motion::check_vehicle_motion(m)) {
      r.fail(m.count > 0 ? "segment1" : "vehicle", m.count > 0 ? "duration_s" : "speed_m_s", why);
    }
  }
}

SceneDocTable vehicle_motion_doc() {
  SceneDocTable t = schema::document(kFields, "vehicle motion", kNote);
  for (SceneDocRow& row : t.rows) {
    // The devices' own defaults (their plants' VehicleMotionParams).
    if (row.key == "`[earth] rotation_rate_rad_s`")
      row.fallback = "7.292115e-5 (`inertial_platform`, axes = 1: 0)";
    if (row.key == "`[vehicle] latitude_deg`") row.fallback = "50 (`inertial_platform`: 45)";
  }
  const SceneDocTable segments = schema::document(kSegmentFields);
  t.rows.insert(t.rows.end(), segments.rows.begin(), segments.rows.end());
  return t;
}

}  // namespace gyrostab::tools
