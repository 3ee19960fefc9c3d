// The scheduler (firmware/scheduler/): every task runs at exactly its ticks, phases respected, in table
// order; its counters are exact against a fake clock the tasks advance by known amounts; overruns are
// counted. Expected values are built independently of the scheduler's modulo rule (by stepping phase +
// n·period).
#include "firmware/scheduler/scheduler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gyrostab::firmware {
namespace scheduler_test {

// A clock the test (and the tasks) move by hand [ns].
struct FakeClock {
  std::int64_t now_ns{0};
};
struct FakeClockRef {
  FakeClock* clock{nullptr};
  std::int64_t operator()() const { return clock->now_ns; }
};
static_assert(MonotonicClock<FakeClockRef>);
static_assert(MonotonicClock<std::int64_t (*)()>);
static_assert(MonotonicClock<posix::MonotonicClock>);

using Log = std::vector<std::pair<std::uint64_t, std::size_t>>;  // (tick, task id) in run order

struct Recorder {
  Log* log{nullptr};
  std::size_t id{0};
  void run(std::uint64_t tick) { log->emplace_back(tick, id); }
};

TEST(Scheduler, EveryTaskRunsAtExactlyItsTicksAndPhasesOver10kTicks) {
  struct Rate {
    std::uint32_t period, phase;
  };
  const std::vector<Rate> rates{{1, 0}, {2, 1}, {5, 3}, {10, 7}, {7, 0}, {1000, 999}, {3, 2}};
  constexpr std::uint64_t kTicks = 10'000;

  Log log;
  std::vector<Recorder> recorders(rates.size());
  Scheduler<8> s;
  for (std::size_t i = 0; i < rates.size(); ++i) {
    recorders[i] = {&log, i};
    const AddResult r = s.add_member<&Recorder::run>("t", rates[i].period, rates[i].phase, 0, recorders[i]);
    ASSERT_TRUE(r.ok());
    ASSERT_EQ(r.id, i);
  }
  for (std::uint64_t k = 0; k < kTicks; ++k) s.run_tick(k);

  // Expected: task i at phase_i, phase_i + period_i, ...; within a tick in table order, i.e. (tick, id)
  // sorted.
  Log expected;
  for (std::size_t i = 0; i < rates.size(); ++i) {
    for (std::uint64_t k = rates[i].phase; k < kTicks; k += rates[i].period) expected.emplace_back(k, i);
  }
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(log, expected);

  for (std::size_t i = 0; i < rates.size(); ++i) {
    const std::uint64_t runs = (kTicks - rates[i].phase + rates[i].period - 1) / rates[i].period;
    EXPECT_EQ(s.counters(i).runs, runs) << "task " << i;
  }
  EXPECT_EQ(s.counters(5).runs, 10u);  // period 1000, phase 999: ticks 999, 1999, ..., 9999
  EXPECT_EQ(s.ticks_run(), kTicks);
  EXPECT_EQ(s.ticks_skipped(), 0u);
  EXPECT_EQ(s.ticks_repeated(), 0u);
}

// Task A costs 100 + (37 k mod 50) ns at tick k, task B 10 ns, and 1000 ns pass between ticks (the wait for
// the timer): every counter then has an exact expected value.
struct CostedTask {
  FakeClock* clock{nullptr};
  bool variable{false};
  static std::int64_t cost_a(std::uint64_t k) { return 100 + static_cast<std::int64_t>((37 * k) % 50); }
  void run(std::uint64_t tick) { clock->now_ns += variable ? cost_a(tick) : 10; }
};

TEST(Scheduler, CountersAreExactWithAFakeClock) {
  FakeClock clock;
  CostedTask a{&clock, true}, b{&clock, false};
  constexpr std::int64_t kBudgetA = 140, kTickBudget = 150, kIdleNs = 1000;
  Scheduler<2, FakeClockRef> s{FakeClockRef{&clock}, kTickBudget};
  const AddResult ra = s.add_member<&CostedTask::run>("a", 1, 0, kBudgetA, a);
  const AddResult rb = s.add_member<&CostedTask::run>("b", 1, 0, 0, b);
  ASSERT_TRUE(ra.ok() && rb.ok());

  constexpr std::uint64_t kTicks = 1000;
  std::int64_t sum = 0, mn = std::numeric_limits<std::int64_t>::max(), mx = 0;
  std::uint64_t overruns = 0, tick_overruns = 0;
  std::int64_t interval_min = std::numeric_limits<std::int64_t>::max(), interval_max = 0;
  for (std::uint64_t k = 0; k < kTicks; ++k) {
    s.run_tick(k);
    clock.now_ns += kIdleNs;
    const std::int64_t c = CostedTask::cost_a(k);
    sum += c;
    mn = std::min(mn, c);
    mx = std::max(mx, c);
    if (c > kBudgetA) ++overruns;
    if (c + 10 > kTickBudget) ++tick_overruns;
    if (k > 0) {  // A starts each tick; start-to-start = previous tick's A + B + idle
      const std::int64_t interval = CostedTask::cost_a(k - 1) + 10 + kIdleNs;
      interval_min = std::min(interval_min, interval);
      interval_max = std::max(interval_max, interval);
    }
  }
  const PerfCounter& ca = s.counters(ra.id);
  EXPECT_EQ(ca.runs, kTicks);
  EXPECT_EQ(ca.total_ns, sum);
  EXPECT_EQ(ca.min_ns, mn);
  EXPECT_EQ(ca.max_ns, mx);
  EXPECT_EQ(ca.mean_ns(), sum / static_cast<std::int64_t>(kTicks));
  EXPECT_EQ(ca.last_ns, CostedTask::cost_a(kTicks - 1));
  EXPECT_EQ(ca.overruns, overruns);
  EXPECT_GT(overruns, 0u);  // the budget sits inside the cost range, so both branches are exercised
  EXPECT_LT(overruns, kTicks);
  EXPECT_EQ(ca.interval_min_ns, interval_min);
  EXPECT_EQ(ca.interval_max_ns, interval_max);

  const PerfCounter& cb = s.counters(rb.id);
  EXPECT_EQ(cb.runs, kTicks);
  EXPECT_EQ(cb.min_ns, 10);
  EXPECT_EQ(cb.max_ns, 10);
  EXPECT_EQ(cb.mean_ns(), 10);
  EXPECT_EQ(cb.overruns, 0u);  // no budget

  const PerfCounter& ct = s.tick_counters();
  EXPECT_EQ(ct.runs, kTicks);
  EXPECT_EQ(ct.total_ns, sum + 10 * static_cast<std::int64_t>(kTicks));
  EXPECT_EQ(ct.min_ns, mn + 10);
  EXPECT_EQ(ct.max_ns, mx + 10);
  EXPECT_EQ(ct.overruns, tick_overruns);
  EXPECT_EQ(ct.interval_min_ns, interval_min);  // a tick starts with A
}

// A run exactly at the budget is not an overrun; one nanosecond more is.
TEST(Scheduler, OverrunMeansComputeTimeAboveTheBudget) {
  FakeClock clock;
  struct Task {
    FakeClock* clock;
    void run(std::uint64_t tick) { clock->now_ns += (tick % 4 == 3) ? 501 : 500; }
  } task{&clock};
  Scheduler<1, FakeClockRef> s{FakeClockRef{&clock}};
  ASSERT_TRUE(s.add_member<&Task::run>("t", 1, 0, 500, task).ok());
  for (std::uint64_t k = 0; k < 400; ++k) s.run_tick(k);
  EXPECT_EQ(s.counters(0).overruns, 100u);
  EXPECT_EQ(s.counters(0).max_ns, 501);
  EXPECT_EQ(s.counters(0).min_ns, 500);
  EXPECT_EQ(s.tick_counters().overruns, 0u);  // no tick budget given
}

TEST(Scheduler, TasksNotDueDoNotRunAndAreNotTimed) {
  FakeClock clock;
  CostedTask slow{&clock, false};
  Scheduler<1, FakeClockRef> s{FakeClockRef{&clock}};
  ASSERT_TRUE(s.add_member<&CostedTask::run>("every 4th", 4, 1, 0, slow).ok());
  for (std::uint64_t k = 0; k < 8; ++k) s.run_tick(k);
  EXPECT_EQ(s.counters(0).runs, 2u);  // ticks 1 and 5
  EXPECT_EQ(s.counters(0).total_ns, 20);
  EXPECT_EQ(s.tick_counters().runs, 8u);   // every tick is counted
  EXPECT_EQ(s.tick_counters().min_ns, 0);  // ticks without due tasks cost nothing on the fake clock
  EXPECT_EQ(s.tick_counters().max_ns, 10);
  EXPECT_EQ(s.counters(0).interval_min_ns, 10);  // start at 1: 0 ns, start at 5: after one 10 ns run
}

TEST(Scheduler, AddRefusesBadTasksAndAFullTable) {
  Scheduler<2> s;
  const TaskFn fn = [](void*, std::uint64_t) {};
  EXPECT_EQ(s.add({"zero period", 0, 0, 0, fn, nullptr}).status, AddStatus::kZeroPeriod);
  EXPECT_EQ(s.add({"phase = period", 4, 4, 0, fn, nullptr}).status, AddStatus::kPhaseNotBelowPeriod);
  EXPECT_EQ(s.add({"phase > period", 4, 9, 0, fn, nullptr}).status, AddStatus::kPhaseNotBelowPeriod);
  EXPECT_EQ(s.add({"no function", 1, 0, 0, nullptr, nullptr}).status, AddStatus::kNoFunction);
  EXPECT_EQ(s.size(), 0u);
  EXPECT_TRUE(s.add({"a", 4, 3, 0, fn, nullptr}).ok());
  const AddResult b = s.add({"b", 1, 0, 0, fn, nullptr});
  EXPECT_TRUE(b.ok());
  EXPECT_EQ(b.id, 1u);
  EXPECT_EQ(s.add({"c", 1, 0, 0, fn, nullptr}).status, AddStatus::kTableFull);
  EXPECT_EQ(s.size(), 2u);
  EXPECT_STREQ(s.task(1).name, "b");
  EXPECT_EQ(s.capacity(), 2u);
}

TEST(Scheduler, TaskDueOnTickNumberEvenWhenTicksAreSkippedOrRepeated) {
  Log log;
  Recorder r{&log, 0};
  Scheduler<1> s;
  ASSERT_TRUE(s.add_member<&Recorder::run>("t", 3, 2, 0, r).ok());
  for (std::uint64_t k : {0u, 1u, 2u, 5u, 5u, 6u, 8u}) s.run_tick(k);
  const Log expected{{2, 0}, {5, 0}, {5, 0}, {8, 0}};
  EXPECT_EQ(log, expected);
  EXPECT_EQ(s.ticks_skipped(), 3u);   // 3, 4 and 7
  EXPECT_EQ(s.ticks_repeated(), 1u);  // the second 5
  EXPECT_EQ(s.ticks_run(), 7u);
  EXPECT_TRUE(s.due(0, 11));
  EXPECT_FALSE(s.due(0, 12));
}

std::int64_t g_function_clock_ns = 0;
std::int64_t function_clock() {
  return g_function_clock_ns;
}

TEST(Scheduler, AcceptsAPlainFunctionPointerClock) {
  Scheduler<1, std::int64_t (*)()> s{&function_clock};
  const TaskFn fn = [](void*, std::uint64_t) { g_function_clock_ns += 250; };
  ASSERT_TRUE(s.add({"t", 2, 0, 200, fn, nullptr}).ok());
  for (std::uint64_t k = 0; k < 10; ++k) s.run_tick(k);
  EXPECT_EQ(s.counters(0).runs, 5u);
  EXPECT_EQ(s.counters(0).total_ns, 1250);
  EXPECT_EQ(s.counters(0).overruns, 5u);
  EXPECT_EQ(s.counters(0).interval_min_ns, 250);
}

TEST(Scheduler, NullClockCountsRunsWithZeroTimes) {
  Log log;
  Recorder r{&log, 0};
  Scheduler<1> s;  // NullClock
  ASSERT_TRUE(s.add_member<&Recorder::run>("t", 1, 0, 1, r).ok());
  for (std::uint64_t k = 0; k < 100; ++k) s.run_tick(k);
  EXPECT_EQ(s.counters(0).runs, 100u);
  EXPECT_EQ(s.counters(0).max_ns, 0);
  EXPECT_EQ(s.counters(0).overruns, 0u);
}

TEST(Scheduler, ResetCountersKeepsTheTable) {
  Log log;
  Recorder r{&log, 0};
  Scheduler<1> s;
  ASSERT_TRUE(s.add_member<&Recorder::run>("t", 2, 1, 0, r).ok());
  for (std::uint64_t k = 0; k < 10; ++k) s.run_tick(k);
  s.reset_counters();
  EXPECT_EQ(s.counters(0).runs, 0u);
  EXPECT_EQ(s.ticks_run(), 0u);
  for (std::uint64_t k = 10; k < 20; ++k) s.run_tick(k);
  EXPECT_EQ(s.counters(0).runs, 5u);
  EXPECT_EQ(s.ticks_skipped(), 0u);  // tick 10 after a reset is not a gap
  EXPECT_EQ(s.size(), 1u);
}

// The host clock only has to be usable and monotonic here; its values are not asserted (docs/architecture.md,
// tests: compute
// time is measured by benchmarks, not asserted against the wall clock).
TEST(Scheduler, PosixMonotonicClockNeverGoesBackwards) {
  posix::MonotonicClock clock;
  std::int64_t previous = clock();
  for (int i = 0; i < 1000; ++i) {
    const std::int64_t now = clock();
    ASSERT_GE(now, previous);
    previous = now;
  }
  Scheduler<1, posix::MonotonicClock> s;
  const TaskFn fn = [](void*, std::uint64_t) {};
  ASSERT_TRUE(s.add({"t", 1, 0, 0, fn, nullptr}).ok());
  for (std::uint64_t k = 0; k < 100; ++k) s.run_tick(k);
  EXPECT_EQ(s.counters(0).runs, 100u);
  EXPECT_LE(s.counters(0).min_ns, s.counters(0).mean_ns());
  EXPECT_LE(s.counters(0).mean_ns(), s.counters(0).max_ns);
  EXPECT_GE(s.counters(0).min_ns, 0);
}

TEST(Scheduler, RunTickAllocatesNothing) {
  FakeClock clock;
  CostedTask a{&clock, true}, b{&clock, false};
  Scheduler<4, FakeClockRef> s{FakeClockRef{&clock}, 100};
  ASSERT_TRUE(s.add_member<&CostedTask::run>("a", 1, 0, 120, a).ok());
  ASSERT_TRUE(s.add_member<&CostedTask::run>("b", 10, 3, 0, b).ok());
  gyrostab::testing::AllocationCounter allocations;
  for (std::uint64_t k = 0; k < 100'000; ++k) s.run_tick(k);
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(s.counters(1).runs, 10'000u);
}

}  // namespace scheduler_test
}  // namespace gyrostab::firmware
