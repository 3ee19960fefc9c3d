// Lockstep between the plant and controller loops (the two-process LCM mode) reproduces the in-process run
// bit for bit: figures and signals.csv, every shipped scene, 50 000 ticks, over the in-memory bus (no network
// needed; the same over LCM udpm:// is tests/lcm/lcm_lockstep_test.cpp). 2.6 s here, with two fuzzers on the
// machine's two cores: a receive past its deadline no longer waits in the kernel (hil/link/memory_bus.hpp).
#include <gtest/gtest.h>

#include "tests/support/pair_in_threads.hpp"
#include "tests/support/shipped_scenes.hpp"

namespace gyrostab {
namespace lcm_memory_lockstep_test {

TEST(LockstepDeterminism, PlantAndControllerThreadsReproduceTheInProcessRun) {
  const auto scenes = testing::shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    constexpr std::int64_t kTicks = 50'000;
    tools::RunRequest in;
    in.scene_path = path;
    in.ticks = kTicks;
    in.write_outputs = false;
    in.progress = false;
    nlohmann::json report;
    std::string csv;
    in.report_out = &report;
    in.csv_out = &csv;
    const int rc = tools::run_scene(in);
    EXPECT_EQ(rc, 0) << path;
    if (rc != 0) continue;
    const auto r = testing::run_pair_in_threads(path, kTicks);
    EXPECT_EQ(r.plant_rc, 0) << path;
    EXPECT_EQ(r.controller_rc, 0) << path;
    if (r.plant_rc != 0 || r.controller_rc != 0) continue;
    EXPECT_EQ(r.plant_report["figures"].dump(), report["figures"].dump()) << path;
    EXPECT_TRUE(r.csv == csv) << path << ": signals.csv differs";
    EXPECT_FALSE(csv.empty());
  }
}

}  // namespace lcm_memory_lockstep_test
}  // namespace gyrostab
