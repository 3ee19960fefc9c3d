// The vehicle's motion fed tick by tick into an instrument's FrameInputs
// (sim/models/gyro_in_rotating_frame.hpp): one generator sample per tick, tick k integrating from the frame
// at its start to the LEFT limit at its end (the end of tick k is the start of tick k + 1, except at a
// manoeuvre corner, where the next tick starts from the right limit: sim/motion/corner_clock.hpp); linear in
// between. Shared by the gyro vertical, the gyrocompass and the inertial platform; each names its frame by
// `FrameOf` (instrument_frames.hpp). Units: as FrameSample (rad/s, rad/s², m/s²); time in integer ns at the
// tick ends. Hot path (begin_tick/end_tick): no heap, one generator sample per tick (two at a corner, ~40
// trig calls each). Test: through the instruments' shipped scenes
// (tests/determinism/scene_determinism_test.cpp).
#pragma once

#include <cstdint>

#include "sim/models/gyro_in_rotating_frame.hpp"
#include "sim/motion/corner_clock.hpp"
#include "sim/motion/earth_vehicle.hpp"
#include "sim/motion/vehicle_motion.hpp"

namespace gyrostab::plants {

// FrameOf: models::FrameSample(const motion::EarthVehicleSample&) const — the instrument's frame.
template <class FrameOf>
class VehicleFrameFeed {
 public:
  VehicleFrameFeed(const motion::VehicleMotionParams& m, std::int64_t tick_ns, FrameOf frame_of)
      : vehicle_(motion::make_vehicle(m)),
        corners_(m),
        frame_of_(frame_of),
        tick_ns_(tick_ns),
        tick_s_(1e-9 * static_cast<double>(tick_ns)),
        motion_(vehicle_.sample_ns(0)),
        frame_(frame_of_(motion_)) {}

  // At the current tick's start (after end_tick: the next tick's).
  const models::FrameSample& frame() const { return frame_; }
  const motion::EarthVehicleSample& motion() const { return motion_; }
  // At the end of the tick begun last (its left limit).
  const models::FrameSample& next_frame() const { return next_frame_; }

  // Before tick `tick`'s step: `in` runs from the current frame to the left limit at the tick's end.
  void begin_tick(std::int64_t tick, models::FrameInputs& in) {
    t1_ns_ = (tick + 1) * tick_ns_;
    next_motion_ = vehicle_.sample_left_ns(t1_ns_);
    next_frame_ = frame_of_(next_motion_);
    in.t0 = static_cast<double>(tick) * tick_s_;
    in.h = tick_s_;
    in.s0 = frame_;
    in.s1 = next_frame_;
  }
  // After the step: moves to the next tick's start (the right limit at a corner) and holds it in `in`.
  // Returns true at a corner.
  bool end_tick(models::FrameInputs& in) {
    const bool corner = corners_.corner_at(t1_ns_);
    if (corner) {
      motion_ = vehicle_.sample_ns(t1_ns_);
      frame_ = frame_of_(motion_);
    } else {
      motion_ = next_motion_;
      frame_ = next_frame_;
    }
    in.hold(frame_);
    return corner;
  }

 private:
  motion::VehicleGenerator vehicle_;
  motion::CornerClock corners_;
  FrameOf frame_of_;
  std::int64_t tick_ns_;
  double tick_s_;  // = PlantTiming::tick_s()
  std::int64_t t1_ns_{0};
  motion::EarthVehicleSample motion_{}, next_motion_{};
  models::FrameSample frame_{}, next_frame_{};
};

}  // namespace gyrostab::plants
