// A bus log is input like a scene file: the scene it carries passes the same limits before the TOML parser
// sees it. A log whose scene event holds a table header 200 000 levels deep (the parser recursed once per
// level and overflowed the stack: replay exited 139) is refused with the reason, and nothing is replayed.
#include <gtest/gtest.h>
#include <lcm/eventlog.h>

#include <string>
#include <vector>

#include "hil/lcm/log_event_codec.hpp"
#include "tests/support/bus_log_fixtures.hpp"

namespace gyrostab {
namespace {

struct Event {
  std::string channel;
  std::int64_t timestamp{0};
  std::vector<std::uint8_t> data;
};

std::vector<Event> read_events(const std::string& path) {
  std::vector<Event> out;
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "r");
  if (log == nullptr) return out;
  while (lcm_eventlog_event_t* e = lcm_eventlog_read_next_event(log)) {
    const auto* d = static_cast<const std::uint8_t*>(e->data);
    out.push_back({std::string(e->channel, static_cast<std::size_t>(e->channellen)), e->timestamp,
                   std::vector<std::uint8_t>(d, d + e->datalen)});
    lcm_eventlog_free_event(e);
  }
  lcm_eventlog_destroy(log);
  return out;
}

void write_events(const std::string& path, std::vector<Event>& events) {
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "w");
  ASSERT_NE(log, nullptr);
  for (Event& ev : events) {
    lcm_eventlog_event_t e{};
    e.timestamp = ev.timestamp;
    e.channellen = static_cast<std::int32_t>(ev.channel.size());
    e.channel = ev.channel.data();
    e.datalen = static_cast<std::int32_t>(ev.data.size());
    e.data = ev.data.data();
    ASSERT_EQ(lcm_eventlog_write_event(log, &e), 0);
  }
  lcm_eventlog_destroy(log);
}

TEST(HostileLog, ADeepSceneInALogIsRefusedBeforeTheParser) {
  testing::ScratchDir d("hostile-log");
  const std::string log = d.file("run.lcmlog"), bad = d.file("deep.lcmlog");
  ASSERT_EQ(testing::record_run(std::string(GYROSTAB_SOURCE_DIR) + "/sim/scenes/monorail.toml", log, 20), 0);
  std::vector<Event> events = read_events(log);
  ASSERT_GT(events.size(), 3u);
  hil::SceneEvent scene;
  std::string why;
  ASSERT_TRUE(hil::decode(events[0].data.data(), static_cast<int>(events[0].data.size()), scene, why)) << why;
  std::string deep = "[a";
  for (int i = 0; i < 200'000; ++i) deep += ".a";
  scene.toml = deep + "]\n" + scene.toml;
  events[0].data = hil::encode(scene);
  write_events(bad, events);
  for (const bool resimulate : {false, true}) {
    const testing::ReplayResult r = testing::replay(bad, resimulate);
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find("nested more than 32 levels deep"), std::string::npos) << r.out;
  }
}

}  // namespace
}  // namespace gyrostab
