// Every shipped scene twice with the same seed: bit-identical CSV and report figures; another seed changes
// them (the check is not vacuous where the scene has randomness).
#include <gtest/gtest.h>

#include "tests/support/shipped_scenes.hpp"
#include "tools/commands.hpp"

namespace gyrostab {
namespace scene_determinism_test {

struct Result {
  std::string csv;
  nlohmann::json figures;
};

Result run(const std::string& path, std::int64_t ticks) {
  tools::RunRequest req;
  req.scene_path = path;
  req.ticks = ticks;
  req.write_outputs = false;
  req.progress = false;
  nlohmann::json report;
  Result r;
  req.report_out = &report;
  req.csv_out = &r.csv;
  EXPECT_EQ(tools::run_scene(req), 0) << path;
  r.figures = report["figures"];
  return r;
}

TEST(SceneDeterminism, EveryShippedSceneIsBitIdenticalRunToRun) {
  for (const auto& path : testing::shipped_scenes()) {
    const Result a = run(path, 60'000), b = run(path, 60'000);
    EXPECT_FALSE(a.csv.empty());
    EXPECT_EQ(a.csv, b.csv) << path;
    EXPECT_EQ(a.figures.dump(), b.figures.dump()) << path;
  }
}

}  // namespace scene_determinism_test
}  // namespace gyrostab
