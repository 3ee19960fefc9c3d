// Every shipped scene, run in process with `--log`, gives a complete bus log whose replay into the controller
// alone reproduces every actuator frame bit for bit and whose open-loop re-simulation reproduces every sensor
// frame bit for bit; recording the same scene twice gives byte-identical logs (docs/architecture.md, the
// loop: same scene + seed
// ⇒ bit-identical logs).
#include <gtest/gtest.h>

#include "tests/support/bus_log_fixtures.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/log/bus_log_reader.hpp"
#include "tools/run/replay_session.hpp"

namespace gyrostab {
namespace {

using tools::buslog::BusLogReader;
using tools::buslog::ReadStatus;

constexpr std::int64_t kTicks = 3000;  // 3 s at 1 kHz (0.3 s for the 10 kHz drive scene): fast, many control runs

TEST(BusLogRoundTrip, EveryShippedSceneReplaysAndResimulatesBitIdentical) {
  const auto scenes = testing::shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& scene : scenes) {
    SCOPED_TRACE(scene);
    testing::ScratchDir dir("roundtrip");
    const std::string log = dir.file("run.lcmlog");
    ASSERT_EQ(testing::record_run(scene, log, kTicks), 0);

    // The layout: the scene event, then kTicks whole ticks (frames stamped with their tick), then the end event.
    BusLogReader r;
    ASSERT_EQ(r.open(log), ReadStatus::kOk) << r.problem();
    tools::buslog::TickRecord t;
    ReadStatus s;
    std::int64_t n = 0;
    while ((s = r.next(t)) == ReadStatus::kOk) {
      ASSERT_EQ(t.tick, n);
      ASSERT_EQ(t.sensor.tick, static_cast<std::uint64_t>(n));
      ASSERT_EQ(t.actuator.tick, static_cast<std::uint64_t>(n));
      ++n;
    }
    ASSERT_EQ(s, ReadStatus::kEnd) << r.problem();
    EXPECT_EQ(n, kTicks);
    EXPECT_EQ(r.end_event().reason, hil::EndReason::kCompleted);
    EXPECT_EQ(r.end_event().ticks, kTicks);
    EXPECT_FALSE(r.scene().toml.empty());

    const auto replayed = testing::replay(log);
    EXPECT_EQ(replayed.rc, 0) << replayed.out;
    EXPECT_NE(replayed.out.find(std::to_string(kTicks) + " ticks, every actuator frame identical"), std::string::npos)
        << replayed.out;
    const auto resimulated = testing::replay(log, /*resimulate=*/true);
    EXPECT_EQ(resimulated.rc, 0) << resimulated.out;
    EXPECT_NE(resimulated.out.find(std::to_string(kTicks) + " ticks, every re-simulated sensor frame identical"),
              std::string::npos)
        << resimulated.out;

    const std::string again = dir.file("again.lcmlog");
    ASSERT_EQ(testing::record_run(scene, again, kTicks), 0);
    EXPECT_TRUE(testing::read_bytes(log) == testing::read_bytes(again)) << "two recordings of one scene differ";
  }
}

// The scene comes from the log; --scene replaces it, and a scene that changes the controller is caught.
TEST(BusLogRoundTrip, SceneOverrideIsUsedAndADifferentControllerIsAMismatch) {
  testing::ScratchDir dir("override");
  const std::string scene = GYROSTAB_SOURCE_DIR "/sim/scenes/ship-roll-damper-active.toml";
  const std::string log = dir.file("run.lcmlog");
  ASSERT_EQ(testing::record_run(scene, log, 500), 0);

  tools::RunRequest req;
  req.role = tools::Role::kReplay;
  req.transport.replay_log = log;
  req.write_outputs = false;
  req.progress = false;
  req.scene_path = scene;  // the same scene from its file: identical
  EXPECT_EQ(tools::replay_log(req), 0);

  // The same scene with a different damping gain: the controller's commands differ from the first control run.
  const auto bytes = testing::read_bytes(scene);
  std::string text(bytes.begin(), bytes.end());
  const std::string from = "precession_damping = 8.36e4";
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "the shipped scene changed; pick another key to alter";
  text.replace(at, from.size(), "precession_damping = 1.0e5");
  const std::string changed = dir.file("changed.toml");
  testing::write_bytes(changed, std::vector<std::uint8_t>(text.begin(), text.end()), text.size());
  req.scene_path = changed;
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(tools::replay_log(req), tools::kReplayExitMismatch);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("MISMATCH at tick"), std::string::npos) << err;
}

}  // namespace
}  // namespace gyrostab
