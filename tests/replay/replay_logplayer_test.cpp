// lcm-logplayer plays a gyrostab bus log onto a real LCM bus, and lcm-logger records every event of it with
// the same channel and payload: the log is an ordinary LCM event log. Runs inside a private network namespace
// (unshare -n, or unshare -rn when not root; loopback up with multicast and a 224.0.0.0/4 route,
// docs/architecture.md, messages and transports),
// so no packet leaves the host; where no namespace can be made (container without the privilege), the test
// exits 77 = SKIP (ctest SKIP_RETURN_CODE).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <lcm/eventlog.h>

#include "tests/support/bus_log_fixtures.hpp"

namespace gyrostab {
namespace {

constexpr int kSkip = 77;
constexpr const char* kProbeChannel = "GYROSTAB_PROBE";

struct Event {
  std::string channel;
  std::vector<std::uint8_t> data;
};

std::vector<Event> raw_events(const std::string& path) {
  std::vector<Event> out;
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "r");
  if (log == nullptr) return out;
  while (lcm_eventlog_event_t* e = lcm_eventlog_read_next_event(log)) {
    const auto* d = static_cast<const std::uint8_t*>(e->data);
    out.push_back({std::string(e->channel, static_cast<std::size_t>(e->channellen)),
                   std::vector<std::uint8_t>(d, d + e->datalen)});
    lcm_eventlog_free_event(e);
  }
  lcm_eventlog_destroy(log);
  return out;
}

// A one-event log on the probe channel: played until the logger has it, so the real log is played only once
// the logger listens.
void write_probe(const std::string& path) {
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "w");
  ASSERT_NE(log, nullptr);
  char data[4] = {'p', 'i', 'n', 'g'};
  lcm_eventlog_event_t e{};
  e.channellen = static_cast<std::int32_t>(std::string(kProbeChannel).size());
  e.channel = const_cast<char*>(kProbeChannel);
  e.datalen = 4;
  e.data = data;
  ASSERT_EQ(lcm_eventlog_write_event(log, &e), 0);
  lcm_eventlog_destroy(log);
}

std::string unshare_command() {
  if (std::system("unshare -n true >/dev/null 2>&1") == 0) return "unshare -n";
  if (std::system("unshare -rn true >/dev/null 2>&1") == 0) return "unshare -rn";
  return {};
}

TEST(BusLogLcmTools, LogplayerPlaysEveryEventToLcmLogger) {
  const std::string unshare = unshare_command();
  if (unshare.empty() || std::system("command -v ip >/dev/null && command -v lcm-logplayer >/dev/null && "
                                     "command -v lcm-logger >/dev/null") != 0) {
    std::printf("SKIP: no private network namespace (unshare -n / -rn refused) or no ip / lcm-logplayer\n");
    std::fflush(stdout);
    std::_Exit(kSkip);
  }
  testing::ScratchDir dir("logplayer");
  const std::string log = dir.file("run.lcmlog");
  ASSERT_EQ(testing::record_run(GYROSTAB_SOURCE_DIR "/sim/scenes/power-stabilizer.toml", log, 300), 0);
  const std::string probe = dir.file("probe.lcmlog");
  write_probe(probe);
  const std::string got = dir.file("logged.lcmlog");
  const auto expected_bytes = testing::read_bytes(log).size();

  // Inside the namespace: loopback with multicast; the logger; the probe until it arrives; the log at its
  // recorded pace (sim time: 0.3 s); wait until the logger's file holds at least as many bytes as the log
  // (each event is logged with the same channel and data, so the same size); stop the logger.
  const std::string url = "udpm://239.255.76.67:7667?ttl=0";
  const std::string script = dir.file("play.sh");
  {
    std::FILE* f = std::fopen(script.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f,
                 "set -e\n"
                 "ip link set lo up; ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo\n"
                 // lcm-logger 1.3.1 lists -l in its help but only parses the long form
                 "lcm-logger -q -f --flush-interval=10 --lcm-url='%s' '%s' & logger=$!\n"
                 "n=0\n"
                 "until [ -s '%s' ]; do\n"
                 "  lcm-logplayer -l '%s' '%s'; sleep 0.1; n=$((n+1))\n"
                 "  if [ $n -ge 200 ]; then kill $logger; echo 'the logger never received the probe'; exit 3; fi\n"
                 "done\n"
                 "lcm-logplayer -l '%s' '%s'\n"
                 "n=0\n"
                 "while [ $(stat -c %%s '%s') -lt %zu ] && [ $n -lt 300 ]; do sleep 0.1; n=$((n+1)); done\n"
                 "kill -INT $logger; wait $logger || true\n",
                 url.c_str(), got.c_str(), got.c_str(), url.c_str(), probe.c_str(), url.c_str(), log.c_str(),
                 got.c_str(), expected_bytes);
    std::fclose(f);
  }
  const std::string cmd = unshare + " sh " + script;
  const int rc = std::system(cmd.c_str());
  ASSERT_EQ(rc, 0) << cmd;

  const std::vector<Event> original = raw_events(log);
  std::vector<Event> received;
  for (Event& e : raw_events(got)) {
    if (e.channel != kProbeChannel) received.push_back(std::move(e));
  }
  ASSERT_EQ(original.size(), 1u + 2 * 300 + 1);  // scene, 300 ticks, end
  ASSERT_EQ(received.size(), original.size()) << "events lost on the way through LCM";
  for (std::size_t i = 0; i < original.size(); ++i) {
    EXPECT_EQ(received[i].channel, original[i].channel) << "event " << i;
    EXPECT_TRUE(received[i].data == original[i].data) << "event " << i << " payload differs";
  }
}

}  // namespace
}  // namespace gyrostab
