// Zero heap allocations over 1e6 closed-loop ticks (plant, sensors, sea, firmware controller, recorder)
// for every shipped scene, counted from the first tick to the last; a scene driven by a motion record runs to
// the record's end instead (a run past it is refused: the record is not extrapolated).
#include <gtest/gtest.h>

#include "tests/support/alloc_counter.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/commands.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab {
namespace {

std::uint64_t g_before = 0, g_after = 0;

std::int64_t ticks_for(const std::string& path) {
  constexpr std::int64_t kTicks = 1'000'000;
  tools::SceneReader r;
  if (!r.open(path)) return kTicks;
  const auto scene = tools::read_device_scene(r);
  const motion::SceneBaseMotion* m = scene ? scene->base_motion() : nullptr;
  if (m == nullptr || m->kind != motion::BaseMotionKind::kRecorded) return kTicks;
  return std::min(kTicks, static_cast<std::int64_t>(m->recorded.record()->t.back() / scene->loop().tick_s()));
}

TEST(ZeroAllocation, EveryShippedSceneOverAMillionTicks) {
  const auto scenes = testing::shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    tools::RunRequest req;
    req.scene_path = path;
    req.ticks = ticks_for(path);
    req.write_outputs = false;
    req.progress = false;
    req.before_loop = [] { g_before = testing::allocations_so_far(); };
    req.after_loop = [] { g_after = testing::allocations_so_far(); };
    nlohmann::json report;
    req.report_out = &report;
    ASSERT_EQ(tools::run_scene(req), 0) << path;
    EXPECT_GE(report["timing"]["ticks"].get<std::int64_t>(), std::min<std::int64_t>(req.ticks, 1'000'000)) << path;
    EXPECT_GE(req.ticks, 50'000) << path;
    EXPECT_EQ(g_after - g_before, 0u) << path;
  }
}

}  // namespace
}  // namespace gyrostab
