// What `gyrostab replay` (replay.hpp) and `gyrostab replay --resimulate` (resimulate.hpp) share: the bus log
// opened and its scene event checked against the scene the device was built from, the pacing, the exit
// codes and the closing lines.
//
// Exit codes (docs/logs.md, "Exit codes of `gyrostab replay`"):
//   0  every frame identical over the whole log (which ends with its end event)
//   2  nothing replayed: the log cannot be opened, or its scene is refused
//   3  re-simulation: the plant diverged where the recorded run did not
//   4  mismatch: the first differing tick and fields are printed
//   5  the log is truncated or corrupt: the byte offset is printed; the ticks before it replayed identically
#pragma once

#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>

#include "tools/log/bus_log_reader.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

inline constexpr int kReplayExitMismatch = 4;
inline constexpr int kReplayExitBadLog = 5;

class ReplaySession {
 public:
  // Opens req.transport.replay_log; false: the exit code is in `exit_code` and the reason was printed.
  bool open(const LoopConfig& loop, const RunRequest& req, int& exit_code) {
    log_path_ = req.transport.replay_log;
    const buslog::ReadStatus s = reader_.open(log_path_);
    if (s == buslog::ReadStatus::kUnreadable) {
      std::fprintf(stderr, "gyrostab: %s\n", reader_.problem().c_str());
      exit_code = 2;
      return false;
    }
    if (s != buslog::ReadStatus::kOk) {
      std::fprintf(stderr, "gyrostab: %s: %s, nothing replayed: %s\n", log_path_.c_str(), buslog::describe(s),
                   reader_.problem().c_str());
      exit_code = kReplayExitBadLog;
      return false;
    }
    // The scene text is covered by a check sum; the other fields of the scene event must agree with it.
    const buslog::SceneEvent& e = reader_.scene();
    std::string differs;
    if (e.name != loop.name) differs += " name '" + e.name + "' vs '" + loop.name + "';";
    if (e.device != loop.device) differs += " device '" + e.device + "' vs '" + loop.device + "';";
    if (e.seed != loop.seed) differs += " seed " + std::to_string(e.seed) + " vs " + std::to_string(loop.seed) + ";";
    if (e.tick_ns != loop.tick_ns) {
      differs += " tick_ns " + std::to_string(e.tick_ns) + " vs " + std::to_string(loop.tick_ns) + ";";
    }
    if (!differs.empty()) {
      if (!req.transport.replay_scene_override) {
        std::fprintf(stderr, "gyrostab: %s: byte 0: corrupt scene event: its fields disagree with its text:%s\n",
                     log_path_.c_str(), differs.c_str());
        exit_code = kReplayExitBadLog;
        return false;
      }
      std::fprintf(stderr, "gyrostab: %s: note: --scene differs from the recorded scene:%s\n", log_path_.c_str(),
                   differs.c_str());
    }
    real_time_ = req.transport.replay_real_time;
    tick_ns_ = loop.tick_ns;
    clock_gettime(CLOCK_MONOTONIC, &deadline_);
    start_ = std::chrono::steady_clock::now();
    return true;
  }

  buslog::ReadStatus next(buslog::TickRecord& t) {
    if (real_time_) pace();
    return reader_.next(t);
  }

  const buslog::BusLogReader& reader() const { return reader_; }
  const std::string& log_path() const { return log_path_; }
  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  // The line after the last tick: kEnd ⇒ 0, else the log's problem ⇒ kReplayExitBadLog. `what` names the
  // frames compared ("actuator frames").
  int finish(buslog::ReadStatus s, const char* what, std::int64_t ticks) const {
    const double wall = elapsed_s();
    const double rate = wall > 0 ? static_cast<double>(ticks) / wall : 0.0;
    if (s == buslog::ReadStatus::kEnd) {
      std::printf("%s: %lld ticks, every %s identical (%.0f ticks/s); the run ended: %s\n", log_path_.c_str(),
                  static_cast<long long>(ticks), what, rate, reader_.end_event().detail.c_str());
      return 0;
    }
    std::fprintf(stderr, "gyrostab: %s: log %s: %s\n", log_path_.c_str(), buslog::describe(s),
                 reader_.problem().c_str());
    std::fprintf(stderr, "gyrostab: %s: the %lld ticks before it: every %s identical\n", log_path_.c_str(),
                 static_cast<long long>(ticks), what);
    return kReplayExitBadLog;
  }

 private:
  void pace() {
    deadline_.tv_nsec += static_cast<long>(tick_ns_ % 1'000'000'000);
    deadline_.tv_sec += static_cast<time_t>(tick_ns_ / 1'000'000'000);
    if (deadline_.tv_nsec >= 1'000'000'000) {
      deadline_.tv_nsec -= 1'000'000'000;
      ++deadline_.tv_sec;
    }
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline_, nullptr) == EINTR) {
    }
  }

  buslog::BusLogReader reader_;
  std::string log_path_;
  bool real_time_{false};
  std::int64_t tick_ns_{1};
  timespec deadline_{};
  std::chrono::steady_clock::time_point start_;
};

}  // namespace gyrostab::tools
