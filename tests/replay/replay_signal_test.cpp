// SIGTERM or SIGINT in the middle of `gyrostab run SCENE --log FILE` stops the run at a tick boundary: the
// process exits with 128 + the signal, and the log reads to its end without error — the scene event, whole
// ticks only, the end event naming the signal — and replays identically. The run is a child process of the
// CLI (GYROSTAB_CLI); the signal is sent once the log has grown past two stream buffers (so the loop is
// running), whatever the machine's speed: the scene is made endless.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>

#include "tests/support/bus_log_fixtures.hpp"
#include "tools/log/bus_log_reader.hpp"

extern char** environ;

namespace gyrostab {
namespace {

using tools::buslog::BusLogReader;
using tools::buslog::ReadStatus;

// The active ship damper, made endless (1e6 s) with a small CSV table and no plot.
std::string endless_scene(const testing::ScratchDir& dir) {
  const auto bytes = testing::read_bytes(GYROSTAB_SOURCE_DIR "/sim/scenes/ship-roll-damper-active.toml");
  std::string text(bytes.begin(), bytes.end());
  const std::string from = "duration_s = 900.0";
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "the shipped scene changed";
  if (at != std::string::npos) text.replace(at, from.size(), "duration_s = 1.0e6");
  const std::string every = "record_every = 50";
  const auto at_every = text.find(every);
  EXPECT_NE(at_every, std::string::npos) << "the shipped scene changed";
  EXPECT_EQ(text.find("plots"), std::string::npos) << "the shipped scene sets plots now";
  if (at_every != std::string::npos) text.replace(at_every, every.size(), "record_every = 1000000\nplots = false");
  const std::string path = dir.file("endless.toml");
  testing::write_bytes(path, std::vector<std::uint8_t>(text.begin(), text.end()), text.size());
  return path;
}

void stop_mid_run(int signo) {
  testing::ScratchDir dir("signal");
  const std::string scene = endless_scene(dir);
  const std::string log = dir.file("run.lcmlog");
  const std::string out = dir.file("out");
  std::vector<std::string> args = {GYROSTAB_CLI, "run", scene, "--log", log, "--out", out, "--no-progress"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, GYROSTAB_CLI, nullptr, nullptr, argv.data(), environ), 0);

  // The writer's stream buffer is 256 KiB: past 512 KiB on disk the loop has run for a while.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  std::error_code ec;
  while (std::filesystem::file_size(log, ec) < 512 * 1024 || ec) {
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, WNOHANG), 0) << "the run ended before the signal";
    ASSERT_LT(std::chrono::steady_clock::now(), give_up) << "the log never grew";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(kill(pid, signo), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping (status " << status << ")";
  EXPECT_EQ(WEXITSTATUS(status), 128 + signo);

  BusLogReader r;
  ASSERT_EQ(r.open(log), ReadStatus::kOk) << r.problem();
  tools::buslog::TickRecord t;
  ReadStatus s;
  std::int64_t ticks = 0;
  while ((s = r.next(t)) == ReadStatus::kOk) ++ticks;
  ASSERT_EQ(s, ReadStatus::kEnd) << r.problem();
  EXPECT_GT(ticks, 1000);
  EXPECT_EQ(r.end_event().reason, hil::EndReason::kSignal);
  EXPECT_EQ(r.end_event().signal, signo);
  EXPECT_EQ(r.end_event().ticks, ticks);
  EXPECT_TRUE(std::filesystem::exists(out + "/report.json")) << "outputs up to the stop are written";

  const auto replayed = testing::replay(log);
  EXPECT_EQ(replayed.rc, 0) << replayed.out;
}

TEST(BusLogSignal, SigtermMidRunLeavesACompleteLog) { stop_mid_run(SIGTERM); }
TEST(BusLogSignal, SigintMidRunLeavesACompleteLog) { stop_mid_run(SIGINT); }

}  // namespace
}  // namespace gyrostab
