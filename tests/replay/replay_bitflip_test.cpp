// A single flipped bit in a bus log is never silently replayed: in a recorded sensor frame it is reported at
// exactly its tick (re-simulation compares every sensor frame; replay compares the controller's response);
// anywhere else it is a corrupt log (exit 5, with the byte offset) or a mismatch; nothing crashes.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>

#include "hil/lcm/frame_codec.hpp"
#include "tools/signals/device_signals.hpp"
#include "sim/random/seeded_rng.hpp"
#include "tests/support/bus_log_fixtures.hpp"
#include "tests/support/shipped_scenes.hpp"
#include "tools/log/bus_log_reader.hpp"
#include "tools/run/replay_session.hpp"

namespace gyrostab {
namespace {

using tools::buslog::BusLogReader;
using tools::buslog::ReadStatus;
using tools::buslog::TickRecord;

constexpr std::int64_t kTicks = 400;
constexpr std::int64_t kFlipTick = 237;  // not a multiple of 10: off the control ticks of the 10 kHz drive scene
constexpr int kHeaderBytes = 28;         // LCM event header before the channel name

std::string scene_device(const std::string& log) {
  BusLogReader r;
  EXPECT_EQ(r.open(log), ReadStatus::kOk) << r.problem();
  return r.scene().device;
}

std::vector<TickRecord> read_ticks(const std::string& log) {
  BusLogReader r;
  EXPECT_EQ(r.open(log), ReadStatus::kOk) << r.problem();
  std::vector<TickRecord> out;
  TickRecord t;
  while (r.next(t) == ReadStatus::kOk) out.push_back(t);
  return out;
}

// The log with one bit of tick kFlipTick's sensor frame flipped, made by re-encoding the frame with the field
// changed; checks that exactly one bit of the file differs.
template <class Change>
std::vector<std::uint8_t> with_sensor_change(const std::vector<std::uint8_t>& log, const TickRecord& t,
                                             const msg::DeviceSignals& device, Change change,
                                             const std::string& channel) {
  std::vector<std::uint8_t> out = log;
  const std::size_t at = static_cast<std::size_t>(t.sensor_offset) + kHeaderBytes + channel.size();
  const int size = hil::sensor_encoded_size(device);
  msg::AnySensorFrame f{};
  std::int64_t sim_us = 0;
  EXPECT_EQ(hil::decode(&log[at], size, device, f, &sim_us), hil::DecodeError::kOk);
  change(f);
  EXPECT_EQ(hil::encode(f, device, sim_us, &out[at], size), size);
  int bits = 0;
  for (std::size_t i = 0; i < out.size(); ++i) bits += std::popcount(static_cast<unsigned>(out[i] ^ log[i]));
  EXPECT_EQ(bits, 1) << "the edit is not a single bit flip";
  return out;
}

void flip_sign(double& v) {
  v = std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) ^ (1ull << 63));
}

// The flips of a device's sensor frame: the tick (bit 40), and the sign bit of every signal of its table.
struct FieldFlip {
  std::string name;
  int signal;  // -1: the tick
  void operator()(msg::AnySensorFrame& f) const {
    if (signal < 0) {
      f.tick ^= 1ull << 40;
    } else {
      flip_sign(f.signal[signal]);
    }
  }
};

std::vector<FieldFlip> flips_of(const msg::DeviceSignals& d) {
  std::vector<FieldFlip> out{{"tick bit 40", -1}};
  for (std::size_t i = 0; i < d.sensors.size(); ++i) {
    std::string n(d.sensors[i].name);
    if (d.sensors[i].count > 1) n += "[" + std::to_string(d.sensors[i].element) + "]";
    out.push_back({n, static_cast<int>(i)});
  }
  return out;
}

// The first tick a replay reports as differing, or -1.
std::int64_t mismatch_tick(const std::string& out) {
  const std::string key = "MISMATCH at tick ";
  const auto at = out.find(key);
  return at == std::string::npos ? -1 : std::stoll(out.substr(at + key.size()));
}

