// Every `gyrostab run` report carries an error estimate beside its run time (docs/accuracy.md): for
// every shipped scene, run to its full duration, report.json "error_estimate" is available, the window's
// re-integration at the run's own step lands on the run's states bit for bit (`reproduces_run`: the capture
// of state and held inputs is complete) and every per-state estimate is finite and non-negative. The
// documented exceptions must say why instead: the dc-drive scene (its drives step inside the tick) and the
// gyro pendulum on a Kepler orbit (the rigid-body variant; its error is bounded by its oracle in
// tests/oracle/chelnokov_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "tests/support/shipped_scenes.hpp"
#include "tools/commands.hpp"

namespace gyrostab::tools {
namespace run_error_estimate_test {

TEST(RunErrorEstimate, EveryShippedSceneReportsOneOrSaysWhyNot) {
  int estimated = 0;
  for (const std::string& path : testing::shipped_scenes()) {
    SCOPED_TRACE(path);
    RunRequest req;
    req.scene_path = path;
    req.write_outputs = false;
    req.progress = false;
    nlohmann::json report;
    req.report_out = &report;
    ASSERT_EQ(run_scene(req), 0);
    ASSERT_TRUE(report.contains("error_estimate"));
    const nlohmann::json& e = report["error_estimate"];
    const std::string stem = std::filesystem::path(path).stem().string();
    if (stem == "power-stabilizer-drive" || stem == "gyro-pendulum-kepler-orbit") {
      EXPECT_FALSE(e["available"].get<bool>());
      EXPECT_FALSE(e["why"].get<std::string>().empty());
      continue;
    }
    ASSERT_TRUE(e["available"].get<bool>()) << e.dump();
    EXPECT_TRUE(e["reproduces_run"].get<bool>()) << e.dump();
    EXPECT_GT(e["window_ticks"].get<int>(), 0);
    ASSERT_FALSE(e["max_abs_error"].empty());
    for (const auto& [name, v] : e["max_abs_error"].items()) {
      const double x = v.get<double>();
      EXPECT_TRUE(std::isfinite(x) && x >= 0.0) << name << " = " << x;
    }
    ++estimated;
  }
  EXPECT_GE(estimated, 12);
}

}  // namespace run_error_estimate_test
}  // namespace gyrostab::tools
