// Logs of the CAN bus: a lockstep run's --can-log is the bus itself (candump, listening at the same time,
// records the same frames in the same order); `gyrostab replay` replays it into the controller and finds
// every command frame bit for bit, and finds a flipped bit or a missing frame; and canplayer, replaying the
// log onto vcan, drives a listening controller process to send exactly the recorded command frames.
#include <gtest/gtest.h>
#include <signal.h>

#include <fstream>
#include <sstream>

#include "hil/can/frame_map.hpp"
#include "tests/hil/hil_test_support.hpp"
#include "tools/run/can_link_setup.hpp"

namespace gyrostab::testing {
namespace {

constexpr const char* kTicks = "300";

// The monorail's bus: its own map, generated from its signal table.
const can::DeviceBus& monorail_bus() {
  static const can::DeviceBus bus = tools::can_bus_of("monorail");
  return bus;
}

// A message's identifier as candump writes it (3 hex digits).
std::string hex_id(std::string_view name) {
  for (const can::MessageSpec& m : monorail_bus().messages()) {
    if (m.name != name) continue;
    char buf[8];
    std::snprintf(buf, sizeof buf, "%03X", m.id);
    return buf;
  }
  ADD_FAILURE() << "no message " << name;
  return "";
}

int id_of(std::string_view name) { return std::stoi(hex_id(name), nullptr, 16); }

std::vector<std::string> frame_lines(const std::string& text, bool commands_only = false) {
  std::vector<std::string> command_ids;
  for (std::size_t i = 0; i < monorail_bus().messages().size(); ++i) {
    const can::MessageSpec& m = monorail_bus().messages()[i];
    if (m.direction == can::Direction::kActuator) command_ids.push_back(hex_id(m.name));
  }
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '(') continue;
    std::string rest = line.substr(line.find(") ") + 2);  // "vcan0 ID#DATA": no timestamp
    const std::string id = rest.substr(rest.find(' ') + 1, 3);
    if (commands_only && std::find(command_ids.begin(), command_ids.end(), id) == command_ids.end()) continue;
    out.push_back(rest);
  }
  return out;
}

// A lockstep CAN run started by hand, the plant only once the controller's socket is open, so that no set
// needs a resend: the log then holds each tick's sets once. candump listens throughout.
struct RecordedRun {
  TempDir d;
  std::string log = d / "bus.candump";
  std::string candump = d / "candump.log";
  std::string scene_path = scene("monorail.toml");