TEST(BusLogBitFlip, AFlippedSensorBitIsReportedAtExactlyItsTick) {
  for (const auto& scene : testing::shipped_scenes()) {
    SCOPED_TRACE(scene);
    testing::ScratchDir dir("bitflip");
    const std::string log = dir.file("run.lcmlog");
    ASSERT_EQ(testing::record_run(scene, log, kTicks), 0);
    const auto bytes = testing::read_bytes(log);
    const auto ticks = read_ticks(log);
    ASSERT_EQ(ticks.size(), static_cast<std::size_t>(kTicks));
    const TickRecord& t = ticks[kFlipTick];
    const msg::DeviceSignals& device = *tools::find_device_signals(scene_device(log));
    int controller_saw = 0;
    for (const FieldFlip& flip : flips_of(device)) {
      SCOPED_TRACE(flip.name);
      const std::string bad = dir.file("flipped.lcmlog");
      testing::write_bytes(bad, with_sensor_change(bytes, t, device, flip, "GYROSTAB_SENSOR"), bytes.size());
      // Re-simulation recomputes every sensor frame: the first difference is the flipped frame.
      const auto resim = testing::replay(bad, /*resimulate=*/true);
      EXPECT_EQ(resim.rc, tools::kReplayExitMismatch) << resim.out;
      EXPECT_EQ(mismatch_tick(resim.out), kFlipTick) << resim.out;
      // The controller: identical if it does not read the field at this tick, else the first difference can
      // only be at the flipped tick or later (nothing before it changed).
      const auto rep = testing::replay(bad);
      if (rep.rc == 0) continue;
      EXPECT_EQ(rep.rc, tools::kReplayExitMismatch) << rep.out;
      EXPECT_GE(mismatch_tick(rep.out), kFlipTick) << rep.out;
      if (mismatch_tick(rep.out) == kFlipTick) ++controller_saw;
      // A frame stamped 2^40 ticks ahead is stale to the fault monitor at once (status bits of that tick).
      if (flip.signal < 0) {
        EXPECT_EQ(mismatch_tick(rep.out), kFlipTick) << rep.out;
      }
    }
    // Every controller sees the stale stamp; the monitor-only Schuler pendulum and the servo gyro read no other
    // flipped field at that tick, so one is the honest lower bound across scenes.
    EXPECT_GE(controller_saw, 1) << "the controller did not react at the flipped tick to any field";
  }
}

// Random single-bit flips anywhere in a short log: replay and re-simulation never crash, end with a
// documented code, and at least one of them refuses the log (the scene and end events carry a check sum,
// every header field and frame timestamp is checked, and the frames themselves are compared bit for bit).
TEST(BusLogBitFlip, RandomFlipsAnywhereAreNeverSilent) {
  testing::ScratchDir dir("randomflip");
  const std::string log = dir.file("run.lcmlog");
  ASSERT_EQ(testing::record_run(GYROSTAB_SOURCE_DIR "/sim/scenes/monorail.toml", log, 40), 0);
  const auto bytes = testing::read_bytes(log);
  const auto ticks = read_ticks(log);
  ASSERT_EQ(ticks.size(), 40u);
  // Three regions, sampled alike: the scene event, the frames, the end event.
  const std::size_t frames_begin = static_cast<std::size_t>(ticks.front().sensor_offset);
  const std::size_t end_begin = static_cast<std::size_t>(ticks.back().actuator_offset) + kHeaderBytes +
                                std::string("GYROSTAB_ACTUATOR").size() +
                                static_cast<std::size_t>(hil::actuator_encoded_size(*tools::find_device_signals("monorail")));
  ASSERT_LT(end_begin, bytes.size());
  const std::size_t region[3][2] = {{0, frames_begin}, {frames_begin, end_begin}, {end_begin, bytes.size()}};
  random::SeededRng rng(20261123, 1);
  const std::string bad = dir.file("flipped.lcmlog");
  for (int i = 0; i < 240; ++i) {
    const auto& [lo, hi] = region[i % 3];
    const std::size_t byte = lo + static_cast<std::size_t>(rng.next() % (hi - lo));
    const int bit = static_cast<int>(rng.next() % 8);
    auto copy = bytes;
    copy[byte] = static_cast<std::uint8_t>(copy[byte] ^ (1u << bit));
    testing::write_bytes(bad, copy, copy.size());
    const auto rep = testing::replay(bad);
    const auto resim = testing::replay(bad, /*resimulate=*/true);
    SCOPED_TRACE("byte " + std::to_string(byte) + " bit " + std::to_string(bit));
    EXPECT_TRUE(rep.rc == 0 || rep.rc == tools::kReplayExitMismatch || rep.rc == tools::kReplayExitBadLog) << rep.out;
    EXPECT_TRUE(resim.rc == 0 || resim.rc == tools::kReplayExitMismatch || resim.rc == tools::kReplayExitBadLog)
        << resim.out;
    EXPECT_TRUE(rep.rc != 0 || resim.rc != 0) << "silently accepted\n" << rep.out << resim.out;
  }
}

}  // namespace
}  // namespace gyrostab
