// `run --mcap`: the frames of the run kept for its MCAP file's /gyrostab/sensor and /gyrostab/actuator
// channels (tools/log/frame_channel.hpp). A tick sink (closed_loop.hpp) that copies the frames of every
// `every`-th tick (by default the recorder's row interval: the frames of the recorded ticks; 1 for every tick)
// into a table sized before tick 0, like the recorder's: no allocation, no I/O and no waiting on the loop
// thread; the file is written from the table after the run. A table past the recorder's ceiling is refused
// before the run with the size it would need (size_problem).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "firmware/msg/signal_spec.hpp"
#include "tools/log/frame_channel.hpp"
#include "tools/loop/closed_loop.hpp"

namespace gyrostab::tools {

class FrameTable final : public TickSink {
 public:
  // Room for the ticks 0, every, 2 every, ... below `ticks`.
  FrameTable(const msg::DeviceSignals& device, std::int64_t ticks, std::int64_t every);

  // "" if a table for these ticks fits under the recorder's ceiling (kRecorderCeilingBytes), else the message.
  static std::string size_problem(const msg::DeviceSignals& device, std::int64_t ticks, std::int64_t every);

  bool stop_requested() override { return false; }
  bool record(std::int64_t tick, const msg::AnySensorFrame& sensor, const msg::AnyActuatorFrame& command) override;

  std::size_t rows() const { return static_cast<std::size_t>(rows_); }
  std::int64_t tick(std::size_t row) const { return ticks_[row]; }
  const msg::DeviceSignals& device() const { return device_; }
  // A direction's rows, as frame_channel(device(), direction) describes them.
  const ChannelRows& rows_of(FrameDirection direction) const {
    return direction == FrameDirection::kSensor ? static_cast<const ChannelRows&>(sensor_view_)
                                                : static_cast<const ChannelRows&>(actuator_view_);
  }

 private:
  class View final : public ChannelRows {
   public:
    View(const FrameTable& t, FrameDirection d) : t_(t), d_(d) {}
    std::size_t rows() const override { return t_.rows(); }
    std::int64_t tick(std::size_t row) const override { return t_.tick(row); }
    double value(std::size_t row, std::size_t signal) const override {
      return d_ == FrameDirection::kSensor ? t_.sensor_[row * t_.sensor_width_ + signal]
                                           : t_.actuator_[row * t_.actuator_width_ + signal];
    }

   private:
    const FrameTable& t_;
    FrameDirection d_;
  };

  const msg::DeviceSignals& device_;
  std::int64_t every_;
  std::int64_t next_{0};
  std::int64_t capacity_;
  std::int64_t rows_{0};
  std::size_t sensor_width_, actuator_width_;
  std::vector<std::int64_t> ticks_;
  std::vector<double> sensor_, actuator_;
  View sensor_view_{*this, FrameDirection::kSensor};
  View actuator_view_{*this, FrameDirection::kActuator};
};

// Two tick sinks as one (the bus log and the frame table): both see every tick; either may stop the loop.
class TickFanOut final : public TickSink {
 public:
  TickFanOut(TickSink* a, TickSink* b) : a_(a), b_(b) {}
  // The one sink when the other is absent, else this fan-out.
  TickSink* sink() { return a_ == nullptr ? b_ : b_ == nullptr ? a_ : this; }
  bool stop_requested() override { return a_->stop_requested() || b_->stop_requested(); }
  bool record(std::int64_t tick, const msg::AnySensorFrame& s, const msg::AnyActuatorFrame& c) override {
    const bool ra = a_->record(tick, s, c);
    const bool rb = b_->record(tick, s, c);
    return ra && rb;
  }

 private:
  TickSink* a_;
  TickSink* b_;
};

}  // namespace gyrostab::tools
