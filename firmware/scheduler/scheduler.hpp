// Fixed-step multi-rate scheduler on integer ticks (docs/architecture.md, the loop): task i runs at every
// tick k with k mod period_i == phase_i (0 ≤ phase_i < period_i), in the order the tasks were added; every
// task is bracketed by a PerfCounter (runs, compute min/mean/max, overruns vs its budget, start-to-start
// interval), PX4-style, and so is the whole tick.
//
// Resources: a fixed table of `Capacity` tasks inside the object, no heap, no OS, no locks; the time source
// is injected (`Clock`, see clock.hpp). Pacing (waiting for the next tick) is the caller's business: the
// in-process loop calls run_tick back to back, a real-time runner waits on CLOCK_MONOTONIC deadlines, a
// target waits for its timer interrupt.
//
// Clock reads: one at the start of a tick and one after each task that runs, so a tick with n due tasks
// costs n + 1 reads; a task's compute time includes the (O(Capacity)) due-checks between it and the
// previous due task.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/scheduler/clock.hpp"
#include "firmware/scheduler/perf_counter.hpp"

namespace gyrostab::firmware {

// What a task is: a function of (context, tick). Plain function pointer + context, so a task costs two
// words and needs neither std::function nor virtual dispatch.
using TaskFn = void (*)(void* context, std::uint64_t tick);

struct TaskSpec {
  const char* name{""};           // for reports; must outlive the scheduler (a string literal)
  std::uint32_t period_ticks{1};  // runs every period_ticks ticks (≥ 1) [tick]
  std::uint32_t phase_ticks{0};   // at ticks k with k mod period_ticks == phase_ticks [tick]
  std::int64_t budget_ns{0};      // compute time above which a run counts as an overrun; ≤ 0: none [ns]
  TaskFn run{nullptr};            // the task
  void* context{nullptr};         // passed to run
};

enum class AddStatus : std::uint8_t {
  kOk,
  kTableFull,            // Capacity tasks already added
  kZeroPeriod,           // period_ticks == 0
  kPhaseNotBelowPeriod,  // phase_ticks ≥ period_ticks
  kNoFunction,           // run == nullptr
};

struct AddResult {
  AddStatus status{AddStatus::kOk};
  std::size_t id{0};  // index for task()/counters(), valid when ok()
  constexpr bool ok() const { return status == AddStatus::kOk; }
};

template <std::size_t Capacity, MonotonicClock Clock = NullClock>
class Scheduler {
  static_assert(Capacity > 0, "a scheduler without tasks has nothing to schedule");

 public:
  // `time_source`: the clock (a function-pointer clock must be given, its default is null).
  // `tick_budget_ns`: budget of a whole tick (all due tasks), e.g. the tick period; ≤ 0: none.
  constexpr explicit Scheduler(Clock time_source = Clock{}, std::int64_t tick_budget_ns = 0)
      : clock_(time_source), tick_budget_ns_(tick_budget_ns) {}

  // Adds a task at the end of the table (it runs after the tasks added before it in the same tick). O(1).
  [[nodiscard]] constexpr AddResult add(const TaskSpec& spec) {
    if (spec.run == nullptr) return {AddStatus::kNoFunction, 0};
    if (spec.period_ticks == 0) return {AddStatus::kZeroPeriod, 0};
    if (spec.phase_ticks >= spec.period_ticks) return {AddStatus::kPhaseNotBelowPeriod, 0};
    if (size_ == Capacity) return {AddStatus::kTableFull, 0};
    tasks_[size_] = spec;
    counters_[size_] = PerfCounter{};
    return {AddStatus::kOk, size_++};
  }

  // Adds `object.*Method(tick)` as a task, e.g. add_member<&Controller::step>("control", 1, 0, 200'000, c).
  template <auto Method, class T>
  [[nodiscard]] constexpr AddResult add_member(const char* name, std::uint32_t period_ticks,
                                               std::uint32_t phase_ticks, std::int64_t budget_ns, T& object) {
    return add({name, period_ticks, phase_ticks, budget_ns, &call_member<Method, T>, &object});
  }

  // Runs every task due at `tick`, in table order, and updates the counters. Ticks normally advance by one;
  // a gap is counted in ticks_skipped(), a repeated or earlier tick in ticks_repeated() (its tasks run
  // again). O(Capacity) time (one 64-bit modulo per task), O(1) stack.
  constexpr void run_tick(std::uint64_t tick) {
    if (ticks_run_ > 0) {
      if (tick > last_tick_ + 1) ticks_skipped_ += tick - last_tick_ - 1;
      if (tick <= last_tick_) ++ticks_repeated_;
    }
    last_tick_ = tick;
    ++ticks_run_;

    const std::int64_t tick_start = clock_();
    std::int64_t task_start = tick_start;
    for (std::size_t i = 0; i < size_; ++i) {
      const TaskSpec& t = tasks_[i];
      if (tick % t.period_ticks != t.phase_ticks) continue;
      t.run(t.context, tick);
      const std::int64_t task_end = clock_();
      counters_[i].record(task_start, task_end - task_start, t.budget_ns);
      task_start = task_end;
    }
    tick_counter_.record(tick_start, task_start - tick_start, tick_budget_ns_);
  }

  // Whether the task `id` runs at `tick` (the rule run_tick applies). O(1).
  constexpr bool due(std::size_t id, std::uint64_t tick) const {
    return tick % tasks_[id].period_ticks == tasks_[id].phase_ticks;
  }

  constexpr std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return Capacity; }
  constexpr const TaskSpec& task(std::size_t id) const { return tasks_[id]; }
  constexpr const PerfCounter& counters(std::size_t id) const { return counters_[id]; }
  constexpr const PerfCounter& tick_counters() const { return tick_counter_; }  // whole ticks
  constexpr std::uint64_t ticks_run() const { return ticks_run_; }
  constexpr std::uint64_t ticks_skipped() const { return ticks_skipped_; }
  constexpr std::uint64_t ticks_repeated() const { return ticks_repeated_; }
  constexpr Clock& clock() { return clock_; }

  // Zeroes every counter (e.g. after a warm-up); the task table stays.
  constexpr void reset_counters() {
    for (PerfCounter& c : counters_) c = PerfCounter{};
    tick_counter_ = PerfCounter{};
    ticks_run_ = ticks_skipped_ = ticks_repeated_ = 0;
    last_tick_ = 0;
  }

 private:
  template <auto Method, class T>
  static void call_member(void* context, std::uint64_t tick) {
    (static_cast<T*>(context)->*Method)(tick);
  }

  Clock clock_;
  std::int64_t tick_budget_ns_{0};
  std::array<TaskSpec, Capacity> tasks_{};
  std::array<PerfCounter, Capacity> counters_{};
  PerfCounter tick_counter_{};
  std::size_t size_{0};
  std::uint64_t last_tick_{0};
  std::uint64_t ticks_run_{0};
  std::uint64_t ticks_skipped_{0};
  std::uint64_t ticks_repeated_{0};
};

}  // namespace gyrostab::firmware
