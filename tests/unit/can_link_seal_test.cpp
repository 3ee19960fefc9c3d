// The link envelope of a CAN FD set (hil/can/link_seal.hpp): a sealed set passes the decoder and the guard;
// a set of another session, a recording (session 0), a body frame moved under another header, a wrong key and
// a replayed set are each refused under their cause and leave the receiver able to take the genuine next set.
#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <span>

#include "gyrostab_signals/union_fixture_can.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/link_seal.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab::can {
namespace can_link_seal_test {

using hil::GuardVerdict;
using hil::LinkEnvelope;
using hil::LinkGuard;

// The union fixture's bus: the IMU, two drives, the cluster (two frames) and the header.
constexpr DeviceBus kBus = whole_bus(union_fixture::kCanMap);
constexpr std::uint64_t kSession = 0x1a2b3c4d;
constexpr std::uint64_t kControllerId = 0x0c0ffee1;

using Set = std::array<CanFrame, kMaxMessagesPerDirection>;

firmware::link::Key128 key(std::uint8_t salt) {
  firmware::link::Key128 k;
  for (std::size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = static_cast<std::uint8_t>(salt ^ (i * 41));
  return k;
}

msg::SensorFrame sensor(std::uint64_t tick, double roll) {
  msg::SensorFrame f{};
  f.tick = tick;
  f.time_ns = static_cast<std::int64_t>(tick) * 1'000'000;
  f.sequence = static_cast<std::uint32_t>(tick);
  f.carrier_angle_rad[msg::kRoll] = roll;
  f.gimbal_angle_rad[msg::kAxis2] = 0.5 * roll;
  return f;
}

// A plant: encodes with the bus's encoder (shared, so that every set continues the alive counters the
// receiver expects, as a forger that reads the bus would make them) and seals with its own guard.
struct Sender {
  Sender(FrameEncoder& e, std::uint64_t session, std::optional<firmware::link::Key128> k = std::nullopt)
      : guard(can_guard_config(hil::plant_guard(session, k))), enc(e) {}
  std::size_t make(std::uint64_t tick, double roll, Set& out, FrameEncoder* with = nullptr) {
    const std::size_t n = (with != nullptr ? *with : enc).encode(sensor(tick, roll), out);
    seal(std::span<CanFrame>(out.data(), n), guard);
    return n;
  }
  LinkGuard guard;
  FrameEncoder& enc;
};

// A controller: assembles sets and judges them.
struct Receiver {
  explicit Receiver(std::optional<firmware::link::Key128> k = std::nullopt)
      : guard(can_guard_config(hil::controller_guard(kControllerId, 0, k))) {}
  // Feeds a set's frames; the verdict on the set they complete (kOk: taken, and bound at the first).
  GuardVerdict offer(const Set& s, std::size_t n, msg::SensorFrame* out = nullptr) {
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_EQ(rx.accept(s[i]), FrameError::kNone) << "the decoder refused frame 0x" << std::hex << s[i].id;
    }
    EXPECT_TRUE(rx.ready());
    Set got{};
    const std::size_t m = rx.ready_frames(got);
    LinkEnvelope e;
    const GuardVerdict v = open(std::span<const CanFrame>(got.data(), m), guard, e);
    if (v != GuardVerdict::kOk) {
      rx.drop_ready();
      return v;
    }
    msg::SensorFrame f{};
    EXPECT_TRUE(rx.take(f));
    if (out != nullptr) *out = f;
    if (!guard.bound()) guard.bind(e);
    return v;
  }
  LinkGuard guard;
  SetAssembler rx{kBus, Direction::kSensor};
};

// A copy of `genuine` whose first body frame (the IMU's) is `foreign`'s, with the genuine frame's alive counter
// and a valid CRC: it passes the decoder, only the MAC can tell.
Set mixed(const Set& genuine, const Set& foreign) {
  Set m = genuine;
  m[0] = foreign[0];
  m[0].data[kAliveByte] = genuine[0].data[kAliveByte];
  m[0].data[kCrcByte] = frame_crc(m[0].id, m[0].data, m[0].len);
  return m;
}

TEST(CanLinkSeal, TheHeaderCarriesTheEnvelopeAndTheSetPassesTheDecoder) {
  FrameEncoder bus(kBus, Direction::kSensor);
  Sender plant(bus, kSession);
  Set s{};
  const std::size_t n = plant.make(0, 0.01, s);
  ASSERT_EQ(n, 6u);
  const CanFrame& h = s[n - 1];
  EXPECT_EQ(h.id, 0x2FFu) << "SENSOR_HUB";
  EXPECT_EQ(h.len, kHeaderLength);
  const LinkEnvelope e = read_link_envelope(h);
  EXPECT_EQ(e.sender, kSession);
  EXPECT_EQ(e.session, kSession);
  EXPECT_EQ(e.freshness, 1u);
  EXPECT_NE(e.mac, 0u) << "an unkeyed SipHash of the set, not zero";
  EXPECT_EQ(h.data[kCrcByte], frame_crc(h.id, h.data, h.len)) << "the CRC covers the envelope";
  Receiver controller;
  msg::SensorFrame got{};
  EXPECT_EQ(controller.offer(s, n, &got), GuardVerdict::kOk);
  EXPECT_EQ(got.carrier_angle_rad[msg::kRoll], 0.01);
  EXPECT_EQ(got.gimbal_angle_rad[msg::kAxis2], 0.005);
  EXPECT_EQ(controller.guard.session(), kSession);
  EXPECT_EQ(controller.guard.peer(), kSession);
}

TEST(CanLinkSeal, WithoutAKeyAnotherSessionARecordingAndAMixedSetAreRefused) {
  FrameEncoder bus(kBus, Direction::kSensor);
  Sender plant(bus, kSession), other(bus, kSession + 7), recording(bus, 0), copier(bus, kSession);
  Receiver controller;
  Set s{};
  std::size_t n = plant.make(0, 0.01, s);
  ASSERT_EQ(controller.offer(s, n), GuardVerdict::kOk);

  n = other.make(1, 0.02, s);
  EXPECT_EQ(controller.offer(s, n), GuardVerdict::kForeign) << "another session";
  n = recording.make(1, 0.02, s);
  EXPECT_EQ(controller.offer(s, n), GuardVerdict::kRecorded) << "session 0";

  // The genuine tick-1 set with its IMU frame taken from a set of the same session and sender (a copier):
  // the decoder cannot tell, the unkeyed MAC does.
  FrameEncoder snapshot = bus;
  Set genuine{}, foreign{};
  n = plant.make(1, 0.02, genuine);
  copier.make(1, 0.99, foreign, &snapshot);
  EXPECT_EQ(controller.offer(mixed(genuine, foreign), n), GuardVerdict::kForeign) << "a mixed set";

  // The genuine set, resent (next alive counters, next freshness), is taken.
  msg::SensorFrame got{};
  n = plant.make(1, 0.02, s);
  EXPECT_EQ(controller.offer(s, n, &got), GuardVerdict::kOk);
  EXPECT_EQ(got.tick, 1u);
  EXPECT_EQ(got.carrier_angle_rad[msg::kRoll], 0.02);
  const hil::GuardCounters c = controller.guard.counters();
  EXPECT_EQ(c.foreign, 2u);
  EXPECT_EQ(c.recorded, 1u);
  EXPECT_EQ(c.bad_mac, 0u);
}

TEST(CanLinkSeal, WithAKeyAForgeryAMixedSetAndAReplayAreRefused) {
  const firmware::link::Key128 k = key(0x3c), wrong = key(0x3d);
  FrameEncoder bus(kBus, Direction::kSensor);
  Sender plant(bus, kSession, k), forger(bus, kSession, wrong), copier(bus, kSession, wrong);
  Receiver controller(k);
  Set s{};
  std::size_t n = plant.make(0, 0.01, s);
  ASSERT_EQ(controller.offer(s, n), GuardVerdict::kOk);
  EXPECT_TRUE(controller.guard.authenticated());

  // The forger's freshness must be newer than the last accepted one, or it is refused as a replay before
  // its MAC is checked: it has sealed a set of its own before.
  FrameEncoder scratch(kBus, Direction::kSensor);
  Set junk{};
  forger.make(0, 0.0, junk, &scratch);
  n = forger.make(1, 0.5, s);
  EXPECT_EQ(read_link_envelope(s[n - 1]).freshness, 2u);
  EXPECT_EQ(controller.offer(s, n), GuardVerdict::kBadMac) << "the right session under the wrong key";

  FrameEncoder snapshot = bus;
  Set genuine{}, foreign{};
  n = plant.make(1, 0.02, genuine);
  copier.make(1, 0.99, foreign, &snapshot);
  EXPECT_EQ(controller.offer(mixed(genuine, foreign), n), GuardVerdict::kBadMac) << "a mixed set";

  msg::SensorFrame got{};
  n = plant.make(1, 0.02, s);
  EXPECT_EQ(controller.offer(s, n, &got), GuardVerdict::kOk);
  EXPECT_EQ(got.carrier_angle_rad[msg::kRoll], 0.02);

  // The accepted set again, its alive counters brought forward (the decoder would take it): its freshness is
  // not newer, so it is a replay.
  Set again = s;
  for (std::size_t i = 0; i < n; ++i) {
    again[i].data[kAliveByte] = static_cast<std::uint8_t>((again[i].data[kAliveByte] + 1u) & kAliveMask);
    again[i].data[kCrcByte] = frame_crc(again[i].id, again[i].data, again[i].len);
  }
  EXPECT_EQ(controller.offer(again, n), GuardVerdict::kReplayed);
  const hil::GuardCounters c = controller.guard.counters();
  EXPECT_EQ(c.bad_mac, 2u);
  EXPECT_EQ(c.replayed, 1u);
  EXPECT_EQ(c.foreign, 0u);
}

}  // namespace can_link_seal_test
}  // namespace gyrostab::can
