// Allocations over LCM udpm:// itself: the plant and controller loops as two threads of this process, each
// with its own lcm_t, from their first tick to their last. The loop threads (ppoll, lcm_handle dispatching
// into a preallocated buffer, lcm_publish) must not allocate at all. LCM's own receive threads may
// (docs/transport.md): on LCM 1.3.1 they do a few dozen times around the first message of each channel (GLib
// regex and handler tables, seen with gdb), never per tick — the process-wide count must not grow with the
// run.
#include <gtest/gtest.h>

#include <atomic>

#include "tests/lcm/lcm_test_support.hpp"
#include "tests/support/alloc_counter.hpp"
#include "tests/support/pair_in_threads.hpp"

namespace gyrostab::testing {
namespace {

TwoThreadBarrier g_barrier;
std::uint64_t g_before = 0, g_after = 0;

std::uint64_t g_thread_before[2], g_thread_after[2];
std::atomic<int> g_slot{0};
thread_local int t_slot = -1;

struct Counts {
  std::uint64_t process{0};
  std::uint64_t loop_threads[2]{};
};

void before_hook() {
  t_slot = g_slot.fetch_add(1);
  g_thread_before[t_slot] = allocations_on_this_thread();
  g_barrier.meet([] { g_before = allocations_so_far(); });
}
void after_hook() {
  g_thread_after[t_slot] = allocations_on_this_thread();
  g_barrier.meet([] { g_after = allocations_so_far(); });
}

Counts allocations_in_run(std::int64_t ticks) {
  g_slot = 0;
  const auto r = run_pair_in_threads(scene("monorail.toml"), ticks, before_hook, after_hook,
                                     "_alloc" + std::to_string(ticks));
  EXPECT_EQ(r.plant_rc, 0);
  EXPECT_EQ(r.controller_rc, 0);
  EXPECT_EQ(r.plant_report["link"]["transport"], "lcm");
  EXPECT_EQ(r.plant_report["timing"]["ticks"], ticks);
  Counts c;
  c.process = g_after - g_before;
  for (int i = 0; i < 2; ++i) c.loop_threads[i] = g_thread_after[i] - g_thread_before[i];
  return c;
}

TEST(LcmAllocation, LoopThreadsNeverAllocateAndLcmsReceiveThreadsNotPerTick) {
  const Counts short_run = allocations_in_run(2'000);
  const Counts long_run = allocations_in_run(20'000);
  std::printf(
      "allocations from tick 0 to the end: loop threads %llu + %llu, whole process %llu (2000 ticks), "
      "%llu (20000 ticks)\n",
      static_cast<unsigned long long>(long_run.loop_threads[0]),
      static_cast<unsigned long long>(long_run.loop_threads[1]),
      static_cast<unsigned long long>(short_run.process), static_cast<unsigned long long>(long_run.process));
  for (const Counts& c : {short_run, long_run}) {
    EXPECT_EQ(c.loop_threads[0], 0u);
    EXPECT_EQ(c.loop_threads[1], 0u);
  }
  // LCM's receive threads: a few dozen around the first messages of each channel (how many fall after the
  // loops' first tick depends on thread timing: 26-38 seen), never per tick — one per tick would be ≥ 20000.
  EXPECT_LT(short_run.process, 100u);
  EXPECT_LT(long_run.process, 100u) << "allocations grow with the number of ticks";
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_LCM_TEST_MAIN()
