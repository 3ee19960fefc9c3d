// Reads a gyrostab bus log (tools/log/bus_log_format.hpp, docs/logs.md) tick by tick through LCM's own log
// API (lcm_eventlog_read_next_event), and checks what LCM's reader does not: LCM skips silently to the next
// sync word after garbage and stops without a word at a cut event. Here every event must start exactly where
// the previous one ended, with the event number, channel, timestamp and payload the layout prescribes, and
// the log must end with its end event; the first violation stops reading with a message naming the byte
// offset of the offending event. Everything before it is delivered, so a cut log still replays its prefix.
//
//   BusLogReader r;
//   if (r.open(path) != ReadStatus::kOk) { r.problem() }   // reads and checks the scene event
//   TickRecord t;
//   while (r.next(t) == ReadStatus::kOk) { ... t.sensor, t.actuator ... }
//   kEnd: complete (r.end_event()); kTruncated / kCorrupt: r.problem(), r.problem_offset()
//
// Never crashes or throws on any input (tests/fuzz/bus_log_fuzz.cpp); allocation per event (LCM's reader
// allocates), so it is for tools, not for a real-time loop. Payloads are never trusted beyond the file: a
// length field is checked against the bytes left before LCM reads the event.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/signal_spec.hpp"
#include "tools/log/bus_log_format.hpp"

struct _lcm_eventlog_t;

namespace gyrostab::tools::buslog {

enum class ReadStatus {
  kOk,          // one more whole tick (or, from open(), the scene event)
  kEnd,         // the end event: the log is complete
  kTruncated,   // the file stops inside an event, or at an event boundary without the end event
  kCorrupt,     // an event that does not belong there: no sync word, wrong number/channel/timestamp/payload
  kUnreadable,  // open(): the file cannot be opened
};

const char* describe(ReadStatus s);

struct TickRecord {
  std::int64_t tick{0};
  msg::AnySensorFrame sensor{};
  msg::AnyActuatorFrame actuator{};
  std::int64_t sensor_offset{0};    // byte offset of the sensor event in the file
  std::int64_t actuator_offset{0};  // byte offset of the actuator event
};

class BusLogReader {
 public:
  BusLogReader();
  ~BusLogReader();
  BusLogReader(const BusLogReader&) = delete;
  BusLogReader& operator=(const BusLogReader&) = delete;

  // Opens `path` and reads the scene event (the first event).
  ReadStatus open(const std::string& path);
  // Reads the next tick's sensor and actuator events into `out` (unchanged unless kOk), decoded as the
  // scene's device's frames (its signal table: tools/signals/device_signals.hpp).
  ReadStatus next(TickRecord& out);
  const msg::DeviceSignals& signals() const { return *signals_; }

  const SceneEvent& scene() const { return scene_; }
  const std::string& channel_suffix() const { return suffix_; }
  const EndEvent& end_event() const { return end_; }  // valid after next() returned kEnd
  std::int64_t ticks_read() const { return ticks_; }
  std::int64_t file_size() const { return file_size_; }
  // After kTruncated / kCorrupt / kUnreadable: one line, with the byte offset; and that offset.
  const std::string& problem() const { return problem_; }
  std::int64_t problem_offset() const { return problem_offset_; }

 private:
  struct Event;
  ReadStatus read_event(Event& e);
  ReadStatus fail(ReadStatus s, std::int64_t offset, const std::string& what);
  ReadStatus read_frame_event(const char* what, const std::string& expected_channel, Event& e);
  std::string tick_name() const;

  _lcm_eventlog_t* log_{nullptr};
  const msg::DeviceSignals* signals_{nullptr};
  std::string path_;
  std::int64_t file_size_{0};
  std::int64_t next_eventnum_{0};
  std::int64_t ticks_{0};
  bool done_{false};
  ReadStatus last_{ReadStatus::kOk};
  SceneEvent scene_;
  EndEvent end_;
  std::string suffix_, sensor_channel_, actuator_channel_, end_channel_;
  std::string problem_;
  std::int64_t problem_offset_{-1};
};

}  // namespace gyrostab::tools::buslog
