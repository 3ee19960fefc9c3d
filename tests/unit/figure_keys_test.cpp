// Every figure a shipped scene reports (report.json "figures") is declared in its device's signal table
// ([[figure]]), so the figure documentation generated from the tables (docs/icd/<device>.md) names every key a
// user finds in a report. Each scene runs 400 ticks in process: which keys a device reports depends on the
// scene's options, not on the run's length.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "gyrostab_signals/all_outputs.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/commands.hpp"

namespace gyrostab {
namespace figure_keys_test {

const tools::DeviceOutputs* outputs_of(const std::string& device) {
  for (const tools::NamedDeviceOutputs& d : tools::kAllDeviceOutputs)
    if (d.device == device) return d.outputs;
  return nullptr;
}

TEST(FigureKeys, EveryReportedFigureIsDeclaredInTheDevicesTable) {
  int scenes = 0, keys = 0;
  for (const auto& path : testing::shipped_scenes()) {
    tools::RunRequest req;
    req.scene_path = path;
    req.ticks = 400;
    req.write_outputs = false;
    req.progress = false;
    nlohmann::json report;
    req.report_out = &report;
    ASSERT_EQ(tools::run_scene(req), 0) << path;
    const std::string device = report["scene"]["device"].get<std::string>();
    const tools::DeviceOutputs* out = outputs_of(device);
    ASSERT_NE(out, nullptr) << path << ": device " << device << " has no signal table";
    std::set<std::string> declared;
    for (const tools::FigureSpec& f : out->figures) declared.insert(std::string(f.name));
    ASSERT_TRUE(report["figures"].is_object()) << path;
    ASSERT_FALSE(report["figures"].empty()) << path;
    for (const auto& [key, value] : report["figures"].items()) {
      EXPECT_TRUE(declared.count(key)) << path << ": figure '" << key << "' is not a [[figure]] of "
                                       << "tools/devices/" << device << "/" << device << "_signals.toml";
      ++keys;
    }
    ++scenes;
  }
  std::printf("%d scenes, %d reported figures, each declared in its device's table\n", scenes, keys);
  EXPECT_GE(scenes, 18);
  EXPECT_GT(keys, scenes);
}

}  // namespace figure_keys_test
}  // namespace gyrostab
