// Hostile or careless input to `check` and `run` (in this process, as the CLI calls them): nesting and size
// limits before the TOML parser, the recorder's memory ceiling and --ticks checked by `check` and `run` alike,
// an output path with shell syntax (no shell is ever involved), an output path that cannot be one, and an
// output directory whose files are replaced as a set.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/bus_log_fixtures.hpp"
#include "tools/commands.hpp"
#include "tools/scene/toml_limits.hpp"

namespace gyrostab {
namespace hostile_input_test {

namespace fs = std::filesystem;

std::string monorail_text() {
  std::ifstream f(std::string(GYROSTAB_SOURCE_DIR) + "/sim/scenes/monorail.toml");
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// The scene with the first line that starts with `key =` replaced by `line`.
std::string with_line(std::string text, const std::string& key, const std::string& line) {
  const std::size_t at = text.find("\n" + key + " =");
  EXPECT_NE(at, std::string::npos) << key;
  const std::size_t end = text.find('\n', at + 1);
  return text.replace(at + 1, end - at - 1, line);
}

struct Result {
  int rc{-1};
  std::string err;
};

Result run_text(const std::string& text, bool check_only, std::int64_t ticks = -1, const std::string& out = "") {
  tools::RunRequest req;
  req.scene_path = "hostile.toml";
  req.scene_text = text;
  req.check_only = check_only;
  req.progress = false;
  req.ticks = ticks;
  req.write_outputs = !out.empty();
  if (!out.empty()) req.out_dir = out;
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  Result r;
  r.rc = tools::run_scene(req);
  r.err = ::testing::internal::GetCapturedStderr();
  ::testing::internal::GetCapturedStdout();
  return r;
}

Result run_file(const std::string& path, bool check_only) {
  tools::RunRequest req;
  req.scene_path = path;
  req.check_only = check_only;
  req.progress = false;
  req.write_outputs = false;
  ::testing::internal::CaptureStderr();
  Result r;
  r.rc = tools::run_scene(req);
  r.err = ::testing::internal::GetCapturedStderr();
  return r;
}

TEST(TomlLimits, CountsHeadersDottedKeysArraysAndInlineTables) {
  int line = 0;
  EXPECT_EQ(tools::toml_nesting_depth("[scene]\nname = \"x\"\n", &line), 2);
  EXPECT_EQ(tools::toml_nesting_depth("[a.b.c]\nd.e = [[1, 2], [3]]\n"), 3 + 2 + 2);
  EXPECT_EQ(tools::toml_nesting_depth("x = {a = {b.c = 1}}\n"), 1 + 1 + 1 + 1 + 2);
  EXPECT_EQ(tools::toml_nesting_depth("s = \"[[[[{{{{.\" # [[[[\n'q' = '...'\n"), 1) << "strings and comments";
  EXPECT_EQ(tools::toml_nesting_depth("m = \"\"\"\n[[[[\n\"\"\"\n[t]\n", &line), 1);
  // Every shipped scene is far inside the limit.
  for (const auto& e : fs::directory_iterator(std::string(GYROSTAB_SOURCE_DIR) + "/sim/scenes")) {
    if (e.path().extension() != ".toml") continue;
    std::ifstream f(e.path());
    std::ostringstream s;
    s << f.rdbuf();
    EXPECT_LE(tools::toml_nesting_depth(s.str()), 4) << e.path();
    EXPECT_EQ(tools::toml_limits_problem(s.str(), e.path().string()), "") << e.path();
  }
}

TEST(HostileScene, ADeepDottedHeaderIsRefusedBeforeTheParser) {
  // 200 000 levels, 400 KB: toml++ recursed once per level and overflowed the stack (exit 139).
  std::string deep = "[a";
  for (int i = 0; i < 200'000; ++i) deep += ".a";
  deep += "]\nx = 1\n";
  for (const bool check : {true, false}) {
    const Result r = run_text(deep, check);
    EXPECT_EQ(r.rc, 2);
    EXPECT_NE(r.err.find("hostile.toml:1: nested more than 32 levels deep"), std::string::npos) << r.err;
  }
  std::string arrays = "x = ";
  for (int i = 0; i < 100'000; ++i) arrays += "[";
  EXPECT_EQ(run_text(arrays, true).rc, 2);
  std::string tables = "x = ";
  for (int i = 0; i < 100'000; ++i) tables += "{a = ";
  EXPECT_NE(run_text(tables, true).err.find("nested more than"), std::string::npos);
}

TEST(HostileScene, AnOversizedFileIsRefusedUnreadAndAMissingOneSaysSo) {
  testing::ScratchDir d("hostile");
  const std::string big = d.file("big.toml");
  {
    std::ofstream f(big);
    f << monorail_text() << "[junk]\nx = [";
    for (int i = 0; i < 300'000; ++i) f << "1.0, ";
    f << "1.0]\n";
  }
  Result r = run_file(big, true);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("larger than a scene may be (1048576 bytes); not parsed"), std::string::npos) << r.err;
  r = run_file(d.file("missing.toml"), true);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("missing.toml: cannot read the scene file (No such file or directory)"), std::string::npos)
      << r.err;
}

TEST(HostileScene, ARecordingAboveTheCeilingIsRefusedByCheckAndRun) {
  // 1e12 ticks: the recorder was sized before tick 0 and the run died of std::bad_alloc (exit 134).
  const std::string huge =
      with_line(with_line(monorail_text(), "duration_s", "duration_s = 1e6"), "tick_us", "tick_us = 1");
  for (const bool check : {true, false}) {
    const Result r = run_text(huge, check);
    EXPECT_EQ(r.rc, 2);
    EXPECT_NE(r.err.find("the recording would need"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("above the ceiling of 1.02e+03 MiB"), std::string::npos) << r.err;
  }
  // The same scene recorded every 10 000 ticks fits (and is then refused or run on its other merits).
  const std::string sparse = with_line(huge, "record_every", "record_every = 100000");
  EXPECT_EQ(run_text(sparse, true).err.find("the recording would need"), std::string::npos);
}

TEST(HostileScene, TicksBeyondTheIntegerClockOrTheCeilingAreRefused) {
  Result r = run_text(monorail_text(), false, 9'223'372'036'854'775'807LL);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("would overflow the integer clock"), std::string::npos) << r.err;
  r = run_text(monorail_text(), false, 2'000'000'000'000LL);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("the recording would need"), std::string::npos) << r.err;
}

TEST(HostileScene, WhatCheckAcceptsRunRuns) {
  const std::string bad = with_line(monorail_text(), "record_every", "record_every = 10\nsignals = [\"nope\"]");
  const Result c = run_text(bad, true);
  EXPECT_EQ(c.rc, 2) << "check refuses what run would refuse";
  EXPECT_NE(c.err.find("\"nope\" is not a signal of this device"), std::string::npos) << c.err;
}

TEST(OutputDir, AnOutPathWithShellSyntaxIsJustAPath) {
  testing::ScratchDir d("hostile-out");
  const fs::path cwd = fs::current_path();
  fs::current_path(d.file(""));
  const std::string out = d.file("x'; touch PWNED; echo '");
  const Result r = run_text(monorail_text(), false, 200, out);
  fs::current_path(cwd);
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_FALSE(fs::exists(d.file("PWNED"))) << "a shell ran the output path";
  EXPECT_TRUE(fs::exists(out + "/report.json"));
  EXPECT_TRUE(fs::exists(out + "/signals.csv"));
  EXPECT_TRUE(fs::exists(out + "/signals.png")) << r.err << " (needs /usr/bin/python3 with matplotlib)";
  for (const auto& e : fs::directory_iterator(out)) {
    EXPECT_EQ(e.path().filename().string().rfind(".staging", 0), std::string::npos) << "staging left behind";
  }
}

TEST(OutputDir, AFileOrAPathInProcIsRefusedBeforeRunning) {
  testing::ScratchDir d("hostile-out");
  {
    std::ofstream f(d.file("a-file"));
    f << "x";
  }
  Result r = run_text(monorail_text(), false, 200, d.file("a-file"));
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("exists and is not a directory"), std::string::npos) << r.err;
  r = run_text(monorail_text(), false, 200, "/proc/self/out");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("inside /proc"), std::string::npos) << r.err;
}

TEST(OutputDir, ARunReplacesTheWholeSetOfOutputs) {
  testing::ScratchDir d("hostile-out");
  const std::string out = d.file("o");
  ASSERT_EQ(run_text(monorail_text(), false, 200, out).rc, 0);
  ASSERT_TRUE(fs::exists(out + "/signals.png"));
  // The next run draws no figure: the earlier run's figure must not stay beside the new report.
  ::setenv("GYROSTAB_PLOT_SCRIPT", "", 1);
  const Result r = run_text(monorail_text(), false, 100, out);
  ::unsetenv("GYROSTAB_PLOT_SCRIPT");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_TRUE(fs::exists(out + "/report.json"));
  EXPECT_FALSE(fs::exists(out + "/signals.png")) << "an older run's figure left beside this run's report";
}

// A plot helper that fails says why itself (one line); the run's message names the helper and its exit status
// and does not blame a missing matplotlib that is there.
TEST(OutputDir, AFailingPlotHelperIsNamedWithItsExitStatus) {
  testing::ScratchDir d("hostile-out");
  const std::string script = d.file("failing_plot.py");
  {
    std::ofstream f(script);
    f << "import sys\nsys.stderr.write('failing_plot.py: the figure could not be laid out\\n')\nsys.exit(1)\n";
  }
  ::setenv("GYROSTAB_PLOT_SCRIPT", script.c_str(), 1);
  const Result r = run_text(monorail_text(), false, 100, d.file("o"));
  ::unsetenv("GYROSTAB_PLOT_SCRIPT");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("the figure could not be laid out"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("failing_plot.py exited 1"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("matplotlib"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(d.file("o") + "/report.json"));
}

}  // namespace hostile_input_test
}  // namespace gyrostab
