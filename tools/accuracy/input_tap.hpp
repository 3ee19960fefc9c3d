// A device seen through a tap: the closed loop (run_closed_loop) runs the device unchanged, and after every
// tick the tap hands the device to `capture(device, tick)`, which copies what the plant held over that tick
// (its zero-order-hold inputs) and the state it reached. The accuracy study replays those inputs open loop.
#pragma once

#include <cstdint>

#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::tools::accuracy {

template <class Device, class Capture>
struct InputTap {
  Device& device;
  Capture capture;

  void sense(std::int64_t tick, msg::SensorFrame& f) { device.sense(tick, f); }
  void actuate(const msg::ActuatorFrame& cmd) { device.actuate(cmd); }
  void advance(std::int64_t tick) {
    device.advance(tick);
    capture(static_cast<const Device&>(device), tick);
  }
  bool finite() const { return device.finite(); }
  void record(double* row) const { device.record(row); }
  msg::ActuatorFrame initial_command() const { return device.initial_command(); }
  auto& controller() { return device.controller(); }
};

template <class Device, class Capture>
InputTap<Device, Capture> make_input_tap(Device& d, Capture c) {
  return {d, c};
}

}  // namespace gyrostab::tools::accuracy
