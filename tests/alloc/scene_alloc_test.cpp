// Zero heap allocations over 1e6 closed-loop ticks (plant, sensors, sea, firmware controller, recorder)
// for every shipped scene, counted from the first tick to the last.
#include <gtest/gtest.h>

#include "tests/support/alloc_counter.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/commands.hpp"

namespace gyrostab {
namespace {

std::uint64_t g_before = 0, g_after = 0;

TEST(ZeroAllocation, EveryShippedSceneOverAMillionTicks) {
  const auto scenes = testing::shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    tools::RunRequest req;
    req.scene_path = path;
    req.ticks = 1'000'000;
    req.write_outputs = false;
    req.progress = false;
    req.before_loop = [] { g_before = testing::allocations_so_far(); };
    req.after_loop = [] { g_after = testing::allocations_so_far(); };
    nlohmann::json report;
    req.report_out = &report;
    ASSERT_EQ(tools::run_scene(req), 0) << path;
    EXPECT_GE(report["timing"]["ticks"].get<std::int64_t>(), 1'000'000) << path;
    EXPECT_EQ(g_after - g_before, 0u) << path;
  }
}

}  // namespace
}  // namespace gyrostab
