#include "tools/run/frame_table.hpp"

#include <algorithm>

#include "tools/loop/recorder.hpp"

namespace gyrostab::tools {

namespace {

std::int64_t rows_for(std::int64_t ticks, std::int64_t every) {
  return ticks <= 0 ? 0 : (ticks - 1) / every + 1;
}

}  // namespace

FrameTable::FrameTable(const msg::DeviceSignals& device, std::int64_t ticks, std::int64_t every)
    : device_(device),
      every_(std::max<std::int64_t>(every, 1)),
      capacity_(rows_for(ticks, std::max<std::int64_t>(every, 1))),
      sensor_width_(frame_width(device, FrameDirection::kSensor)),
      actuator_width_(frame_width(device, FrameDirection::kActuator)) {
  const auto n = static_cast<std::size_t>(capacity_);
  ticks_.resize(n);
  sensor_.resize(n * sensor_width_);
  actuator_.resize(n * actuator_width_);
}

std::string FrameTable::size_problem(const msg::DeviceSignals& device, std::int64_t ticks, std::int64_t every) {
  every = std::max<std::int64_t>(every, 1);
  const std::int64_t rows = rows_for(ticks, every);
  const auto width = static_cast<std::int64_t>(1 + frame_width(device, FrameDirection::kSensor) +
                                               frame_width(device, FrameDirection::kActuator));
  if (rows == 0 || rows <= kRecorderCeilingBytes / (width * 8)) return "";
  const std::int64_t need = (rows * width * 8) >> 20;
  const std::int64_t min_every = (ticks / (kRecorderCeilingBytes / (width * 8))) + 1;
  return "the frames of every " + std::to_string(every) + " tick(s) of " + std::to_string(ticks) + " ticks need " +
         std::to_string(need) + " MiB of table, more than the " + std::to_string(kRecorderCeilingBytes >> 20) +
         " MiB a run may record; ask for fewer (--mcap-frames-every " + std::to_string(min_every) +
         " or more) or a shorter run (--ticks)";
}

bool FrameTable::record(std::int64_t tick, const msg::AnySensorFrame& sensor, const msg::AnyActuatorFrame& command) {
  if (tick < next_) return true;
  next_ = (tick / every_ + 1) * every_;
  if (tick % every_ != 0 || rows_ >= capacity_) return true;
  const auto r = static_cast<std::size_t>(rows_);
  ticks_[r] = tick;
  frame_values(sensor, device_, &sensor_[r * sensor_width_]);
  frame_values(command, device_, &actuator_[r * actuator_width_]);
  ++rows_;
  return true;
}

}  // namespace gyrostab::tools
