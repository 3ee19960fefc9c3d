// `[output] signals`: a run records only the columns its scene names (tools/loop/recorder.hpp); an unknown
// name is refused before running with the list of valid ones (by `gyrostab check` too).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tools/commands.hpp"
#include "tools/loop/recorder.hpp"

namespace gyrostab {
namespace output_signals_test {

TEST(OutputSignals, RecorderKeepsTheSelectedColumnsInTheirOrder) {
  tools::Recorder all({"a", "b", "c"}, 4, 1);
  tools::Recorder some({"a", "b", "c"}, 4, 1, {"c", "a"});
  for (int k = 0; k < 3; ++k) {
    double* r = all.row(k);
    r[0] = 10.0 * k;
    r[1] = 10.0 * k + 1;
    r[2] = 10.0 * k + 2;
    double* s = some.row(k);  // the device writes its full row
    s[0] = 10.0 * k;
    s[1] = 10.0 * k + 1;
    s[2] = 10.0 * k + 2;
  }
  EXPECT_EQ(all.width(), 4u);
  EXPECT_EQ(some.width(), 3u);
  EXPECT_EQ(some.columns(), (std::vector<std::string>{"t_s", "c", "a"}));
  EXPECT_EQ(some.rows(), 3u);
  EXPECT_EQ(some.at(2, 1), 22.0);  // the last row too (it is moved out of the scratch row on read)
  EXPECT_EQ(some.at(2, 2), 20.0);
  EXPECT_EQ(some.csv(), "t_s,c,a\n0,2,0\n1,12,10\n2,22,20\n");
}

TEST(OutputSignals, UnknownOrRepeatedNamesAreNamedWithTheValidOnes) {
  EXPECT_EQ(tools::Recorder::check_signals({"a", "b"}, {"b"}), "");
  const std::string bad = tools::Recorder::check_signals({"a", "b"}, {"x", "a", "a"});
  EXPECT_NE(bad.find("\"x\" is not a signal of this device"), std::string::npos) << bad;
  EXPECT_NE(bad.find("\"a\" is listed twice"), std::string::npos) << bad;
  EXPECT_NE(bad.find("(valid: a, b)"), std::string::npos) << bad;
}

std::string shipped(const char* name) { return std::string(GYROSTAB_SOURCE_DIR "/sim/scenes/") + name; }

TEST(OutputSignals, SceneRecordsOnlyWhatItNames) {
  tools::RunRequest req;
  req.scene_path = shipped("power-stabilizer.toml");
  req.write_outputs = false;
  req.progress = false;
  req.ticks = 100;
  std::string full, some;
  req.csv_out = &full;
  ASSERT_EQ(tools::run_scene(req), 0);
  // The same scene with `signals` added to its [output] section.
  std::ifstream f(req.scene_path);
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto at = text.find("[output]");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 8, "\nsignals = [\"beta_rad\", \"alpha_rad\"]");
  req.scene_text = text;
  req.csv_out = &some;
  ASSERT_EQ(tools::run_scene(req), 0);
  EXPECT_EQ(full.substr(0, full.find(',', 4)), "t_s,alpha_rad");
  EXPECT_EQ(some.substr(0, some.find('\n')), "t_s,beta_rad,alpha_rad");
  EXPECT_LT(some.size(), full.size() / 2);

  // An unknown name: refused by `gyrostab check` (the scene validation) and by `gyrostab run`.
  const auto bad = text.replace(text.find("\"alpha_rad\"]"), 12, "\"alpha_deg\"]");
  std::vector<std::string> problems;
  EXPECT_EQ(tools::check_scene_text(bad, "bad.toml", &problems), 2);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("[output] signals: \"alpha_deg\" is not a signal of this device"), std::string::npos)
      << problems[0];
  EXPECT_NE(problems[0].find("valid: alpha_rad, beta_rad"), std::string::npos) << problems[0];
  req.scene_text = bad;
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(tools::run_scene(req), 2);
  ::testing::internal::GetCapturedStderr();
}

}  // namespace output_signals_test
}  // namespace gyrostab
