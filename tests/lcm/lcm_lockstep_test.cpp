// Lockstep over LCM udpm:// is bit-identical to the in-process run of the same scene and seed
// (docs/architecture.md, the loop):
// report.json "figures" and signals.csv compared byte for byte, for every shipped scene (shortened with
// --ticks to keep the label fast on a small machine), whatever the timing (--jitter), with the processes
// started by `run --transport lcm` or by hand in either order, and with two runs sharing one bus (channel
// suffixes keep them apart).
#include <gtest/gtest.h>

#include "tests/lcm/lcm_test_support.hpp"
#include "tests/support/shipped_scenes.hpp"

namespace gyrostab::testing {
namespace {

constexpr const char* kTicks = "3000";

Outputs in_process(const std::string& scene_path, const std::string& dir) {
  return testing::in_process(scene_path, dir, kTicks);
}

TEST(LcmLockstep, EveryShippedSceneIsBitIdenticalToInProcess) {
  const auto scenes = shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    TempDir d;
    const Outputs ref = in_process(path, d / "inproc");
    const Exit e =
        run({gyrostab_bin(), "run", path, "--transport", "lcm", "--ticks", kTicks, "--out", d / "lcm"});
    EXPECT_EQ(e.code, 0) << path;
    if (e.code != 0) continue;
    expect_identical(ref, outputs_of(d / "lcm"), path);
    const nlohmann::json r = read_json(d / "lcm/report.json");
    EXPECT_EQ(r["processes"]["what_happened"], "completed") << path;
    EXPECT_EQ(r["link"]["counters"]["accepted"], std::stoi(kTicks)) << path;
    EXPECT_EQ(r["controller_process"]["link"]["counters"]["accepted"], std::stoi(kTicks)) << path;
    // The controller is not told the tick count: it stops on the plant's end-of-run frame, which it acknowledges.
    EXPECT_EQ(r["link"]["end_of_run"]["tick"], std::stoi(kTicks)) << path;
    EXPECT_EQ(r["link"]["end_of_run"]["acknowledged"], true) << path;
    EXPECT_EQ(r["controller_process"]["link"]["end_of_run"]["tick"], std::stoi(kTicks)) << path;
    // The firmware counters travel back into timing.controller, as in process.
    EXPECT_EQ(r["timing"]["controller"]["fault_monitor"]["good_frames"], std::stoi(kTicks)) << path;
  }
}

TEST(LcmLockstep, InjectedTimingJitterDoesNotChangeTheResult) {
  TempDir d;
  const std::string path = scene("monorail.toml");
  const Outputs ref = in_process(path, d / "inproc");
  const Exit e = run({gyrostab_bin(), "run", path, "--transport", "lcm", "--ticks", kTicks, "--jitter",
                      "400@0.1", "--out", d / "lcm"});
  ASSERT_EQ(e.code, 0);
  expect_identical(ref, outputs_of(d / "lcm"), "monorail with --jitter");
}

TEST(LcmLockstep, ABusPerDirectionGivesTheSameResult) {
  TempDir d;
  const std::string path = scene("power-stabilizer.toml");
  const Outputs ref = in_process(path, d / "inproc");
  const Exit e = run({gyrostab_bin(), "run", path, "--transport", "lcm", "--ticks", kTicks, "--lcm-actuator-url",
                      "udpm://239.255.76.67:7668?ttl=0", "--out", d / "lcm"});
  ASSERT_EQ(e.code, 0);
  expect_identical(ref, outputs_of(d / "lcm"), "actuator frames on their own port");
  EXPECT_EQ(read_json(d / "lcm/report.json")["link"]["subscribes_on"], "udpm://239.255.76.67:7668?ttl=0");
}

TEST(LcmLockstep, PlantStartedFirstResendsUntilTheControllerAnswers) {
  TempDir d;
  const std::string path = scene("servo-gyro.toml");
  const Outputs ref = in_process(path, d / "inproc");
  const std::vector<std::string> common{"--ticks", kTicks, "--channel-suffix", "_byhand"};
  const pid_t plant = spawn(cat({gyrostab_bin(), "plant", path, "--out", d / "plant"}, common));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const pid_t controller =
      spawn(cat({gyrostab_bin(), "controller", path, "--out", d / "controller"}, common));
  EXPECT_EQ(wait_for(plant).code, 0);
  EXPECT_EQ(wait_for(controller).code, 0);
  expect_identical(ref, outputs_of(d / "plant"), "plant started 300 ms before the controller");
  const nlohmann::json r = read_json(d / "plant/report.json");
  EXPECT_GT(r["link"]["counters"]["resent"].get<int>(), 0)
      << "the first sensor frame went out before anyone listened";
  const nlohmann::json c = read_json(d / "controller/report.json");
  EXPECT_EQ(c["link"]["what_happened"], "completed");
}

TEST(LcmLockstep, TwoRunsOnOneBusDoNotMix) {
  TempDir d;
  const std::string a = scene("monorail.toml"), b = scene("power-stabilizer.toml");
  const Outputs ref_a = in_process(a, d / "ref_a"), ref_b = in_process(b, d / "ref_b");
  // Same URL, default channel names plus the suffix each `run` picks from its pid.
  const pid_t pa =
      spawn({gyrostab_bin(), "run", a, "--transport", "lcm", "--ticks", kTicks, "--out", d / "a"});
  const pid_t pb =
      spawn({gyrostab_bin(), "run", b, "--transport", "lcm", "--ticks", kTicks, "--out", d / "b"});
  EXPECT_EQ(wait_for(pa).code, 0);
  EXPECT_EQ(wait_for(pb).code, 0);
  expect_identical(ref_a, outputs_of(d / "a"), "monorail beside power-stabilizer");
  expect_identical(ref_b, outputs_of(d / "b"), "power-stabilizer beside monorail");
  const nlohmann::json ra = read_json(d / "a/report.json");
  // LCM delivers only the subscribed channel: nothing of the other run may even arrive. (An exact repeat of
  // the last frame is the start-up resend, not the other run.)
  const nlohmann::json& rej = ra["link"]["counters"]["rejected"];
  EXPECT_EQ(rej["total"].get<int>() - rej["repeated"].get<int>(), 0) << rej.dump();
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_LCM_TEST_MAIN()
