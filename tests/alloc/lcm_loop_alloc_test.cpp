// Zero heap allocations in the plant and controller loops of the two-process (LCM) mode, counted over
// both loops from their first tick to their last for every shipped scene: encode, publish, receive, decode,
// the frame checks, the statistics and the device code. The transport is the in-memory bus (the loops' code
// is the same over LCM; LCM's own receive thread may allocate and is kept off the loop thread, see
// docs/transport.md and tests/lcm/lcm_link_alloc_test.cpp).
#include <gtest/gtest.h>

#include "tests/support/alloc_counter.hpp"
#include "tests/support/pair_in_threads.hpp"
#include "tests/support/shipped_scenes.hpp"

namespace gyrostab {
namespace {

testing::TwoThreadBarrier g_barrier;
std::uint64_t g_before = 0, g_after = 0;

TEST(ZeroAllocation, PlantAndControllerLoopsOverTheMemoryBusForEveryShippedScene) {
  const auto scenes = testing::shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    const auto r = testing::run_pair_in_threads(
        path, 20'000, [] { g_barrier.meet([] { g_before = testing::allocations_so_far(); }); },
        [] { g_barrier.meet([] { g_after = testing::allocations_so_far(); }); });
    EXPECT_EQ(r.plant_rc, 0) << path;
    EXPECT_EQ(r.controller_rc, 0) << path;
    if (r.plant_rc != 0 || r.controller_rc != 0) continue;
    EXPECT_EQ(r.plant_report["timing"]["ticks"], 20'000) << path;
    EXPECT_EQ(r.controller_report["link"]["counters"]["accepted"], 20'000) << path;
    EXPECT_EQ(g_after - g_before, 0u) << path;
  }
}

}  // namespace
}  // namespace gyrostab
