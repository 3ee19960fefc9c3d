// Zero heap allocations over the ticks of a logging run (`gyrostab run SCENE --log FILE`): for every shipped
// scene, the loop with the bus log as its tick sink — two frames encoded into preallocated buffers and two LCM
// events written per tick, through a stream buffer set at open() — allocates nothing from the first tick to
// the last. 20 000 ticks write ~7 MB per scene, so the stream buffer is flushed to the file ~27 times.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/alloc_counter.hpp"
#include "tests/support/bus_log_fixtures.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/commands.hpp"

namespace gyrostab {
namespace {

std::uint64_t g_before = 0, g_after = 0;

TEST(ZeroAllocation, LoggingLoopOfEveryShippedScene) {
  const auto scenes = testing::shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    testing::ScratchDir dir("alloc");
    const std::string log = dir.file("run.lcmlog");
    tools::RunRequest req;
    req.scene_path = path;
    req.ticks = 20'000;
    req.write_outputs = false;
    req.progress = false;
    req.transport.log_path = log;
    req.before_loop = [] { g_before = testing::allocations_so_far(); };
    req.after_loop = [] { g_after = testing::allocations_so_far(); };
    nlohmann::json report;
    req.report_out = &report;
    ASSERT_EQ(tools::run_scene(req), 0) << path;
    EXPECT_EQ(report["timing"]["ticks"].get<std::int64_t>(), 20'000) << path;
    EXPECT_GT(std::filesystem::file_size(log), 20'000u * 2 * (28 + 15 + 88)) << path << ": the log was written";
    EXPECT_EQ(g_after - g_before, 0u) << path;
  }
}

}  // namespace
}  // namespace gyrostab
