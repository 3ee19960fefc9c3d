// Bad frames on the bus reach the firmware as "no sensor frame this tick" and nothing else: a controller
// process (`gyrostab controller --can-if`) is driven by this test acting as the plant over vcan. After good
// ticks 0..K-1, from tick K on one frame of every sensor set is bad in one way — wrong length, unknown id,
// bad CRC, stale (repeated) alive counter, skipped alive counter — or the bus falls silent. Each bad frame
// is rejected and counted under its cause in the controller's report; the controller steps tick K without a
// frame when its receive timeout expires (lockstep: the plant is lost), holds the last good frame for
// hold_ticks = 1 tick and is in the safe state at tick K + 1 — the stated reaction (fault_monitor.hpp: the
// safe state starts at the (hold_ticks + 1)-th consecutive bad tick) — and exits 6.
// And a cangen flood on the same bus (random ids, and classic frames on one of our ids) does not stall a
// lockstep run: it completes bit-identical to in-process, the flood's frames on our id counted as rejected.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>

#include "firmware/msg/fault_bits.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/link_seal.hpp"
#include "hil/can/socketcan_link.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "tests/hil/hil_test_support.hpp"
#include "gyrostab_signals/ship_roll_damper_frames.hpp"
#include "tools/run/can_link_setup.hpp"
#include "tools/scene/scene_hash.hpp"

