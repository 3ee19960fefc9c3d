// Records a run's bus as a gyrostab bus log (tools/log/bus_log_format.hpp, docs/logs.md) through LCM's own
// log API (lcm_eventlog_create / lcm_eventlog_write_event), so lcm-logplayer and lcm-spy read it.
//
//   BusLogWriter w;
//   if (!w.open(path, scene_event, suffix, error)) ...   // creates the file, writes the scene event
//   per tick: w.write_tick(k, sensor, actuator);         // or write_sensor / write_actuator separately
//   w.close({ticks, EndReason::kCompleted, 0, ""}, error);  // end event, flush, close
//
// Per tick (write_*): encodes into buffers sized at open() and hands LCM a preassigned event: no heap
// allocation, no flush. The stdio stream buffer (256 KiB) is ours too, set at open(), so even the first
// write allocates nothing. A failed write (disk full) is remembered: every later write returns false and
// close() reports it. Not thread-safe; one writer per file.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/signal_spec.hpp"
#include "hil/lcm/frame_codec.hpp"
#include "tools/log/bus_log_format.hpp"

struct _lcm_eventlog_t;

namespace gyrostab::tools::buslog {

class BusLogWriter {
 public:
  BusLogWriter();
  ~BusLogWriter();  // closes like close() with reason kOther if still open
  BusLogWriter(const BusLogWriter&) = delete;
  BusLogWriter& operator=(const BusLogWriter&) = delete;

  // Creates (truncates) `path` and writes the scene event. false with `error` set.
  // The frames are encoded as the scene's device's LCM types (its signal table).
  bool open(const std::string& path, const SceneEvent& scene, const std::string& channel_suffix,
            std::string& error);

  bool write_sensor(std::int64_t tick, const msg::AnySensorFrame& f);
  bool write_actuator(std::int64_t tick, const msg::AnyActuatorFrame& f);
  bool write_tick(std::int64_t tick, const msg::AnySensorFrame& s, const msg::AnyActuatorFrame& a) {
    return write_sensor(tick, s) && write_actuator(tick, a);
  }

  // Writes the end event (timestamp = sim time of end.ticks), flushes and closes; false with `error` set if
  // any write since open() failed or the file cannot be flushed.
  bool close(const EndEvent& end, std::string& error);

  bool is_open() const { return log_ != nullptr; }
  bool failed() const { return failed_; }
  const std::string& path() const { return path_; }
  std::int64_t events_written() const { return events_; }

 private:
  bool write(const std::string& channel, std::int64_t timestamp_us, const std::uint8_t* data, int size);

  _lcm_eventlog_t* log_{nullptr};
  std::string path_;
  std::string sensor_channel_, actuator_channel_, end_channel_;
  std::int64_t tick_ns_{0};
  std::int64_t events_{0};
  bool failed_{false};
  const msg::DeviceSignals* signals_{nullptr};
  std::array<std::uint8_t, hil::kMaxEncodedSize> sensor_buf_{};
  std::array<std::uint8_t, hil::kMaxEncodedSize> actuator_buf_{};
  std::unique_ptr<char[]> stream_buf_;
};

}  // namespace gyrostab::tools::buslog
