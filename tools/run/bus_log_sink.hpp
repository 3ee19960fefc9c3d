// `gyrostab run SCENE --log FILE` and `gyrostab plant ... --log FILE`: the loop with its bus recorded as a
// gyrostab bus log (tools/log/bus_log_format.hpp, docs/logs.md). BusLog is the loop's tick sink
// (closed_loop.hpp): per tick it encodes the sensor frame and the actuator frame used for the tick into the
// writer's preallocated buffers and writes two events (no allocation: tests/alloc/bus_log_alloc_test.cpp);
// before each tick it polls SIGINT/SIGTERM (tools/log/stop_signal.hpp), so a signal stops the run at a tick
// boundary and the log is closed whole, with its end event.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "tools/log/bus_log_writer.hpp"
#include "tools/log/stop_signal.hpp"
#include "tools/loop/closed_loop.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

// The scene event of a run: the request's scene text (run_scene fills it when a log is asked for), else the
// scene file read again.
bool scene_event_of(const LoopConfig& loop, const RunRequest& req, buslog::SceneEvent& e, std::string& error);
buslog::EndEvent end_event_of(const LoopOutcome& o, int signo);

struct LoggedRun {
  std::string error;   // the log could not be created or a write failed (exit 3)
  int stop_signal{0};  // the run was stopped by this signal at a tick boundary (exit 128 + signal)
  nlohmann::json summary;  // report.json "log"
};

class BusLog final : public TickSink {
 public:
  // Creates the log with the scene event; false with `error` set.
  bool open(const LoopConfig& loop, const RunRequest& req, std::string& error);
  bool stop_requested() override { return stop_signal_received() != 0; }
  bool record(std::int64_t tick, const msg::AnySensorFrame& s, const msg::AnyActuatorFrame& a) override {
    return writer_.write_tick(tick, s, a);
  }
  // Writes the end event and closes; fills `run` (summary, error).
  void close(const LoopOutcome& outcome, LoggedRun& run, const std::string& detail_override = "");

 private:
  buslog::BusLogWriter writer_;
  std::string path_;
};

}  // namespace gyrostab::tools
