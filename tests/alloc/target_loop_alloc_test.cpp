// Zero heap allocations in the plant's loop over the target link (`run --transport target`, docs/pil.md),
// counted from its first tick to its last: encoding the sensor frame, writing the FIFO, polling, reading,
// decoding and checking the answer, the statistics and the device's plant code. The controller is the image on
// QEMU's Cortex-M7 (it has no heap at all: the cross build proves it). Skipped where qemu-system-arm or the
// images are missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/alloc_counter.hpp"
#include "tools/commands.hpp"

namespace gyrostab {
namespace {

std::uint64_t g_before = 0, g_after = 0;

// qemu-system-arm on the PATH (looked up directly: no shell).
bool have_qemu() {
  const char* path = std::getenv("PATH");
  std::string rest = path != nullptr ? path : "";
  for (std::size_t at = 0; at <= rest.size();) {
    const std::size_t colon = std::min(rest.find(':', at), rest.size());
    const std::string dir = rest.substr(at, colon - at);
    if (!dir.empty() && std::filesystem::exists(dir + "/qemu-system-arm")) return true;
    at = colon + 1;
  }
  return false;
}

TEST(ZeroAllocation, PlantLoopOverTheTargetLink) {
  if (!have_qemu()) GTEST_SKIP() << "no qemu-system-arm";
  if (!std::filesystem::exists(std::string(GYROSTAB_BINARY_DIR) + "/arm/m7/ship_roll_damper.elf")) {
    GTEST_SKIP() << "no controller images (arm-none-eabi-g++ missing at build time)";
  }
  for (const char* scene : {"ship-roll-damper-active", "power-stabilizer-drive", "gyrocompass-fixed-base-settling"}) {
    tools::RunRequest req;
    req.scene_path = std::string(GYROSTAB_SOURCE_DIR) + "/sim/scenes/" + scene + ".toml";
    req.ticks = 20'000;
    req.write_outputs = false;
    req.progress = false;
    req.role = tools::Role::kPlant;
    req.transport.transport = "target";
    nlohmann::json report;
    req.report_out = &report;
    req.before_loop = [] { g_before = testing::allocations_so_far(); };
    req.after_loop = [] { g_after = testing::allocations_so_far(); };
    ASSERT_EQ(tools::run_scene(req), 0) << scene;
    EXPECT_EQ(report["timing"]["ticks"], 20'000) << scene;
    EXPECT_EQ(report["link"]["target"]["image_ticks"]["stepped"], 20'000) << scene;
    EXPECT_EQ(g_after - g_before, 0u) << scene;
  }
}

}  // namespace
}  // namespace gyrostab
