// Who may steer the loop over LCM (hil/link/link_guard.hpp, docs/transport.md, sessions and authentication):
//   - two runs on the same channels: each pair's frames are foreign to the other; nothing foreign is acted
//     on (both results are the in-process ones, bit for bit) and both runs say so (exit 7);
//   - pairs started by hand on the same channels: detected, never a silent success;
//   - a controller started on another scene (another gain) is refused at the handshake, with both scene hashes;
//   - a bus log played onto a live bus (lcm-logplayer): its frames are refused as recorded;
//   - with a link key, a third process that copies every envelope and sends forged commands ahead of the
//     genuine ones changes nothing: every forgery fails its MAC, the run is the in-process run.
#include <gtest/gtest.h>
#include <lcm/lcm.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cmath>

#include <fstream>

#include "hil/lcm/frame_codec.hpp"
#include "tools/scene/scene_hash.hpp"
#include "tools/signals/device_signals.hpp"
#include "tests/lcm/lcm_test_support.hpp"

namespace gyrostab::testing {
namespace {

std::uint64_t refused(const nlohmann::json& link, const char* kind) {
  return link["session"]["refused"][kind].get<std::uint64_t>();
}

TEST(LcmSession, TwoRunsOnTheSameChannelsRefuseEachOthersFrames) {
  TempDir d;
  // Two scenes of one device (the same frame types): their frames reach each other's guards, which refuse them
  // as another session's (frames of another device's types are refused by fingerprint before that).
  const std::string a = scene("ship-roll-damper-active.toml"), b = scene("ship-roll-damper-passive.toml");
  const Outputs ref_a = in_process(a, d / "ref_a", "3000"), ref_b = in_process(b, d / "ref_b", "3000");
  const std::vector<std::string> shared{"--transport", "lcm", "--ticks", "3000", "--channel-suffix", "_shared"};
  const pid_t pa = spawn(cat({gyrostab_bin(), "run", a, "--out", d / "a"}, shared));
  const pid_t pb = spawn(cat({gyrostab_bin(), "run", b, "--out", d / "b"}, shared));
  const Exit ea = wait_for(pa), eb = wait_for(pb);
  expect_identical(ref_a, outputs_of(d / "a"), "active damper sharing its channels");
  expect_identical(ref_b, outputs_of(d / "b"), "passive damper sharing its channels");
  // The overlap is seen by whichever process listened while the other pair talked — a run's plant or its
  // controller process — so the test counts both of each run.
  std::uint64_t seen = 0;
  for (const auto& [dir, e] : {std::pair{d / "a", ea}, std::pair{d / "b", eb}}) {
    const nlohmann::json r = read_json(dir + "/report.json");
    const std::uint64_t foreign =
        refused(r["link"], "foreign") + refused(r["controller_process"]["link"], "foreign");
    seen += foreign;
    // Unless the runs did not overlap at all, each saw the other's frames and says so.
    if (foreign > 0) {
      EXPECT_EQ(e.code, 7) << dir;
    } else {
      EXPECT_EQ(e.code, 0) << dir;
    }
  }
  EXPECT_GT(seen, 0u) << "the two runs never overlapped";
}

TEST(LcmSession, PairsStartedByHandOnOneBusAreNeverASilentSuccess) {
  TempDir d;
  const std::string m = scene("monorail.toml");
  const std::vector<std::string> common{"--ticks", "3000", "--timeout-ms", "500", "--start-timeout-ms", "3000"};
  // No suffix, no session: as a user starts them in four terminals.
  std::vector<pid_t> pids;
  for (const char* name : {"p1", "p2"}) pids.push_back(spawn(cat({gyrostab_bin(), "plant", m, "--out", d / name}, common)));
  for (const char* name : {"c1", "c2"})
    pids.push_back(spawn(cat({gyrostab_bin(), "controller", m, "--out", d / name}, common)));
  int silent_successes = 0;
  for (const pid_t p : pids) {
    const Exit e = wait_for(p);
    EXPECT_NE(e.code, -1) << "a process crashed";
    if (e.code == 0) ++silent_successes;
  }
  EXPECT_EQ(silent_successes, 0) << "a process shared its bus with another pair and exited 0";
}

TEST(LcmSession, AControllerOfAnotherSceneIsRefusedWithBothHashes) {
  TempDir d;
  const std::string m = scene("monorail.toml");
  std::string other_text = read_file(m);
  const std::size_t at = other_text.find("k = 5500");
  ASSERT_NE(at, std::string::npos);
  other_text.replace(at, 8, "k = 6000");  // the same device and frames, another gain
  const std::string other = d / "monorail-k6000.toml";
  std::ofstream(other) << other_text;
  const std::string ours = tools::format_scene_hash(tools::scene_hash(read_file(m)));
  const std::string theirs = tools::format_scene_hash(tools::scene_hash(other_text));
  ASSERT_NE(ours, theirs);
  const std::vector<std::string> common{"--ticks", "2000", "--timeout-ms", "500", "--start-timeout-ms", "2000",
                                        "--channel-suffix", "_scene"};
  const pid_t p = spawn(cat({gyrostab_bin(), "plant", m, "--out", d / "p"}, common));
  const Exit c = run(cat({gyrostab_bin(), "controller", other, "--out", d / "c"}, common));
  const Exit pe = wait_for(p);
  EXPECT_NE(c.code, 0);
  EXPECT_NE(pe.code, 0);
  // The controller saw only the plant's frames, every one of another scene: it never bound, and says whose.
  const nlohmann::json rc = read_json(d / "c/report.json");
  const nlohmann::json& session = rc["link"]["session"];
  EXPECT_GT(session["refused"]["other_scene"].get<int>(), 0) << session.dump();
  EXPECT_EQ(session["scene"], theirs) << session.dump();
  EXPECT_EQ(session["other_scene"], ours) << session.dump();
  const std::string why = rc["link"]["what_happened"].get<std::string>();
  EXPECT_NE(why.find(ours), std::string::npos) << why;
  EXPECT_NE(why.find(theirs), std::string::npos) << why;
  // Nothing of the other scene's controller was applied: the plant never bound either.
  const nlohmann::json rp = read_json(d / "p/report.json");
  EXPECT_TRUE(rp["link"]["session"]["peer"].is_null()) << rp["link"]["session"].dump();
}

TEST(LcmSession, ALogPlayedOntoALiveBusIsRefusedAsRecorded) {
  if (access("/usr/bin/lcm-logplayer", X_OK) != 0) GTEST_SKIP() << "no /usr/bin/lcm-logplayer (liblcm-bin)";
  TempDir d;
  const std::string m = scene("monorail.toml");
  const Outputs ref = in_process(m, d / "ref", "3000");
  // The recording uses the default channels, and so does a pair started by hand.
  ASSERT_EQ(run({gyrostab_bin(), "run", m, "--ticks", "3000", "--no-progress", "--log", d / "run.lcmlog", "--out",
                 d / "rec"})
                .code,
            0);
  const pid_t player = spawn({"/usr/bin/lcm-logplayer", "--speed=1", d / "run.lcmlog"});
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const std::vector<std::string> common{"--ticks", "3000"};
  const pid_t c = spawn(cat({gyrostab_bin(), "controller", m, "--out", d / "c"}, common));
  const Exit p = run(cat({gyrostab_bin(), "plant", m, "--out", d / "p"}, common));
  const Exit ce = wait_for(c);
  kill(player, SIGTERM);
  wait_for(player);
  expect_identical(ref, outputs_of(d / "p"), "a live pair beside lcm-logplayer");
  const nlohmann::json pr = read_json(d / "p/report.json"), cr = read_json(d / "c/report.json");
  EXPECT_GT(refused(pr["link"], "recorded") + refused(cr["link"], "recorded"), 100u);
  EXPECT_EQ(p.code, refused(pr["link"], "recorded") > 0 ? 7 : 0);
  EXPECT_EQ(ce.code, refused(cr["link"], "recorded") > 0 ? 7 : 0);
}

// Copies each genuine command's envelope (session, sender, freshness + 1, its MAC) onto a forged command of
// the same tick and sends it at once, racing the genuine frame of the next tick.
struct Forger {
  lcm_t* lcm{nullptr};
  std::string actuator_channel;
  std::uint64_t forged{0};
  const msg::DeviceSignals& device = *tools::find_device_signals("monorail");

