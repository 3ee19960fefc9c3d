// `gyrostab run SCENE --log FILE`: the in-process loop with its bus recorded as a gyrostab bus log
// (tools/log/bus_log_format.hpp, docs/logs.md). BusLogSink is run_closed_loop's tick sink (closed_loop.hpp):
// per tick it encodes the sensor frame and the controller's actuator frame into the writer's preallocated
// buffers and writes two events (no allocation: tests/alloc/bus_log_alloc_test.cpp); before each tick it
// polls SIGINT/SIGTERM (tools/log/stop_signal.hpp), so a signal stops the run at a tick boundary and the log
// is closed whole, with its end event. The LCM plant process hooks the same sink into its loop.
#pragma once

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tools/log/bus_log_writer.hpp"
#include "tools/log/stop_signal.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

struct BusLogSink {
  static constexpr bool kActive = true;
  buslog::BusLogWriter* writer;
  bool stop_requested() { return stop_signal_received() != 0; }
  bool record(std::int64_t tick, const msg::SensorFrame& s, const msg::ActuatorFrame& a) {
    return writer->write_tick(tick, s, a);
  }
};

// The scene event of a run: the request's scene text (run_scene fills it when a log is asked for), else the
// scene file read again.
inline bool scene_event_of(const LoopConfig& loop, const RunRequest& req, buslog::SceneEvent& e, std::string& error) {
  e.name = loop.name;
  e.device = loop.device;
  e.seed = loop.seed;
  e.tick_ns = loop.tick_ns;
  e.source = req.scene_path;
  e.toml = req.scene_text;
  if (e.toml.empty()) {
    std::ifstream f(req.scene_path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    if (!f) {
      error = "cannot read " + req.scene_path + " for the bus log's scene event";
      return false;
    }
    e.toml = s.str();
  }
  return true;
}

inline buslog::EndEvent end_event_of(const LoopOutcome& o, int signo) {
  buslog::EndEvent e;
  e.ticks = o.ticks_run;
  if (o.interrupted && signo != 0) {
    e.reason = buslog::EndReason::kSignal;
    e.signal = signo;
    e.detail = std::string("stopped by ") + signal_name(signo) + " after tick " + std::to_string(o.ticks_run - 1);
  } else if (o.diverged) {
    e.reason = buslog::EndReason::kDiverged;
    e.detail = "the plant state became non-finite at tick " + std::to_string(o.diverged_tick);
  } else if (o.interrupted) {
    e.reason = buslog::EndReason::kOther;
    e.detail = "stopped after tick " + std::to_string(o.ticks_run - 1);
  } else {
    e.detail = "completed";
  }
  return e;
}

struct LoggedRun {
  bool started{false};  // the log was created and the loop ran
  std::string error;   // the log could not be created or a write failed (exit 3)
  int stop_signal{0};  // the run was stopped by this signal at a tick boundary (exit 128 + signal)
  nlohmann::json summary;  // report.json "log"
};

// The loop of run_requested with the bus log of req.transport.log_path. On a log that cannot be created, the
// loop does not run (result.error set, outcome.ticks_run = 0).
template <class Device>
LoopOutcome run_logged(Device& device, const LoopConfig& loop, Recorder& rec, const RunRequest& req,
                       LoggedRun& result) {
  buslog::SceneEvent scene;
  buslog::BusLogWriter writer;
  if (!scene_event_of(loop, req, scene, result.error) ||
      !writer.open(req.transport.log_path, scene, req.transport.channel_suffix, result.error)) {
    return LoopOutcome{};
  }
  result.started = true;
  LoopOutcome outcome;
  {
    StopSignalGuard guard;
    BusLogSink sink{&writer};
    outcome = run_requested(device, loop, rec, req, &sink);
    if (outcome.interrupted) result.stop_signal = stop_signal_received();
  }
  const bool write_failed = writer.failed();
  std::string close_error;
  const buslog::EndEvent end = end_event_of(outcome, result.stop_signal);
  if (!writer.close(end, close_error)) result.error = close_error;
  result.summary = {{"path", req.transport.log_path},
                    {"events", writer.events_written()},
                    {"ticks", outcome.ticks_run},
                    {"complete", result.error.empty()},
                    {"end", end.detail}};
  if (write_failed && result.error.empty()) result.error = "bus log " + req.transport.log_path + ": a write failed";
  return outcome;
}

}  // namespace gyrostab::tools
