#include "tools/log/frame_channel.hpp"

#include <string>

namespace gyrostab::tools {

namespace {

SignalInfo header(const char* name, const char* unit, const char* what) {
  SignalInfo s;
  s.name = name;
  s.unit = unit;
  s.description = what;
  s.integer = true;
  s.declared = true;
  return s;
}

}  // namespace

ChannelInfo frame_channel(const msg::DeviceSignals& device, FrameDirection direction) {
  const bool sensor = direction == FrameDirection::kSensor;
  ChannelInfo c;
  c.topic = sensor ? kSensorTopic : kActuatorTopic;
  c.title = "gyrostab." + std::string(device.device) + (sensor ? ".sensor" : ".actuator");
  if (sensor) {
    c.signals.push_back(header("time_ns", "ns", "publish time on the plant's clock"));
    c.signals.push_back(header("sample_time_ns", "ns", "when the signals were sampled"));
    c.signals.push_back(header("sequence", "-", "publisher's frame counter, +1 per frame, wraps at 2^32"));
    c.signals.push_back(header("status", "bits", "SensorStatusBit set (firmware/msg/fault_bits.hpp)"));
  } else {
    c.signals.push_back(header("time_ns", "ns", "the tick's time: tick x tick_ns"));
    c.signals.push_back(header("sensor_tick", "tick", "tick of the sensor frame the command was computed from"));
    c.signals.push_back(header("sequence", "-", "controller's frame counter, wraps at 2^32"));
    c.signals.push_back(header("status", "bits", "FaultBit set (firmware/msg/fault_bits.hpp): safe state, causes"));
  }
  for (const msg::SignalSpec& spec : sensor ? device.sensors : device.commands) {
    SignalInfo s;
    s.name = std::string(spec.name);
    s.unit = std::string(spec.unit);
    if (!spec.symbol.empty()) s.symbol = std::string(spec.symbol);
    if (!spec.description.empty()) s.description = std::string(spec.description);
    s.min = spec.min;
    s.max = spec.max;
    s.count = spec.count;
    s.element = spec.element;
    s.declared = true;
    c.signals.push_back(std::move(s));
  }
  return c;
}

std::size_t frame_width(const msg::DeviceSignals& device, FrameDirection direction) {
  return kFrameHeaderValues +
         (direction == FrameDirection::kSensor ? device.sensors.size() : device.commands.size());
}

void frame_values(const msg::AnySensorFrame& f, const msg::DeviceSignals& device, double* out) {
  out[0] = static_cast<double>(f.time_ns);
  out[1] = static_cast<double>(f.sample_time_ns);
  out[2] = static_cast<double>(f.sequence);
  out[3] = static_cast<double>(f.status);
  for (std::size_t i = 0; i < device.sensors.size(); ++i) out[kFrameHeaderValues + i] = f.signal[i];
}

void frame_values(const msg::AnyActuatorFrame& f, const msg::DeviceSignals& device, double* out) {
  out[0] = static_cast<double>(f.time_ns);
  out[1] = static_cast<double>(f.sensor_tick);
  out[2] = static_cast<double>(f.sequence);
  out[3] = static_cast<double>(f.status);
  for (std::size_t i = 0; i < device.commands.size(); ++i) out[kFrameHeaderValues + i] = f.signal[i];
}

}  // namespace gyrostab::tools
