// Fault reactions of the plant and controller processes over LCM (docs/architecture.md, faults and safe
// states), each through the fault
// injections of `gyrostab run --transport lcm` or by killing a process:
//   controller: sensor frames missing for N ticks ⇒ hold, then the safe state, status says why;
//               NaN sensor frames ⇒ the fault monitor holds the last good one;
//               the plant killed ⇒ receive timeout, the safe state within hold_ticks + 1 ticks, exit 6;
//   plant:      actuator frames rejected (NaN) or missing (real time) ⇒ zero torque for those ticks;
//               a command withheld (lockstep) ⇒ zero torque for that tick after half the receive timeout;
//               the controller silent or killed ⇒ receive timeout, zero torque after `latency` ticks, exit 6.
// The scene is the monorail (1 kHz, latency 1, the fault monitor's default hold_ticks = 1); signals.csv has a
// row every 10 ticks: the row at t = (k + 1)·1 ms shows the command applied in tick k, which latency 1 makes
// the command of tick k − 1.
#include <gtest/gtest.h>

#include "tests/lcm/lcm_test_support.hpp"

namespace gyrostab::testing {
namespace {

constexpr std::uint32_t kSensorMissing = 1u << 0, kSensorNonFinite = 1u << 2, kHolding = 1u << 8,
                        kSafeState = 1u << 9;

std::vector<std::string> lcm_run(const std::string& out, const std::string& ticks) {
  return {gyrostab_bin(), "run", scene("monorail.toml"), "--transport", "lcm", "--ticks", ticks,
          "--out",        out};
}

// The CSV cell of `column` in the row of time t = row_tick · 1 ms (rows every 10 ticks, the first at tick
// 10).
std::string cell_at(const std::string& csv, const std::string& column, int row_tick) {
  const auto col = csv_column(csv, column);
  const std::size_t row = static_cast<std::size_t>(row_tick / 10 - 1);
  return row < col.size() ? col[row] : "<no row>";
}

TEST(LcmFaults, SensorFramesMissingForFiveTicksTripTheSafeStateAndSayWhy) {
  TempDir d;
  const Exit e = run(cat(lcm_run(d / "out", "1500"), {"--drop-sensor", "1000:5"}));
  ASSERT_EQ(e.code, 0);
  const nlohmann::json r = read_json(d / "out/report.json");
  const nlohmann::json& fm = r["timing"]["controller"]["fault_monitor"];
  EXPECT_EQ(fm["missing"], 5);
  EXPECT_EQ(fm["trips"], 1);
  // hold_ticks = 1: tick 1000 is held, tick 1001 is the safe state.
  EXPECT_EQ(r["controller_process"]["link"]["safe_state_tick"], 1001);
  EXPECT_EQ(r["controller_process"]["link"]["missing_ticks"], 5);
  EXPECT_EQ(r["link"]["counters"]["dropped_by_fault"], 5);
  // The commands of ticks 1000-1004 were answered late (after tick 1005's frame): the plant refused them as
  // stale and its drives were at zero torque those ticks.
  EXPECT_EQ(r["link"]["counters"]["rejected"]["stale"], 5);
  EXPECT_EQ(r["link"]["drive_watchdog"]["zero_torque_ticks"], 5);
  // The safe command with the reason while the link is down; row 1010 shows the command of 1008.
  const std::string csv = read_file(d / "out/signals.csv");
  EXPECT_EQ(std::stoul(cell_at(csv, "status_bits", 1010)), kSafeState | kSensorMissing);
  EXPECT_EQ(cell_at(csv, "motor_torque_Nm", 1010), "0");
  // The frames are back from tick 1005: after 10 good ones the supervisor acknowledges (a link-only trip),
  // and the next good frame re-arms the law. Row 1030 shows the command of 1028.
  const nlohmann::json& safe = r["controller_process"]["link"]["safe_state"];
  EXPECT_EQ(safe["link_loss_acknowledged"], 1);
  EXPECT_EQ(fm["recoveries"], 1);
  EXPECT_EQ(safe["ticks"], 14) << "ticks 1001-1014: four without frames, then ten good ones";
  EXPECT_EQ(std::stoul(cell_at(csv, "status_bits", 1030)), 0u);
  EXPECT_NE(cell_at(csv, "motor_torque_Nm", 1030), "0");
}

TEST(LcmFaults, TenPercentLossInLockstepChangesNoBit) {
  TempDir d;
  ASSERT_EQ(run({gyrostab_bin(), "run", scene("monorail.toml"), "--ticks", "1000", "--no-progress", "--out",
                 d / "inproc"})
                .code,
            0);
  const Exit e = run(cat(lcm_run(d / "out", "1000"), {"--loss", "0.1"}));
  ASSERT_EQ(e.code, 0);
  const nlohmann::json r = read_json(d / "out/report.json");
  EXPECT_GT(r["link"]["counters"]["lost_by_fault"].get<int>(), 50);
  EXPECT_GT(r["controller_process"]["link"]["counters"]["lost_by_fault"].get<int>(), 50);
  EXPECT_EQ(r["figures"].dump(), read_json(d / "inproc/report.json")["figures"].dump());
  EXPECT_TRUE(read_file(d / "out/signals.csv") == read_file(d / "inproc/signals.csv"))
      << "the resends recover every lost frame";
}

TEST(LcmFaults, TenPercentLossInRealTimeEndsDegradedNotCompleted) {
  TempDir d;
  const Exit e = run(cat(lcm_run(d / "out", "3000"), {"--real-time", "--loss", "0.1"}));
  EXPECT_EQ(e.code, 8) << "degraded";
  const nlohmann::json r = read_json(d / "out/report.json");
  const nlohmann::json& safe = r["controller_process"]["link"]["safe_state"];
  EXPECT_GT(safe["share"].get<double>(), 0.05);
  EXPECT_GT(safe["link_loss_acknowledged"].get<int>(), 5) << "it recovers after each dropout";
  EXPECT_LT(safe["share"].get<double>(), 0.9) << "and is not latched for the rest of the run";
  EXPECT_NE(r["processes"]["what_happened"].get<std::string>().find("degraded"), std::string::npos);
}

TEST(LcmFaults, ANonFiniteSensorFrameIsHeldOverByTheFaultMonitor) {
  TempDir d;
  // Tick 1008's frame carries a NaN; row 1010 shows the command of tick 1008.
  const Exit e = run(cat(lcm_run(d / "out", "1200"), {"--corrupt-sensor", "1008:1"}));
  ASSERT_EQ(e.code, 0);
  const nlohmann::json r = read_json(d / "out/report.json");
  const nlohmann::json& fm = r["timing"]["controller"]["fault_monitor"];
  EXPECT_EQ(fm["non_finite"], 1);
  EXPECT_EQ(fm["held_ticks"], 1);
  EXPECT_EQ(fm["trips"], 0);
  EXPECT_EQ(r["controller_process"]["link"]["counters"]["accepted"], 1200)
      << "the link passes content to the monitor";
  const std::string csv = read_file(d / "out/signals.csv");
  EXPECT_EQ(std::stoul(cell_at(csv, "status_bits", 1010)), kHolding | kSensorNonFinite);
  EXPECT_EQ(std::stoul(cell_at(csv, "status_bits", 1020)), 0u) << "recovered: a held tick is not latched";
}

// A sensor fault stays latched: a run whose last 99 of 5000 sensor frames carry a NaN holds one tick, then
// ends in the safe state — 98 ticks, under the 5 % share, and still not "completed".
TEST(LcmFaults, ARunThatEndsInALatchedSafeStateIsDegradedWhateverTheShare) {
  TempDir d;
  const Exit e = run(cat(lcm_run(d / "out", "5000"), {"--corrupt-sensor", "4901:99"}));
  EXPECT_EQ(e.code, 8) << "degraded";
  const nlohmann::json r = read_json(d / "out/report.json");
  const nlohmann::json& safe = r["controller_process"]["link"]["safe_state"];
  EXPECT_LT(safe["share"].get<double>(), 0.05);
  EXPECT_EQ(safe["at_end"], true);
  EXPECT_NE(r["processes"]["what_happened"].get<std::string>().find("ended in the safe state"), std::string::npos)
      << r["processes"]["what_happened"];
}

TEST(LcmFaults, RejectedActuatorFramesGiveZeroTorqueForThoseTicks) {
  TempDir d;
  const Exit e = run(cat(lcm_run(d / "out", "1600"), {"--corrupt-actuator", "1500:20"}));
  ASSERT_EQ(e.code, 0);
  const nlohmann::json r = read_json(d / "out/report.json");
  const nlohmann::json& c = r["link"]["counters"];
  EXPECT_EQ(c["rejected"]["non_finite"], 20);
  EXPECT_EQ(c["accepted"], 1580);
  EXPECT_EQ(r["link"]["drive_watchdog"]["zero_torque_ticks"], 20);
  EXPECT_EQ(r["link"]["drive_watchdog"]["first_tick"], 1500);
  const std::string csv = read_file(d / "out/signals.csv");
  for (const int row : {1510, 1520}) {
    EXPECT_EQ(cell_at(csv, "motor_torque_Nm", row), "0") << row;
    EXPECT_EQ(cell_at(csv, "status_bits", row), "0") << row;
  }
  EXPECT_NE(cell_at(csv, "motor_torque_Nm", 1530), "0") << "the controller's commands apply again";
}

TEST(LcmFaults, AWithheldCommandGivesZeroTorqueForItsTickAndTheRunGoesOn) {
  TempDir d;
  // Lockstep: the controller steps tick 998 but its command never leaves. The plant waits half the receive
  // timeout for it, gives the drives zero torque for that tick and goes on; the row of t = 1000 ms shows it.
  const Exit e = run(cat(lcm_run(d / "out", "1600"), {"--drop-actuator", "998:1", "--timeout-ms", "400"}));
  ASSERT_EQ(e.code, 0);
  const nlohmann::json r = read_json(d / "out/report.json");
  EXPECT_EQ(r["processes"]["what_happened"], "completed");
  EXPECT_EQ(r["timing"]["ticks"], 1600);
  EXPECT_EQ(r["link"]["counters"]["accepted"], 1599);
  EXPECT_EQ(r["link"]["drive_watchdog"]["zero_torque_ticks"], 1);
  EXPECT_EQ(r["link"]["drive_watchdog"]["first_tick"], 998);
  EXPECT_FALSE(r["link"].contains("peer")) << "the controller was never lost";
  const std::string csv = read_file(d / "out/signals.csv");
  EXPECT_EQ(cell_at(csv, "motor_torque_Nm", 1000), "0");
  EXPECT_NE(cell_at(csv, "motor_torque_Nm", 990), "0");
  EXPECT_NE(cell_at(csv, "motor_torque_Nm", 1010), "0") << "the controller's commands apply again";
}

TEST(LcmFaults, ASilentControllerIsLostAtTheReceiveTimeoutAndTheDrivesStop) {
  TempDir d;
  // The controller ends after tick 999 (its --ticks); the plant runs on. Tick 1000's command is missing (zero
  // torque after half the timeout), and the second silent tick in a row waits for the receive timeout.
  const std::vector<std::string> common{"--channel-suffix", "_silent"};
  const pid_t c = spawn(cat({gyrostab_bin(), "controller", scene("monorail.toml"), "--out", d / "c", "--ticks",
                             "1000", "--timeout-ms", "3000"},
                            common));
  const Exit p = run(cat({gyrostab_bin(), "plant", scene("monorail.toml"), "--out", d / "p", "--ticks", "3000",
                          "--timeout-ms", "300"},
                         common));
  EXPECT_EQ(p.code, 6);
  const nlohmann::json r = read_json(d / "p/report.json");
  const nlohmann::json& peer = r["link"]["peer"];
  EXPECT_EQ(peer["lost"], true);
  EXPECT_EQ(peer["lost_at_tick"], 1001);
  EXPECT_EQ(peer["zero_torque_from_tick"], 1002);  // latency 1
  EXPECT_GE(peer["silent_ms"].get<double>(), 300.0);
  EXPECT_EQ(r["link"]["drive_watchdog"]["first_tick"], 1000);
  EXPECT_GE(r["link"]["counters"]["resent"].get<int>(), 5) << "it asked again every 20 ms";
  EXPECT_EQ(r["timing"]["ticks"], 1003) << "the plant stops after the first tick integrated at zero torque";
  EXPECT_NE(r["link"]["what_happened"].get<std::string>().find("controller lost"), std::string::npos);
  EXPECT_EQ(wait_for(c).code, 0) << "the controller ran the ticks it was asked for";
}

// Runs a long scene over LCM, kills `role` with SIGKILL after ~1.5 s and returns the merged report.
nlohmann::json kill_one(const TempDir& d, const std::string& role, Exit& run_exit) {
  const pid_t p = spawn({gyrostab_bin(), "run", scene("ship-roll-damper-active.toml"), "--transport", "lcm",
                         "--timeout-ms", "300", "--out", d / "out"});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const std::vector<pid_t> victims = children_matching(p, "gyrostab " + role + " ");
  EXPECT_EQ(victims.size(), 1u);
  for (const pid_t v : victims) kill(v, SIGKILL);
  run_exit = wait_for(p);
  return read_json(d / "out/report.json");
}

TEST(LcmFaults, KillMinus9OfTheControllerStopsThePlantsDrivesAndIsReported) {
  TempDir d;
  Exit e;
  const nlohmann::json r = kill_one(d, "controller", e);
  EXPECT_EQ(e.code, 6);
  EXPECT_EQ(r["processes"]["controller"]["killed_by_signal"], SIGKILL);
  EXPECT_EQ(r["processes"]["plant"]["exit_code"], 6);
  const nlohmann::json& peer = r["link"]["peer"];
  ASSERT_EQ(peer["lost"], true);
  const int lost = peer["lost_at_tick"].get<int>();
  EXPECT_GT(lost, 0);
  EXPECT_EQ(peer["zero_torque_from_tick"], lost + 1);
  EXPECT_EQ(r["timing"]["ticks"], lost + 2);
  // The first silent tick is a missing command (zero torque after half the timeout), the second is the lost
  // controller.
  EXPECT_EQ(r["link"]["drive_watchdog"]["first_tick"], lost - 1);
}

TEST(LcmFaults, KillMinus9OfThePlantTakesTheControllerToItsSafeStateAndIsReported) {
  TempDir d;
  Exit e;
  const nlohmann::json r = kill_one(d, "plant", e);
  EXPECT_EQ(e.code, 6);
  EXPECT_EQ(r["processes"]["plant"]["killed_by_signal"], SIGKILL);
  EXPECT_EQ(r["processes"]["controller"]["exit_code"], 6);
  const nlohmann::json& link = r["controller_process"]["link"];
  ASSERT_EQ(link["peer"]["lost"], true);
  const int lost = link["peer"]["lost_at_tick"].get<int>();
  EXPECT_GT(lost, 0);
  // hold_ticks = 1: the lost tick is held, the next is safe.
  EXPECT_EQ(link["peer"]["safe_state_tick"], lost + 1);
  EXPECT_EQ(link["peer"]["reaction_ticks"], 2);
  EXPECT_LT(link["peer"]["silent_ms"].get<double>(), 2000.0) << "the steady-state timeout, not the start one";
  EXPECT_EQ(r["timing"]["controller"]["fault_monitor"]["trips"], 1);
  EXPECT_NE(r["processes"]["what_happened"].get<std::string>().find("plant killed by signal 9"),
            std::string::npos);
}

// Starts the 900 s ship over LCM (`run` with its two children) and lets it run for `ms`.
pid_t start_long_run(const TempDir& d, int ms, std::vector<pid_t>& children) {
  const pid_t p = spawn({gyrostab_bin(), "run", scene("ship-roll-damper-active.toml"), "--transport", "lcm",
                         "--out", d / "out"});
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  children = children_matching(p, "gyrostab ");
  return p;
}

TEST(LcmFaults, SigtermToTheRunParentStopsBothChildrenAndMergesTheirOutputs) {
  TempDir d;
  std::vector<pid_t> children;
  const pid_t p = start_long_run(d, 1500, children);
  EXPECT_EQ(children.size(), 2u);
  kill(p, SIGTERM);
  const Exit e = wait_for(p);
  EXPECT_EQ(e.code, 128 + SIGTERM);
  for (const pid_t c : children) EXPECT_NE(::kill(c, 0), 0) << "child " << c << " outlived its parent";
  const nlohmann::json r = read_json(d / "out/report.json");
  EXPECT_NE(r["processes"]["what_happened"].get<std::string>().find("stopped by SIGTERM"), std::string::npos);
  EXPECT_EQ(r["processes"]["plant"]["exit_code"], 128 + SIGTERM);
  EXPECT_EQ(r["processes"]["controller"]["exit_code"], 128 + SIGTERM);
  EXPECT_TRUE(r.contains("controller_process")) << "the controller's report was merged";
  const int ticks = r["timing"]["ticks"].get<int>();
  EXPECT_GT(ticks, 0);
  EXPECT_LT(ticks, 900'000) << "it stopped early";
  // The ship records a row every 50 ticks.
  EXPECT_NEAR(static_cast<double>(csv_column(read_file(d / "out/signals.csv"), "t_s").size()), ticks / 50, 1.0)
      << "the CSV holds every recorded tick up to the stop";
}

TEST(LcmFaults, KillingTheRunParentLeavesNoOrphans) {
  TempDir d;
  std::vector<pid_t> children;
  const pid_t p = start_long_run(d, 1000, children);
  ASSERT_EQ(children.size(), 2u);
  kill(p, SIGKILL);
  wait_for(p);
  // The children get SIGTERM when their parent dies (PR_SET_PDEATHSIG), stop at a tick boundary and exit.
  // They are the test's grandchildren, reparented to init (or the nearest subreaper): poll until gone.
  for (int i = 0; i < 100; ++i) {
    bool alive = false;
    for (const pid_t c : children) alive = alive || ::kill(c, 0) == 0;
    if (!alive) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  for (const pid_t c : children) {
    const std::string state = read_file("/proc/" + std::to_string(c) + "/stat");
    EXPECT_TRUE(state.empty() || state.find(") Z") != std::string::npos) << "child " << c << " still runs: " << state;
  }
}

TEST(LcmFaults, RealTimeMissingActuatorFramesGiveZeroTorqueAndJitterIsReported) {
  TempDir d;
  const Exit e = run(cat(lcm_run(d / "out", "2000"), {"--real-time", "--drop-actuator", "1000:20"}));
  const nlohmann::json r = read_json(d / "out/report.json");
  // A shared VM misses real-time frames of its own; the verdict must say what the share of safe-state ticks
  // was: completed up to kMaxSafeShare, degraded (exit 8) beyond.
  const double share = r["controller_process"]["link"]["safe_state"]["share"].get<double>();
  EXPECT_EQ(e.code, share > 0.05 ? 8 : 0) << "safe-state share " << share;
  EXPECT_EQ(r["timing"]["mode"], "real_time");
  for (const char* h : {"jitter_ns", "lateness_ns", "compute_ns", "period_ns"}) {
    EXPECT_GT(r["timing"][h]["samples"].get<int>(), 1900) << h;
    EXPECT_LE(r["timing"][h]["p50_ns"].get<long>(), r["timing"][h]["p99_ns"].get<long>()) << h;
    EXPECT_LE(r["timing"][h]["p99_ns"].get<long>(), r["timing"][h]["max_ns"].get<long>()) << h;
  }
  EXPECT_EQ(r["controller_process"]["timing"]["mode"], "real_time");
  EXPECT_TRUE(r["link"].contains("real_time_setup"));
  // Timing on a shared VM is noisy: other ticks may miss their window too, these 20 cannot arrive.
  EXPECT_GE(r["link"]["drive_watchdog"]["zero_torque_ticks"].get<int>(), 20);
  EXPECT_GE(r["link"]["counters"]["missed_frames"].get<int>(), 20);
  const std::string csv = read_file(d / "out/signals.csv");
  EXPECT_EQ(cell_at(csv, "motor_torque_Nm", 1010), "0");
  EXPECT_EQ(cell_at(csv, "motor_torque_Nm", 1020), "0");
}

TEST(LcmFaults, AProcessWithoutPeerGivesUpAtTheStartTimeout) {
  TempDir d;
  const Exit c = run({gyrostab_bin(), "controller", scene("monorail.toml"), "--start-timeout-ms", "200",
                      "--channel-suffix", "_alone", "--out", d / "c"});
  EXPECT_EQ(c.code, 6);
  const nlohmann::json rc = read_json(d / "c/report.json");
  EXPECT_EQ(rc["link"]["peer"]["lost_at_tick"], 0);
  EXPECT_EQ(rc["link"]["peer"]["safe_state_tick"], 0)
      << "awaiting the first frame, the command is the safe one";
  const Exit p = run({gyrostab_bin(), "plant", scene("monorail.toml"), "--start-timeout-ms", "200",
                      "--channel-suffix", "_alone", "--out", d / "p"});
  EXPECT_EQ(p.code, 6);
  const nlohmann::json rp = read_json(d / "p/report.json");
  EXPECT_EQ(rp["link"]["peer"]["lost_at_tick"], 0);
  EXPECT_GT(rp["link"]["counters"]["resent"].get<int>(), 0);
}

TEST(LcmFaults, BadOptionsAreRefusedWithExitTwo) {
  EXPECT_EQ(run({gyrostab_bin(), "plant", scene("monorail.toml"), "--channel-suffix", "a.b"}).code, 2);
  EXPECT_EQ(run({gyrostab_bin(), "run", scene("monorail.toml"), "--real-time"}).code, 2);
  EXPECT_NE(
      run({gyrostab_bin(), "run", scene("monorail.toml"), "--transport", "lcm", "--jitter", "abc"}).code, 0);
  EXPECT_NE(run({gyrostab_bin(), "controller", scene("monorail.toml"), "--drop-actuator", "5"}).code, 0);
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_LCM_TEST_MAIN()