  void record() {
    const pid_t dump = spawn({"/bin/sh", "-c", "exec candump -L " + can_if() + " > " + candump});
    ASSERT_TRUE(wait_for_can_listener(-1)) << "candump never opened its socket";
    // The controller runs until the plant's end-of-run set (docs/protocol.md): it is not told the tick count.
    const pid_t controller = spawn({gyrostab_bin(), "controller", scene_path, "--can-if", can_if(),
                                    "--out", d / "controller"});
    ASSERT_TRUE(wait_for_can_listener(id_of("SENSOR_HUB"))) << "the controller never opened its socket";
    const Exit p = run({gyrostab_bin(), "plant", scene_path, "--can-if", can_if(), "--ticks", kTicks, "--can-log", log,
                        "--out", d / "plant"});
    EXPECT_EQ(p.code, 0);
    EXPECT_EQ(wait_for(controller).code, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    kill(dump, SIGINT);
    wait_for(dump);
    const nlohmann::json r = read_json(d / "plant/report.json");
    ASSERT_EQ(r["link"]["counters"]["resent"], 0) << "the controller was not listening yet: start it earlier";
  }
};

TEST(CanReplay, TheRunsLogIsWhatCandumpSawOnTheBus) {
  RecordedRun run_;
  run_.record();
  const std::vector<std::string> ours = frame_lines(read_file(run_.log));
  const std::vector<std::string> theirs = frame_lines(read_file(run_.candump));
  // monorail: imu + drive2 → 3 sensor frames and 2 command frames per tick, and once more for the end of the
  // run (the plant's end-of-run set and the controller's acknowledgement).
  EXPECT_EQ(ours.size(), 5u * (std::stoul(kTicks) + 1));
  EXPECT_EQ(ours, theirs);
}

TEST(CanReplay, GyrostabReplayFindsEveryCommandFrameBitForBitAndCatchesAFlippedBit) {
  RecordedRun run_;
  run_.record();
  EXPECT_EQ(run({gyrostab_bin(), "replay", run_.log}).code, 0);

  // One bit of the precession brake in the command header of tick 150 flipped, CRC left as recorded: the
  // recorded frame is now rejected where the controller sends its frame ⇒ mismatch (4).
  std::string text = read_file(run_.log);
  std::size_t at = 0;
  const std::string header = "vcan0 " + hex_id("CONTROLLER_CMD") + "##";
  for (int n = 0; n <= 150; ++n) at = text.find(header, at + 1);
  ASSERT_NE(at, std::string::npos);
  const std::size_t byte40 = at + header.size() + 1 + 2 * 40;
  text[byte40] = text[byte40] == '0' ? '1' : '0';
  const std::string flipped = run_.d / "flipped.candump";
  std::ofstream(flipped) << text;
  EXPECT_EQ(run({gyrostab_bin(), "replay", flipped}).code, 4);

  // The log names the map it was recorded with (table and fingerprint): a log of another map is refused (5)
  // rather than decoded wrongly.
  std::string other_map = read_file(run_.log);
  const std::size_t map_line = other_map.find("# can-map monorail ");
  ASSERT_NE(map_line, std::string::npos) << "the log names its CAN map";
  other_map[map_line + std::string("# can-map monorail ").size()] ^= 0x01;
  const std::string remapped = run_.d / "remapped.candump";
  std::ofstream(remapped) << other_map;
  EXPECT_EQ(run({gyrostab_bin(), "replay", remapped}).code, 5);

  // The log cut after the end-of-run set: the controller's acknowledgement is missing ⇒ truncated (5).
  std::string cut = read_file(run_.log);
  for (int i = 0; i < 2; ++i) cut.erase(cut.rfind('(', cut.size() - 2));
  const std::string truncated = run_.d / "truncated.candump";
  std::ofstream(truncated) << cut;
  EXPECT_EQ(run({gyrostab_bin(), "replay", truncated}).code, 5);
}

TEST(CanReplay, CanplayerDrivesAListeningControllerToTheRecordedCommandFrames) {
  RecordedRun run_;
  run_.record();
  const std::string ctrl_log = run_.d / "controller.candump";
  const pid_t controller = spawn({gyrostab_bin(), "controller", run_.scene_path, "--can-if", can_if(),
                                  "--can-log", ctrl_log, "--out", run_.d / "listening"});
  ASSERT_TRUE(wait_for_can_listener(id_of("SENSOR_HUB"))) << "the controller never opened its socket";
  // One frame per millisecond (-t -g 1: 5 ms per monorail tick) rather than the recorded 1 kHz bursts: the
  // sanitizer build in the emulated VM fell behind the bursts, lost frames to the full socket queue and went
  // to its safe state. The pacing changes no frame.
  const Exit player = run({"/usr/bin/canplayer", "-t", "-g", "1", "-I", run_.log});
  EXPECT_EQ(player.code, 0);
  const Exit c = wait_for(controller);
  EXPECT_EQ(c.code, 0) << read_file(run_.d / "listening/report.json");
  // The controller drew its own sender id, so the command header's link envelope (sender, freshness, MAC:
  // bytes 44-63, hil/can/frame_map.hpp) and the CRC over it differ from the recording's; every other byte of
  // every command frame must be the recorded one.
  const std::string header = "vcan0 " + hex_id("CONTROLLER_CMD") + "##";
  const auto masked = [&header](std::vector<std::string> lines) {
    for (std::string& l : lines) {
      if (l.rfind(header, 0) != 0) continue;
      const std::size_t data = header.size() + 1;  // after the FD flags nibble
      const auto mask_byte = [&](std::size_t b) {
        if (data + 2 * b + 1 < l.size()) l.replace(data + 2 * b, 2, "xx");
      };
      mask_byte(can::kCrcByte);
      for (std::size_t b = can::kLinkSenderByte; b < can::kHeaderLength; ++b) mask_byte(b);
    }
    return lines;
  };
  const std::vector<std::string> recorded = masked(frame_lines(read_file(run_.log), true));
  const std::vector<std::string> answered = masked(frame_lines(read_file(ctrl_log), true));
  EXPECT_EQ(recorded.size(), 2u * (std::stoul(kTicks) + 1));  // with the end-of-run acknowledgement
  EXPECT_EQ(answered, recorded) << "the controller's command frames differ from the recorded ones";
  // It bound to the recorded plant's session: the log's sets are that session's, and nothing was refused.
  const nlohmann::json r = read_json(run_.d / "listening/report.json");
  EXPECT_EQ(r["link"]["session"]["refused"]["foreign"], 0);
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_HIL_TEST_MAIN()
