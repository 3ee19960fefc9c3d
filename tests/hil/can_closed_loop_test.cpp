// Lockstep over CAN FD on vcan is bit-identical to the in-process run (docs/architecture.md, the loop): for
// every shipped scene, `gyrostab run SCENE --transport can` (plant and controller processes, SocketCAN, the
// frame map with CRC and alive counters) against `gyrostab run SCENE` — report.json "figures" and signals.csv
// compared byte for byte — shortened with --ticks to keep the label fast in the VM. A scene whose bus load
// exceeds 70 % is refused instead (exit 2), and the test checks that exactly the scenes the bus-load
// arithmetic refuses are refused. The report's CAN section must show a clean bus: every set completed,
// nothing rejected.
#include <gtest/gtest.h>

#include <cctype>

#include "hil/can/bus_load.hpp"
#include "tests/hil/hil_test_support.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/run/can_link_setup.hpp"

namespace gyrostab::testing {
namespace {

constexpr int kTicks = 400;

// The device and tick of a scene file, read from its text (the [scene] device and [loop] tick_us lines).
// Plain string search: std::regex trips GCC 12's -Wmaybe-uninitialized under the sanitizers.
std::string value_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("\n" + key);
  if (at == std::string::npos) return "";
  std::size_t i = text.find('=', at);
  if (i == std::string::npos) return "";
  ++i;
  while (i < text.size() && (text[i] == ' ' || text[i] == '"')) ++i;
  std::size_t j = i;
  while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
  return text.substr(i, j - i);
}

tools::LoopConfig loop_of(const std::string& path) {
  const std::string text = read_file(path);
  tools::LoopConfig cfg;
  cfg.device = value_after(text, "device");
  const std::string tick = value_after(text, "tick_us");
  if (!tick.empty()) cfg.tick_ns = std::stoll(tick) * 1000;
  return cfg;
}

TEST(CanClosedLoop, EveryShippedSceneIsBitIdenticalToInProcessOrRefusedForBusLoad) {
  const auto scenes = shipped_scenes();
  ASSERT_FALSE(scenes.empty());
  int identical = 0, refused = 0;
  for (const auto& path : scenes) {
    SCOPED_TRACE(path);
    const tools::LoopConfig cfg = loop_of(path);
    ASSERT_FALSE(cfg.device.empty());
    can::BusLoad load;
    const bool over = !tools::can_bus_load_problem(cfg, tools::TransportOptions{}, load).empty();
    TempDir d;
    const std::string ticks = std::to_string(kTicks);
    const Exit e = run({gyrostab_bin(), "run", path, "--transport", "can", "--can-if", can_if(), "--ticks", ticks,
                        "--no-progress", "--out", d / "can"});
    if (over) {
      EXPECT_EQ(e.code, 2) << "bus load " << load.load << ": CAN must refuse the scene";
      ++refused;
      continue;
    }
    ASSERT_EQ(e.code, 0) << "bus load " << load.load;
    const Exit i = run({gyrostab_bin(), "run", path, "--ticks", ticks, "--no-progress", "--out", d / "inproc"});
    ASSERT_EQ(i.code, 0);
    const Outputs a = outputs_of(d / "inproc"), b = outputs_of(d / "can");
    ASSERT_FALSE(a.figures.empty());
    ASSERT_FALSE(a.csv.empty());
    EXPECT_EQ(a.figures, b.figures) << "figures differ";
    EXPECT_TRUE(a.csv == b.csv) << "signals.csv differs";
    const nlohmann::json r = read_json(d / "can/report.json");
    EXPECT_EQ(r["processes"]["transport"], "can");
    EXPECT_EQ(r["processes"]["what_happened"], "completed");
    EXPECT_EQ(r["link"]["counters"]["accepted"], kTicks);
    const nlohmann::json& pc = r["link"]["can"];
    const nlohmann::json& cc = r["controller_process"]["link"]["can"];
    // One set per tick and one for the end of the run (the plant's end-of-run set, the controller's
    // acknowledgement), plus at most one per lockstep resend of the other side (a start-up resend before the
    // controller listened, or an answer slower than the CAN link's 250 ms resend interval on a very loaded
    // VM): resends carry new alive counters and are never rejected. The end of the run is acknowledged.
    const int plant_resent = r["link"]["counters"]["resent"].get<int>();
    const int controller_resent = r["controller_process"]["link"]["counters"]["resent"].get<int>();
    EXPECT_GE(pc["actuator_rx"]["sets_completed"].get<int>(), kTicks);
    EXPECT_LE(pc["actuator_rx"]["sets_completed"].get<int>(), kTicks + 1 + controller_resent);
    EXPECT_EQ(r["link"]["end_of_run"]["acknowledged"], true) << r["link"].dump();
    EXPECT_TRUE(pc["actuator_rx"]["rejected"].empty()) << pc["actuator_rx"].dump();
    EXPECT_GE(cc["sensor_rx"]["sets_completed"].get<int>(), kTicks);
    EXPECT_LE(cc["sensor_rx"]["sets_completed"].get<int>(), kTicks + 1 + plant_resent);
    EXPECT_TRUE(cc["sensor_rx"]["rejected"].empty()) << cc["sensor_rx"].dump();
    EXPECT_EQ(pc["socket"]["kernel_drops"], 0);
    EXPECT_DOUBLE_EQ(pc["bus_load"]["load"].get<double>(), load.load);
    EXPECT_EQ(r["timing"]["controller"]["fault_monitor"]["good_frames"], kTicks);
    ++identical;
  }
  std::printf("[ result ] %d scenes bit-identical over CAN, %d refused for bus load\n", identical, refused);
  EXPECT_GT(identical, 0);
}

// The CMG cluster on its own node: the four units' gimbal angles and rates in CLUSTER_FB (seven values) and
// CLUSTER_FB_2 (the eighth), their rate commands in CLUSTER_CMD (docs/can.md). At 1 kHz that is 87.6 % of a
// 1/5 Mbit/s bus (refused above), 62.2 % with an 8 Mbit/s data phase.
TEST(CanClosedLoop, CmgClusterOverItsClusterNodeWithAnEightMegabitDataPhase) {
  TempDir d;
  const std::string path = scene("cmg-cluster-singularity-robust.toml");
  const Exit e = run({gyrostab_bin(), "run", path, "--transport", "can", "--can-if", can_if(), "--can-data-bitrate",
                      "8e6", "--ticks", "2000", "--no-progress", "--out", d / "can"});
  ASSERT_EQ(e.code, 0);
  const Exit i = run({gyrostab_bin(), "run", path, "--ticks", "2000", "--no-progress", "--out", d / "inproc"});
  ASSERT_EQ(i.code, 0);
  const Outputs a = outputs_of(d / "inproc"), b = outputs_of(d / "can");
  EXPECT_EQ(a.figures, b.figures);
  EXPECT_TRUE(a.csv == b.csv) << "signals.csv differs";
  const nlohmann::json r = read_json(d / "can/report.json");
  EXPECT_NEAR(r["link"]["can"]["bus_load"]["load"].get<double>(), 0.621625, 1e-9);
  EXPECT_EQ(r["link"]["can"]["bus_load"]["frames_per_tick"], 6) << r["link"]["can"].dump();
  EXPECT_EQ(r["link"]["can"]["nodes"], nlohmann::json::array({"sensor_hub", "controller", "imu", "cluster"}));
}

TEST(CanClosedLoop, PlantAndControllerStartedByHandInEitherOrder) {
  TempDir d;
  const std::string path = scene("servo-gyro.toml");
  // servo-gyro's two drives at 1 kHz load a 1/5 Mbit/s bus to 70.9 % (docs/can.md): an 8 Mbit/s data phase.
  const std::vector<std::string> common{"--can-if", can_if(), "--can-data-bitrate", "8e6", "--ticks", "300"};
  const Exit i = run({gyrostab_bin(), "run", path, "--ticks", "300", "--no-progress", "--out", d / "inproc"});
  ASSERT_EQ(i.code, 0);
  // Plant first: it resends its first sensor set until the controller answers. The controller starts only
  // after a frame was on the bus (`candump -n 1` exits on the first one), so nobody listened to that frame
  // however slowly the plant starts (sanitizer builds in the emulated VM take seconds).
  const pid_t first_frame = spawn({"/bin/sh", "-c", "exec candump -n 1 " + can_if() + " > /dev/null"});
  ASSERT_TRUE(wait_for_can_listener(-1)) << "candump never opened its socket";
  const pid_t plant = spawn(cat({gyrostab_bin(), "plant", path, "--out", d / "plant"}, common));
  EXPECT_EQ(wait_for(first_frame).code, 0);
  const pid_t controller = spawn(cat({gyrostab_bin(), "controller", path, "--out", d / "controller"}, common));
  EXPECT_EQ(wait_for(plant).code, 0);
  EXPECT_EQ(wait_for(controller).code, 0);
  const Outputs a = outputs_of(d / "inproc"), b = outputs_of(d / "plant");
  EXPECT_EQ(a.figures, b.figures);
  EXPECT_TRUE(a.csv == b.csv);
  const nlohmann::json r = read_json(d / "plant/report.json");
  EXPECT_GT(r["link"]["counters"]["resent"].get<int>(), 0) << "the first sensor set went out before anyone listened";
}

TEST(CanClosedLoop, ASceneOverTheBusLoadLimitIsRefusedBeforeAnythingIsSent) {
  TempDir d;
  // power-stabilizer-drive: 10 kHz current loops across the bus, far beyond any CAN FD bus.
  const Exit e = run({gyrostab_bin(), "plant", scene("power-stabilizer-drive.toml"), "--can-if", can_if(), "--ticks",
                      "10", "--out", d / "p"});
  EXPECT_EQ(e.code, 2);
  // The same with a generous data phase is still refused: the arbitration phase alone exceeds the tick.
  const Exit f = run({gyrostab_bin(), "plant", scene("power-stabilizer-drive.toml"), "--can-if", can_if(),
                      "--can-data-bitrate", "8e6", "--ticks", "10", "--out", d / "q"});
  EXPECT_EQ(f.code, 2);
}

// Real time over CAN (as over LCM, docs/transport.md): both sides paced by CLOCK_MONOTONIC deadlines; the
// report carries period, jitter, lateness and compute time; actuator frames withheld for 10 ticks give zero
// torque for those ticks (the drive watchdog), and the run ends with the verdict its safe-state share earns. The 20 ms Schuler monitor scene keeps
// the emulated VM (TCG, ~6 700 FD frames/s) inside its deadlines; timing itself is never asserted.
TEST(CanClosedLoop, RealTimeRunReportsItsTimingAndMissingCommandsGiveZeroTorque) {
  TempDir d;
  const Exit e = run({gyrostab_bin(), "run", scene("schuler-gyro-pendulum.toml"), "--transport", "can", "--can-if",
                      can_if(), "--real-time", "--ticks", "150", "--drop-actuator", "60:10", "--no-progress",
                      "--out", d / "rt"});
  const nlohmann::json r = read_json(d / "rt/report.json");
  // The verdict follows the share of safe-state ticks (docs/transport.md): completed up to 5 %, degraded
  // (exit 8) beyond; an emulated VM may miss real-time frames of its own.
  const double share = r["controller_process"]["link"]["safe_state"]["share"].get<double>();
  ASSERT_EQ(e.code, share > 0.05 ? 8 : 0) << "safe-state share " << share;
  EXPECT_EQ(r["processes"]["transport"], "can");
  EXPECT_EQ(r["timing"]["mode"], "real_time");
  EXPECT_EQ(r["controller_process"]["timing"]["mode"], "real_time");
  for (const char* h : {"jitter_ns", "lateness_ns", "compute_ns", "period_ns"}) {
    EXPECT_GT(r["timing"][h]["samples"].get<int>(), 140) << h;
    EXPECT_LE(r["timing"][h]["p50_ns"].get<long>(), r["timing"][h]["p99_ns"].get<long>()) << h;
    EXPECT_LE(r["timing"][h]["p99_ns"].get<long>(), r["timing"][h]["max_ns"].get<long>()) << h;
  }
  // The controller follows the plant's clock: a slow first step (a sanitizer build in the emulated VM takes
  // ~14 ms of the 20 ms tick) once put its deadlines ahead of every later frame, and it accepted 1 of 150.
  const nlohmann::json& cc = r["controller_process"]["link"]["counters"];
  EXPECT_GE(cc["accepted"].get<int>(), 100) << cc.dump();
  std::printf("[ measured ] controller accepted %d of 150 sensor frames, re-phased %d times\n",
              cc["accepted"].get<int>(), cc["resynced"].get<int>());
  EXPECT_GE(r["link"]["drive_watchdog"]["zero_torque_ticks"].get<int>(), 10);
  EXPECT_GE(r["link"]["counters"]["missed_frames"].get<int>(), 10);
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_HIL_TEST_MAIN()
