#include "tools/run/bus_log_sink.hpp"

#include <fstream>
#include <sstream>

namespace gyrostab::tools {

bool scene_event_of(const LoopConfig& loop, const RunRequest& req, buslog::SceneEvent& e, std::string& error) {
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

buslog::EndEvent end_event_of(const LoopOutcome& o, int signo) {
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

bool BusLog::open(const LoopConfig& loop, const RunRequest& req, std::string& error) {
  buslog::SceneEvent scene;
  path_ = req.transport.log_path;
  return scene_event_of(loop, req, scene, error) &&
         writer_.open(req.transport.log_path, scene, req.transport.channel_suffix, error);
}

void BusLog::close(const LoopOutcome& outcome, LoggedRun& run, const std::string& detail_override) {
  const bool write_failed = writer_.failed();
  buslog::EndEvent end = end_event_of(outcome, run.stop_signal);
  if (!detail_override.empty()) {
    end.reason = buslog::EndReason::kOther;
    end.detail = detail_override;
  }
  std::string close_error;
  if (!writer_.close(end, close_error)) run.error = close_error;
  if (write_failed && run.error.empty()) run.error = "bus log " + path_ + ": a write failed";
  run.summary = {{"path", path_},
                 {"events", writer_.events_written()},
                 {"ticks", outcome.ticks_run},
                 {"complete", run.error.empty()},
                 {"end", end.detail}};
}

}  // namespace gyrostab::tools