  void on_actuator(const msg::AnyActuatorFrame& a, const hil::LinkEnvelope& e) {
    if (a.signal[0] == 1999.0) return;  // one of ours
    msg::AnyActuatorFrame f = a;
    f.tick += 1;
    f.sequence += 1;
    f.signal[0] = 1999.0;  // the monorail's motor torque
    hil::LinkEnvelope fe = e;
    fe.freshness += 1;
    std::uint8_t buf[hil::kMaxEncodedSize];
    const int n = hil::encode(f, device, 0, buf, sizeof buf, fe);
    lcm_publish(lcm, actuator_channel.c_str(), buf, static_cast<unsigned>(n));
    ++forged;
  }
};

void on_actuator_message(const lcm_recv_buf_t* rbuf, const char*, void* user) {
  msg::AnyActuatorFrame a{};
  hil::LinkEnvelope e;
  auto* forger = static_cast<Forger*>(user);
  if (hil::decode(rbuf->data, static_cast<int>(rbuf->data_size), forger->device, a, nullptr, &e) ==
      hil::DecodeError::kOk)
    forger->on_actuator(a, e);
}

TEST(LcmSession, WithAKeyAForgerOnTheBusChangesNoCommand) {
  TempDir d;
  const std::string m = scene("monorail.toml");
  const Outputs ref = in_process(m, d / "ref", "3000");
  const std::string key = d / "link.key";
  {
    std::ofstream f(key);
    f << "# the link key of this test\n00112233445566778899aabbccddeeff\n";
  }
  ASSERT_EQ(chmod(key.c_str(), 0600), 0);
  Forger forger;
  forger.actuator_channel = "GYROSTAB_ACTUATOR_keyed";
  forger.lcm = lcm_create("udpm://239.255.76.67:7667?ttl=0");
  ASSERT_NE(forger.lcm, nullptr);
  lcm_subscription_set_queue_capacity(
      lcm_subscribe(forger.lcm, forger.actuator_channel.c_str(), on_actuator_message, &forger), 100'000);
  std::atomic<bool> stop{false};
  std::thread t([&] {
    while (!stop) lcm_handle_timeout(forger.lcm, 50);
  });
  const Exit e = run({gyrostab_bin(), "run", m, "--transport", "lcm", "--ticks", "3000", "--channel-suffix", "_keyed",
                      "--key-file", key, "--out", d / "lcm"});
  stop = true;
  t.join();
  lcm_destroy(forger.lcm);
  EXPECT_GT(forger.forged, 1000u);
  expect_identical(ref, outputs_of(d / "lcm"), "a keyed run with a forger on its bus");
  const nlohmann::json r = read_json(d / "lcm/report.json");
  EXPECT_EQ(r["link"]["session"]["authenticated"], true);
  // A forgery that reaches the plant before the genuine frame of its tick fails its MAC; one that comes after
  // it carries a freshness value already used (refused as replayed). Which of the two depends on timing.
  EXPECT_GT(refused(r["link"], "bad_mac") + refused(r["link"], "replayed"), 1000u) << "every forgery refused";
  EXPECT_GT(refused(r["link"], "bad_mac"), 0u);
  EXPECT_EQ(r["link"]["counters"]["accepted"], 3000);
  EXPECT_EQ(e.code, 7) << "the run completed, and says that its link was attacked";
}

TEST(LcmSession, AKeyFileOthersCanReadIsRefused) {
  TempDir d;
  const std::string key = d / "open.key";
  {
    std::ofstream f(key);
    f << "00112233445566778899aabbccddeeff\n";
  }
  ASSERT_EQ(chmod(key.c_str(), 0644), 0);
  EXPECT_EQ(run({gyrostab_bin(), "plant", scene("monorail.toml"), "--key-file", key, "--out", d / "p"}).code, 2);
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_LCM_TEST_MAIN()
