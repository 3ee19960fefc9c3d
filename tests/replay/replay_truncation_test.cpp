// A bus log cut short — inside the scene event, inside any frame event, exactly between ticks, inside or
// just before the end event — is reported as truncated with the byte offset of the event that was cut (or of
// the cut, when it falls between events), exit 5, and the whole ticks before the cut replay identically.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "tests/support/bus_log_fixtures.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "hil/lcm/frame_codec.hpp"
#include "tools/log/bus_log_reader.hpp"
#include "tools/run/replay_session.hpp"

namespace gyrostab {
namespace {

using tools::buslog::BusLogReader;
using tools::buslog::ReadStatus;
using tools::buslog::TickRecord;

// Byte layout of an intact log: where each event starts.
struct Layout {
  std::vector<std::int64_t> starts;  // scene event, then sensor/actuator of every tick, then the end event
  std::int64_t size{0};
  // The event a cut at byte `cut` falls into, or starts.
  std::size_t event_at(std::int64_t cut) const {
    return static_cast<std::size_t>(std::upper_bound(starts.begin(), starts.end(), cut) - starts.begin()) - 1;
  }
};

Layout layout_of(const std::string& log) {
  Layout l;
  BusLogReader r;
  EXPECT_EQ(r.open(log), ReadStatus::kOk) << r.problem();
  l.starts.push_back(0);
  TickRecord t;
  while (r.next(t) == ReadStatus::kOk) {
    l.starts.push_back(t.sensor_offset);
    l.starts.push_back(t.actuator_offset);
  }
  l.size = r.file_size();
  // The end event follows the last actuator event (the size of every actuator event: the event header, the
  // channel name and the encoded frame).
  l.starts.push_back(l.starts.back() + 28 + 17 + hil::actuator_encoded_size(r.signals()));
  return l;
}

// Whole ticks before a cut: the events before the one the cut falls into (or starts) are whole; event 0 is the
// scene, 1 + 2k and 2 + 2k are tick k's sensor and actuator frames.
std::int64_t whole_ticks_before(const Layout& l, std::int64_t cut) {
  const std::size_t e = l.event_at(cut);
  return e <= 1 ? 0 : static_cast<std::int64_t>((e - 1) / 2);
}

void expect_cut_reported(const std::vector<std::uint8_t>& bytes, const Layout& l, std::int64_t cut,
                         const std::string& cut_log) {
  testing::write_bytes(cut_log, bytes, static_cast<std::size_t>(cut));
  const std::size_t e = l.event_at(cut);
  const std::int64_t reported = l.starts[e] == cut ? cut : l.starts[e];
  for (const bool resimulate : {false, true}) {
    SCOPED_TRACE(std::string(resimulate ? "resimulate" : "replay") + ", cut at byte " + std::to_string(cut) +
                 " of " + std::to_string(l.size));
    const auto r = testing::replay(cut_log, resimulate);
    EXPECT_EQ(r.rc, tools::kReplayExitBadLog) << r.out;
    EXPECT_NE(r.out.find("truncated"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(": byte " + std::to_string(reported) + ":"), std::string::npos) << r.out;
    if (e == 0) {
      EXPECT_NE(r.out.find("nothing replayed"), std::string::npos) << r.out;
    } else {
      EXPECT_NE(r.out.find("the " + std::to_string(whole_ticks_before(l, cut)) + " ticks before it"),
                std::string::npos)
          << r.out;
    }
  }
}

TEST(BusLogTruncation, CutsAtManyOffsetsReportTheOffsetAndReplayThePrefix) {
  testing::ScratchDir dir("truncation");
  const std::string log = dir.file("run.lcmlog");
  ASSERT_EQ(testing::record_run(GYROSTAB_SOURCE_DIR "/sim/scenes/servo-gyro.toml", log, 30), 0);
  const auto bytes = testing::read_bytes(log);
  const Layout l = layout_of(log);
  ASSERT_EQ(l.size, static_cast<std::int64_t>(bytes.size()));
  ASSERT_EQ(l.starts.size(), 1u + 2 * 30 + 1);

  std::set<std::int64_t> cuts;
  for (std::int64_t c = 0; c < l.size; c += 89) cuts.insert(c);  // a stride co-prime to every event size
  for (const std::int64_t s : l.starts) {                          // each event boundary and its neighbours
    for (const std::int64_t d : {-1, 0, 1, 27, 28, 29}) {
      if (s + d >= 0 && s + d < l.size) cuts.insert(s + d);
    }
  }
  cuts.insert(l.size - 1);
  for (const std::int64_t cut : cuts) expect_cut_reported(bytes, l, cut, dir.file("cut.lcmlog"));

  // The intact log replays whole.
  EXPECT_EQ(testing::replay(log).rc, 0);
}

// One cut in the middle of each shipped scene's log: the prefix is every scene's own frames.
TEST(BusLogTruncation, EveryShippedSceneReplaysTheWholeTicksOfACutLog) {
  for (const auto& scene : testing::shipped_scenes()) {
    SCOPED_TRACE(scene);
    testing::ScratchDir dir("truncation-scenes");
    const std::string log = dir.file("run.lcmlog");
    ASSERT_EQ(testing::record_run(scene, log, 200), 0);
    const auto bytes = testing::read_bytes(log);
    const Layout l = layout_of(log);
    // Inside the sensor payload of tick 120.
    expect_cut_reported(bytes, l, l.starts[1 + 2 * 120] + 100, dir.file("cut.lcmlog"));
  }
}

}  // namespace
}  // namespace gyrostab
