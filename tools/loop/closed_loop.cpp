#include "tools/loop/closed_loop.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>

namespace gyrostab::tools {

namespace {
// The calling thread's CPU time: what the loop itself cost, whatever else the machine ran meanwhile.
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

PlantTick::PlantTick(PlantPort& plant, const LoopConfig& cfg, Recorder* recorder, RowSink* rows)
    : plant_(plant), cfg_(cfg), recorder_(recorder), rows_(rows), applied_(plant.initial_command()) {}

bool PlantTick::step(std::int64_t k, const msg::AnyActuatorFrame& command, LoopOutcome& out) {
  const int latency = cfg_.latency_ticks;
  if (latency == 0) {
    applied_ = command;
  } else {
    pipe_[static_cast<std::size_t>((k + latency) % (kMaxLatencyTicks + 1))] = command;
    if (k >= latency) applied_ = pipe_[static_cast<std::size_t>(k % (kMaxLatencyTicks + 1))];
  }
  out.ticks_run = k + 1;
  if (!plant_.step(k, applied_, out.diverged_state)) {
    out.diverged = true;
    out.diverged_tick = k;
    return false;
  }
  if (recorder_ && recorder_->due(k + 1)) {
    if (double* row = recorder_->row(static_cast<double>(k + 1) * cfg_.tick_s())) {
      plant_.record(row);
      if (rows_ != nullptr) rows_->row(k + 1, recorder_->last_row());
    }
  }
  return true;
}

LoopOutcome run_closed_loop(PlantPort& plant, ControllerPort& controller, const LoopConfig& cfg, Recorder* recorder,
                            bool progress, TickSink* sink, RowSink* rows) {
  LoopOutcome out;
  const std::int64_t ticks = cfg.ticks();
  PlantTick tick(plant, cfg, recorder, rows);
  msg::AnySensorFrame sensor{};
  msg::AnyActuatorFrame command{};
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_s();
  const bool show = progress && isatty(STDERR_FILENO);
  auto last_report = start;
  for (std::int64_t k = 0; k < ticks; ++k) {
    if (sink != nullptr && sink->stop_requested()) {
      out.interrupted = true;
      break;
    }
    plant.sense(k, sensor);
    controller.step(static_cast<std::uint64_t>(k), &sensor, command);
    if (sink != nullptr && !sink->record(k, sensor, command)) {
      out.interrupted = true;
      break;
    }
    if (!tick.step(k, command, out)) break;
    if (show && (k & 0xFFFF) == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_report > std::chrono::seconds(1)) {
        last_report = now;
        std::fprintf(stderr, "\r%s: %5.1f %% of %.0f s simulated", cfg.name.c_str(),
                     100.0 * static_cast<double>(k) / static_cast<double>(ticks), cfg.duration_s);
      }
    }
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.cpu_s = thread_cpu_s() - cpu_start;
  if (show) std::fprintf(stderr, "\r%*s\r", 60, "");
  return out;
}

}  // namespace gyrostab::tools