namespace gyrostab::testing {
namespace {

using can::CanFrame;
// The ship roll damper's own frames (its signal table), as its controller reads and writes them.
using SensorFrame = msg::ship_roll_damper::SensorFrame;
using ActuatorFrame = msg::ship_roll_damper::ActuatorFrame;

std::int64_t mono_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

enum class Bad { kWrongLength, kUnknownId, kBadCrc, kStaleCounter, kSkippedCounter, kSilent };

const char* name_of(Bad b) {
  switch (b) {
    case Bad::kWrongLength: return "wrong length";
    case Bad::kUnknownId: return "unknown identifier";
    case Bad::kBadCrc: return "bad CRC";
    case Bad::kStaleCounter: return "alive counter repeated (stale frame)";
    case Bad::kSkippedCounter: return "alive counter skipped (frames lost)";
    case Bad::kSilent: return "bus silent";
  }
  return "?";
}

// The identifier of a message of the ship roll damper's bus.
std::uint32_t damper_id(std::string_view name) {
  const can::DeviceBus bus = tools::can_bus_of("ship_roll_damper");
  for (const can::MessageSpec& m : bus.messages())
    if (m.name == name) return m.id;
  ADD_FAILURE() << "no message " << name;
  return 0;
}

// The scene hash the controller under test runs with: a CAN set's MAC covers it (hil/can/link_seal.hpp).
std::uint64_t ship_scene_hash() {
  std::ifstream f(scene("ship-roll-damper-active.toml"), std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  return tools::scene_hash(text);
}

// The test's plant: synthetic sensor sets of a ship roll damper (its bus: imu + drive2) over SocketCAN.
class FakePlant {
 public:
  static constexpr std::uint64_t kSession = 0x5e551011;
  explicit FakePlant(std::optional<firmware::link::Key128> key = std::nullopt)
      : guard_(can::can_guard_config(hil::plant_guard(kSession, key, ship_scene_hash()))) {
    can::SocketCanConfig c;
    c.ifname = can_if();
    for (std::size_t i = 0; i < bus_.messages().size(); ++i)
      if (bus_.messages()[i].direction == can::Direction::kActuator)
        c.receive_ids.push_back(bus_.messages()[i].id);
    std::string error;
    EXPECT_TRUE(socket_.open(c, error)) << error;
  }

  static SensorFrame frame(std::uint64_t k) {
    SensorFrame f{};
    f.tick = k;
    f.time_ns = static_cast<std::int64_t>(k) * 1'000'000;
    f.sample_time_ns = f.time_ns;
    f.sequence = static_cast<std::uint32_t>(k);
    f.roll_rad = 0.01 * std::sin(0.01 * static_cast<double>(k));
    f.roll_rate_rad_s = 1e-4 * std::cos(0.01 * static_cast<double>(k));
    return f;
  }

  // Sends the set of tick k, with the DRIVE2_FB frame made bad as `bad` says (kSilent: nothing). Returns the
  // number of bad frames put on the bus.
  int send(std::uint64_t k, std::optional<Bad> bad) { return send(k, bad, guard_); }

  // The set of tick k sealed by another end's guard (a second plant, a forger): the frames continue this
  // plant's alive counters, as a forger that reads the bus would make them, so only the envelope tells.
  void send_as(std::uint64_t k, hil::LinkGuard& other) { send(k, std::nullopt, other); }

 private:
  int send(std::uint64_t k, std::optional<Bad> bad, hil::LinkGuard& guard) {
    if (bad == Bad::kSilent) return 0;
    std::array<CanFrame, can::kMaxMessagesPerDirection> frames{};
    const std::size_t n = enc_.encode(frame(k), frames);
    can::seal(std::span<CanFrame>(frames.data(), n), guard);
    int bad_frames = 0;
    for (std::size_t i = 0; i < n; ++i) {
      CanFrame f = frames[i];
      if (f.id == drive2_fb_) {
        if (bad) {
          corrupt(f, *bad);
          ++bad_frames;
        } else {
          last_good_alive_ = f.data[can::kAliveByte];
        }
      }
      EXPECT_TRUE(socket_.send(f, mono_ns() + 1'000'000'000));
    }
    return bad_frames;
  }

 public:
  // Sends the good set of tick k until the controller's command for tick k comes back; tick 0 is resent every
  // 20 ms until the controller is up. Deadlines, not a number of tries: a sanitizer build starting in the
  // emulated VM took more than 10 s.
  bool exchange(std::uint64_t k, ActuatorFrame& a) {
    const std::int64_t deadline = mono_ns() + (k == 0 ? 120'000'000'000 : 10'000'000'000);
    while (mono_ns() < deadline) {
      send(k, std::nullopt);
      if (receive(a, mono_ns() + (k == 0 ? 20'000'000 : 2'000'000'000)) && a.tick == k) return true;
    }
    return false;
  }

  // Waits for the controller's command set (any tick) until the deadline.
  bool receive(ActuatorFrame& out, std::int64_t deadline) {
    for (;;) {
      CanFrame f;
      if (socket_.receive(f, deadline) != can::CanRx::kFrame) return false;
      if (rx_.accept(f) == can::FrameError::kNone && rx_.ready()) return rx_.take(out);
    }
  }

 private:
  void corrupt(CanFrame& f, Bad bad) {
    switch (bad) {
      case Bad::kWrongLength:
        f.len = drive2_fb_length_ == 48 ? 64 : 48;  // an FD length, not DRIVE2_FB's
        EXPECT_NE(f.len, drive2_fb_length_);
        break;
      case Bad::kUnknownId:
        f.id = 0x555;
        break;
      case Bad::kBadCrc:
        f.data[10] ^= 0x10;
        return;  // keep the now wrong CRC
      case Bad::kStaleCounter:
        f.data[can::kAliveByte] = last_good_alive_;  // the counter of the last accepted DRIVE2_FB again
        break;
      case Bad::kSkippedCounter:
        skip_alive_ = static_cast<std::uint8_t>(((skip_started_ ? skip_alive_ : last_good_alive_) + 2u) & 0xFu);
        skip_started_ = true;
        f.data[can::kAliveByte] = skip_alive_;  // two ahead of the last one the controller saw, every time
        break;
      case Bad::kSilent:
        break;
    }
    f.data[can::kCrcByte] = can::frame_crc(f.id, f.data, f.len);
  }

  can::SocketCan socket_;
  hil::LinkGuard guard_;
  const can::DeviceBus bus_ = tools::can_bus_of("ship_roll_damper");
  const std::uint32_t drive2_fb_ = damper_id("DRIVE2_FB");
  const std::uint8_t drive2_fb_length_ =
      bus_.messages()[static_cast<std::size_t>(bus_.index_of(damper_id("DRIVE2_FB")))].length;
  can::FrameEncoder enc_{bus_, can::Direction::kSensor};
  can::SetAssembler rx_{bus_, can::Direction::kActuator};
  std::uint8_t last_good_alive_{0};
  std::uint8_t skip_alive_{0};
  bool skip_started_{false};
};

constexpr std::uint64_t kGoodTicks = 20;

void run_case(Bad bad) {
  SCOPED_TRACE(name_of(bad));
  TempDir d;
  const pid_t controller =
      spawn({gyrostab_bin(), "controller", scene("ship-roll-damper-active.toml"), "--can-if", can_if(),
             "--can-no-filter", "--ticks", "1000", "--timeout-ms", "300", "--out", d / "controller"});
  FakePlant plant;
  ActuatorFrame a{};
  // Good ticks (tick 0 resent until the controller is up).
  for (std::uint64_t k = 0; k < kGoodTicks; ++k) {
    ASSERT_TRUE(plant.exchange(k, a)) << "no command for good tick " << k;
    EXPECT_FALSE(msg::has(a.status, msg::FaultBit::kSafeState)) << "tick " << k;
  }
  // Tick K: bad from now on, resent every 20 ms as the plant does (each time bad again) for the first 150 ms of
  // the controller's 300 ms receive timeout — so every bad frame is on the bus, and read, before it gives up.
  const std::uint64_t K = kGoodTicks;
  int bad_frames = 0;
  std::vector<ActuatorFrame> after;
  const std::int64_t stop_sending = mono_ns() + 150'000'000;
  const std::int64_t give_up = mono_ns() + 20'000'000'000;
  while (after.size() < 2 && mono_ns() < give_up) {
    if (mono_ns() < stop_sending) bad_frames += plant.send(K, bad);
    ActuatorFrame f{};
    while (plant.receive(f, mono_ns() + 20'000'000)) after.push_back(f);
  }
  const Exit e = wait_for(controller);
  EXPECT_EQ(e.code, 6) << "the controller declares the plant lost";
  ASSERT_GE(after.size(), 2u);
  // Tick K: held (the last good frame drives the law), cause "missing" — the bad frames never surfaced.
  EXPECT_EQ(after[0].tick, K);
  EXPECT_TRUE(msg::has(after[0].status, msg::FaultBit::kHoldingLastGood));
  EXPECT_TRUE(msg::has(after[0].status, msg::FaultBit::kSensorMissing));
  EXPECT_FALSE(msg::has(after[0].status, msg::FaultBit::kSafeState));
  // Tick K + 1 (hold_ticks = 1): the safe state, brake on, zero torque.
  EXPECT_EQ(after[1].tick, K + 1);
  EXPECT_TRUE(msg::has(after[1].status, msg::FaultBit::kSafeState));
  EXPECT_EQ(after[1].precession_torque_Nm, 0.0);
  EXPECT_EQ(after[1].precession_brake, 1.0);

  const nlohmann::json r = read_json(d / "controller/report.json");
  ASSERT_TRUE(r.contains("link")) << "no controller report";
  EXPECT_EQ(r["link"]["safe_state_tick"], K + 1);
  EXPECT_EQ(r["link"]["missing_ticks"], 2);
  const nlohmann::json& rx = r["link"]["can"]["sensor_rx"];
  EXPECT_EQ(r["link"]["counters"]["accepted"], kGoodTicks);
  // Tick 0 may have completed more than once (the test resends it until the controller is up): at least K.
  EXPECT_GE(rx["sets_completed"].get<int>(), static_cast<int>(kGoodTicks));
  if (bad == Bad::kSilent) {
    EXPECT_TRUE(rx["rejected"].empty()) << rx.dump();
  } else {
    EXPECT_GT(bad_frames, 0);
    ASSERT_TRUE(rx["rejected"].contains(name_of(bad))) << rx.dump();
    EXPECT_EQ(rx["rejected"][name_of(bad)], bad_frames) << rx.dump();
    EXPECT_EQ(rx["rejected"].size(), 1u) << "only that cause: " << rx.dump();
  }
}

TEST(CanBadFrames, WrongLength) { run_case(Bad::kWrongLength); }
TEST(CanBadFrames, UnknownId) { run_case(Bad::kUnknownId); }
TEST(CanBadFrames, BadCrc) { run_case(Bad::kBadCrc); }
TEST(CanBadFrames, StaleCounter) { run_case(Bad::kStaleCounter); }
TEST(CanBadFrames, SkippedCounter) { run_case(Bad::kSkippedCounter); }
TEST(CanBadFrames, BusSilent) { run_case(Bad::kSilent); }

// The link envelope over CAN: after the handshake, a complete, well-formed set of tick K whose header names
// another session (without a key), or the right session under the wrong key (with one), is refused before
// the firmware sees it — counted in link.session.refused — and the genuine set of tick K that follows drives
// the command of tick K as if nothing had happened.
void run_session_case(bool keyed) {
  SCOPED_TRACE(keyed ? "keyed: a forged MAC" : "unkeyed: another session");
  TempDir d;
  firmware::link::Key128 key;
  for (std::size_t i = 0; i < key.bytes.size(); ++i) key.bytes[i] = static_cast<std::uint8_t>(0xa5 ^ (i * 29));
  std::vector<std::string> args{gyrostab_bin(), "controller", scene("ship-roll-damper-active.toml"), "--can-if",
                                can_if(), "--can-no-filter", "--ticks", "1000", "--timeout-ms", "300", "--out",
                                d / "controller"};
  if (keyed) {
    std::string hex;
    char b[3];
    for (std::uint8_t v : key.bytes) {
      std::snprintf(b, sizeof b, "%02x", v);
      hex += b;
    }
    const std::string key_path = d / "link.key";
    std::ofstream(key_path) << hex << "\n";
    ASSERT_EQ(::chmod(key_path.c_str(), 0600), 0);
    args.insert(args.end(), {"--key-file", key_path});
  }
  const pid_t controller = spawn(args);
  FakePlant plant(keyed ? std::optional(key) : std::nullopt);
  firmware::link::Key128 wrong = key;
  wrong.bytes[0] ^= 1;
  hil::LinkGuard other(can::can_guard_config(
      hil::plant_guard(keyed ? FakePlant::kSession : FakePlant::kSession + 1, keyed ? std::optional(wrong) : std::nullopt,
                       ship_scene_hash())));
  // A forger's freshness runs ahead of the plant's (which resends tick 0 until the controller is up), else its
  // set is refused as a replay before its MAC is looked at.
  for (int i = 0; i < 5000; ++i) other.protect({});
  ActuatorFrame a{};
  for (std::uint64_t k = 0; k <= kGoodTicks; ++k) {
    if (k == kGoodTicks) plant.send_as(k, other);  // refused: the controller keeps waiting for tick K
    ASSERT_TRUE(plant.exchange(k, a)) << "no command for tick " << k;
    EXPECT_FALSE(msg::has(a.status, msg::FaultBit::kSafeState)) << "tick " << k;
    EXPECT_FALSE(msg::has(a.status, msg::FaultBit::kHoldingLastGood)) << "tick " << k;
  }
  // Then the plant falls silent: the controller declares it lost (exit 6) and writes its report.
  EXPECT_EQ(wait_for(controller).code, 6);
  const nlohmann::json r = read_json(d / "controller/report.json");
  ASSERT_TRUE(r.contains("link")) << "no controller report";
  const nlohmann::json& session = r["link"]["session"];
  EXPECT_EQ(session["authenticated"], keyed);
  EXPECT_EQ(session["refused"][keyed ? "bad_mac" : "foreign"], 1) << session.dump();
  EXPECT_EQ(session["refused"][keyed ? "foreign" : "bad_mac"], 0) << session.dump();
  EXPECT_EQ(r["link"]["counters"]["accepted"], kGoodTicks + 1);
}

TEST(CanSession, ASetOfAnotherSessionIsRefused) { run_session_case(false); }
TEST(CanSession, ASetWithAForgedMacIsRefused) { run_session_case(true); }

// Two complete pairs on one bus, each started as `run --transport can` (the same identifiers, as two pairs
// started by hand would use): neither may act on the other's frames nor end as a silent success. On CAN the
// two pairs' frames interleave on every identifier, so many sets never complete. Each run ends as one of:
//   7  completed bit-identical to its in-process run, foreign sets refused;
//   8  completed, but some ticks got zero torque because their command never arrived (named in the message);
//   6  a process lost its peer, the message naming the other pair's frames as the likely cause;
// never 0 with the other pair's frames on its bus, never a crash, never results changed by the other's frames.
TEST(CanSession, TwoPairsOnOneBusAreNeverASilentSuccess) {
  TempDir d;
  const std::string a = scene("monorail.toml"), b = scene("ship-roll-damper-active.toml");
  const std::vector<std::string> ticks{"--ticks", "2000", "--no-progress"};
  ASSERT_EQ(run(cat({gyrostab_bin(), "run", a, "--out", d / "ref_a"}, ticks)).code, 0);
  ASSERT_EQ(run(cat({gyrostab_bin(), "run", b, "--out", d / "ref_b"}, ticks)).code, 0);
  const std::vector<std::string> can{"--transport", "can", "--can-if", can_if(), "--timeout-ms", "2000"};
  const pid_t pa = spawn(cat(cat({gyrostab_bin(), "run", a, "--out", d / "a"}, ticks), can));
  const pid_t pb = spawn(cat(cat({gyrostab_bin(), "run", b, "--out", d / "b"}, ticks), can));
  const Exit ea = wait_for(pa), eb = wait_for(pb);
  std::uint64_t disturbed = 0;
  for (const auto& [name, e] : {std::pair{std::string("a"), ea}, std::pair{std::string("b"), eb}}) {
    SCOPED_TRACE(name);
    const nlohmann::json r = read_json(d / name + "/report.json");
    ASSERT_TRUE(r.contains("link") && r.contains("processes")) << "no report";
    const std::string happened = r["processes"]["what_happened"].get<std::string>();
    const auto count = [](const nlohmann::json& link) {
      std::uint64_t n = link["session"]["refused"]["foreign"].get<std::uint64_t>();
      for (const char* rx : {"sensor_rx", "actuator_rx"}) {
        if (!link["can"].contains(rx)) continue;
        const nlohmann::json& rej = link["can"][rx]["rejected"];
        for (const char* cause : {"alive counter skipped (frames lost)", "alive counter repeated (stale frame)"})
          if (rej.contains(cause)) n += rej[cause].get<std::uint64_t>();
      }
      return n;
    };
    const std::uint64_t seen = count(r["link"]) + count(r["controller_process"]["link"]);
    disturbed += seen;
    std::printf("[ pair %s ] exit %d, foreign sets and out-of-sequence frames: %llu; %s\n", name.c_str(), e.code,
                static_cast<unsigned long long>(seen), happened.c_str());
    const Outputs ref = outputs_of(d / ("ref_" + name)), got = outputs_of(d / name);
    switch (e.code) {
      case 0:
        EXPECT_EQ(seen, 0u) << "a run shared its bus with another pair and exited 0";
        [[fallthrough]];
      case 7:
        EXPECT_EQ(ref.figures, got.figures) << "a completed run's results changed";
        EXPECT_TRUE(ref.csv == got.csv) << "a completed run's results changed";
        break;
      case 8:
        EXPECT_NE(happened.find("zero torque"), std::string::npos) << happened;
        break;
      case 6:
        EXPECT_NE(happened.find("another pair"), std::string::npos) << "the cause is not named: " << happened;
        break;
      default:
        ADD_FAILURE() << "exit " << e.code << ": " << happened;
    }
  }
  EXPECT_GT(disturbed, 0u) << "the two runs never overlapped";
}

TEST(CanFlood, CangenFloodDoesNotStallALockstepRun) {
  TempDir d;
  const std::string path = scene("ship-roll-damper-active.toml");
  const std::vector<std::string> ticks{"--ticks", "400", "--no-progress"};
  ASSERT_EQ(run(cat({gyrostab_bin(), "run", path, "--out", d / "inproc"}, ticks)).code, 0);
  // Random identifiers at full speed (the kernel filters drop them), and classic frames on the sensor hub's
  // identifier (they pass the filter and reach the decoder) at one per 0.13 ms: a 1 Mbit/s bus saturated with
  // 8-byte classic frames (~130 bits each with stuffing) carries no more. An unpaced flood on our own
  // identifier outruns any receiver on vcan, which has no bit rate (the sanitizer build in the emulated VM
  // lost frames to the full socket queue and the lockstep run stalled), and no real bus could deliver it.
  const pid_t random_flood = spawn({"/usr/bin/cangen", can_if(), "-g", "0", "-i"});
  char hub_id[8];
  std::snprintf(hub_id, sizeof hub_id, "%03X", damper_id("SENSOR_HUB"));
  const pid_t our_id_flood = spawn({"/usr/bin/cangen", can_if(), "-g", "0.13", "-i", "-I", hub_id, "-L", "8"});
  const Exit e = run(cat({gyrostab_bin(), "run", path, "--transport", "can", "--can-if", can_if(), "--out", d / "can"},
                         ticks));
  kill(random_flood, SIGTERM);
  kill(our_id_flood, SIGTERM);
  wait_for(random_flood);
  wait_for(our_id_flood);
  ASSERT_EQ(e.code, 0);
  EXPECT_EQ(read_file(d / "inproc/signals.csv"), read_file(d / "can/signals.csv"));
  const nlohmann::json r = read_json(d / "can/report.json");
  const nlohmann::json& rx = r["controller_process"]["link"]["can"]["sensor_rx"];
  // Every tick's set and the end-of-run set, plus at most the plant's lockstep resends (a start-up resend
  // reaches the controller only if it was already listening).
  EXPECT_GE(rx["sets_completed"].get<int>(), 400);
  EXPECT_LE(rx["sets_completed"].get<int>(), 400 + 1 + r["link"]["counters"]["resent"].get<int>());
  EXPECT_EQ(r["link"]["counters"]["accepted"], 400);
  ASSERT_TRUE(rx["rejected"].contains("classic frame on a CAN FD identifier")) << rx.dump();
  EXPECT_GT(rx["rejected"]["classic frame on a CAN FD identifier"].get<int>(), 0);
  std::printf("[ measured ] flood: the controller rejected %d classic frames on 0x%s during 400 ticks\n",
              rx["rejected"]["classic frame on a CAN FD identifier"].get<int>(), hub_id);
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_HIL_TEST_MAIN()
