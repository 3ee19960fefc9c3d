// Zero heap allocations on the loop's thread over the ticks of a run with the live view and the MCAP file's
// frames (`gyrostab run SCENE --view --mcap FILE --mcap-frames-every 1`): for every shipped scene the loop hands
// each recorded row to the view's feed, which pushes it into the ring allocated before tick 0, and every tick's
// frames to the frame table (tools/run/frame_table.hpp), sized before tick 0; the server's own thread (which
// allocates as it serves) is not the loop's, so the count is the loop thread's alone.
#include <gtest/gtest.h>

#include "tests/support/alloc_counter.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/commands.hpp"

namespace gyrostab {
namespace {

std::uint64_t g_before = 0, g_after = 0;

TEST(ZeroAllocation, LoopWithTheLiveViewAndTheFrameTableOfEveryShippedScene) {
  const auto scenes = testing::shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    tools::RunRequest req;
    req.scene_path = path;
    req.ticks = 20'000;
    req.write_outputs = false;
    req.progress = false;
    req.view.enabled = true;
    req.view.linger_s = 0;
    req.mcap_frames_csv = true;  // keep the frames as for an MCAP file (written with the outputs: none here)
    req.mcap_frames_every = 1;
    req.before_loop = [] { g_before = testing::allocations_on_this_thread(); };
    req.after_loop = [] { g_after = testing::allocations_on_this_thread(); };
    nlohmann::json report;
    req.report_out = &report;
    ASSERT_EQ(tools::run_scene(req), 0) << path;
    EXPECT_EQ(report["timing"]["ticks"].get<std::int64_t>(), 20'000) << path;
    EXPECT_EQ(g_after - g_before, 0u) << path;
  }
}

}  // namespace
}  // namespace gyrostab
