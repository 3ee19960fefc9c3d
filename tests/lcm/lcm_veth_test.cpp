// Plant and controller in two network namespaces joined by a veth pair, LCM over udpm:// with ttl=1 — the
// closed loop as across two hosts on a LAN (docs/transport.md). The plant runs in this test's private
// namespace, the controller in a second one (held by a `sleep` started with `unshare -n`, entered with
// nsenter); each side routes 224.0.0.0/4 to its veth end. The run must be bit-identical to the in-process
// one, and the frames must have crossed the veth (its packet counters).
#include <gtest/gtest.h>

#include "tests/lcm/lcm_test_support.hpp"

namespace gyrostab::testing {
namespace {

int sh(const std::string& cmd) {
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// Packets through `dev` in this process's network namespace, from /proc/net/dev (/sys/class/net shows the
// namespace sysfs was mounted in, not ours). `rx`: received, else transmitted. -1 if there is no such device.
long packets(const std::string& dev, bool rx) {
  std::istringstream in(read_file("/proc/net/dev"));
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    name.erase(0, name.find_first_not_of(' '));
    if (name != dev) continue;
    std::istringstream f(line.substr(colon + 1));
    long v[10] = {};
    for (long& x : v) f >> x;
    return rx ? v[1] : v[9];  // receive: bytes packets ...; transmit starts at field 8: bytes packets
  }
  return -1;
}

TEST(LcmVeth, TwoNamespacesOverAVethPairRunTheClosedLoopBitIdentically) {
  TempDir d;
  const std::string path = scene("servo-gyro.toml");
  ASSERT_EQ(
      run({gyrostab_bin(), "run", path, "--ticks", "3000", "--no-progress", "--out", d / "inproc"}).code, 0);

  const pid_t holder = spawn({"/usr/bin/unshare", "-n", "/bin/sleep", "120"});
  ASSERT_GT(holder, 0);
  // Wait until the holder is in its own namespace.
  const std::string ours = std::filesystem::read_symlink("/proc/self/ns/net").string();
  std::string theirs;
  for (int i = 0; i < 200 && (theirs.empty() || theirs == ours); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::error_code ec;
    theirs = std::filesystem::read_symlink("/proc/" + std::to_string(holder) + "/ns/net", ec).string();
  }
  ASSERT_NE(theirs, ours) << "the second namespace did not appear";
  const std::string in_b = "nsenter -t " + std::to_string(holder) + " -n ";
  ASSERT_EQ(sh("ip link add gsp type veth peer name gsc netns " + std::to_string(holder)), 0);
  ASSERT_EQ(sh("ip addr add 10.77.0.1/24 dev gsp && ip link set gsp up multicast on && "
               "ip route replace 224.0.0.0/4 dev gsp"),
            0);
  ASSERT_EQ(sh(in_b + "sh -c 'ip link set lo up && ip addr add 10.77.0.2/24 dev gsc && "
                      "ip link set gsc up multicast on && ip route add 224.0.0.0/4 dev gsc'"),
            0);
  const long tx_before = packets("gsp", false), rx_before = packets("gsp", true);
  ASSERT_GE(tx_before, 0);

  const std::string url = "udpm://239.255.76.67:7667?ttl=1";
  const std::vector<std::string> common{"--ticks", "3000", "--lcm-url", url};
  const pid_t controller = spawn(cat({"/usr/bin/nsenter", "-t", std::to_string(holder), "-n", gyrostab_bin(),
                                      "controller", path, "--out", d / "controller"},
                                     common));
  const Exit plant = run(cat({gyrostab_bin(), "plant", path, "--out", d / "plant"}, common));
  const Exit ctl = wait_for(controller);
  const long tx = packets("gsp", false) - tx_before, rx = packets("gsp", true) - rx_before;
  kill(holder, SIGKILL);  // its namespace goes, and the veth pair with it
  wait_for(holder);
  ASSERT_EQ(plant.code, 0);
  ASSERT_EQ(ctl.code, 0);
  EXPECT_EQ(read_json(d / "plant/report.json")["figures"].dump(),
            read_json(d / "inproc/report.json")["figures"].dump());
  EXPECT_TRUE(read_file(d / "plant/signals.csv") == read_file(d / "inproc/signals.csv"));
  // Every sensor frame left through the veth and every command came back through it.
  EXPECT_GE(tx, 3000);
  EXPECT_GE(rx, 3000);
  EXPECT_EQ(read_json(d / "plant/report.json")["link"]["url"], url);
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_LCM_TEST_MAIN()
