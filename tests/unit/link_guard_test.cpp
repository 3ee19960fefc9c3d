// Session binding and authentication of the plant ⇄ controller link (hil/link/link_guard.hpp) through the
// endpoint that every transport uses (hil/link/frame_endpoint.hpp), on the in-memory bus: a second pair on
// the same bus, a bus log played onto it, a forger without the key, a replay, a sequence jump.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "hil/lcm/frame_codec.hpp"
#include "hil/link/actuator_frame_check.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "hil/link/link_guard.hpp"
#include "hil/link/memory_bus.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab {
namespace link_guard_test {

constexpr std::uint64_t kSession = 0x1234abcd;
constexpr std::uint64_t kControllerId = 0x0badf00d;

firmware::link::Key128 key(std::uint8_t fill) {
  firmware::link::Key128 k;
  for (std::size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = static_cast<std::uint8_t>(fill + i);
  return k;
}

msg::ActuatorFrame command(std::uint64_t tick, double torque) {
  msg::ActuatorFrame a{};
  a.tick = tick;
  a.sequence = static_cast<std::uint32_t>(tick);
  a.gimbal_torque_Nm[msg::kAxis2] = torque;
  return a;
}

msg::SensorFrame sensor(std::uint64_t tick) {
  msg::SensorFrame s{};
  s.tick = tick;
  s.sequence = static_cast<std::uint32_t>(tick);
  return s;
}

// A plant and a controller on one in-memory bus, each with its guard.
struct Pair {
  explicit Pair(std::optional<firmware::link::Key128> k = std::nullopt, std::uint64_t controller_session = 0)
      : plant(plant_side, hil::plant_guard(kSession, k), msg::kSignals),
        controller(controller_side, hil::controller_guard(kControllerId, controller_session, k), msg::kSignals) {}
  std::unique_ptr<hil::MemoryBus> bus = std::make_unique<hil::MemoryBus>();
  hil::MemoryTransport plant_side{bus->to_controller, bus->to_plant};
  hil::MemoryTransport controller_side{bus->to_plant, bus->to_controller};
  hil::FrameEndpoint<hil::MemoryTransport> plant;
  hil::FrameEndpoint<hil::MemoryTransport> controller;

  // The handshake: the tick-0 sensor frame binds the controller, its tick-0 command binds the plant.
  void handshake() {
    ASSERT_TRUE(plant.send(sensor(0), 0));
    msg::SensorFrame s{};
    ASSERT_EQ(controller.receive(soon(), s), hil::RxStatus::kMessage);
    controller.bind_to_last();
    ASSERT_TRUE(controller.send(command(0, 1.0), 0));
    msg::ActuatorFrame a{};
    ASSERT_EQ(plant.receive(soon(), a), hil::RxStatus::kMessage);
    plant.bind_to_last();
  }
  static std::int64_t soon() { return hil::monotonic_ns() + 200'000'000; }
  static std::int64_t now() { return hil::monotonic_ns(); }
};

TEST(LinkGuard, BindsBothEndsAtTheHandshake) {
  Pair p;
  p.handshake();
  EXPECT_TRUE(p.plant.guard().bound());
  EXPECT_TRUE(p.controller.guard().bound());
  EXPECT_EQ(p.controller.guard().session(), kSession) << "the controller takes the plant's session";
  EXPECT_EQ(p.plant.guard().peer(), kControllerId);
  EXPECT_EQ(p.controller.guard().peer(), kSession) << "the plant's sender id is its session id";
  for (std::uint64_t k = 1; k < 100; ++k) {
    ASSERT_TRUE(p.controller.send(command(k, 2.0), 0));
    msg::ActuatorFrame a{};
    ASSERT_EQ(p.plant.receive(Pair::soon(), a), hil::RxStatus::kMessage);
    EXPECT_EQ(a.tick, k);
  }
  EXPECT_EQ(p.plant.guard().counters().rejected(), 0u);
}

TEST(LinkGuard, ASecondControllerOnTheBusIsForeignAndNeverActedOn) {
  Pair p;
  p.handshake();
  // Another controller (its own id, the same bus, even the same session as it heard the plant's frames).
  hil::MemoryTransport intruder_side{p.bus->to_plant, p.bus->to_controller};
  hil::FrameEndpoint<hil::MemoryTransport> intruder(intruder_side,
                                                    hil::controller_guard(0x77777777, kSession, std::nullopt), msg::kSignals);
  ASSERT_TRUE(intruder.send(command(1, -50.0), 0));
  ASSERT_TRUE(p.controller.send(command(1, 2.0), 0));
  msg::ActuatorFrame a{};
  ASSERT_EQ(p.plant.receive(Pair::soon(), a), hil::RxStatus::kMessage);
  EXPECT_EQ(a.gimbal_torque_Nm[msg::kAxis2], 2.0) << "the genuine command, not the intruder's";
  EXPECT_EQ(p.plant.guard().counters().foreign, 1u);
}

TEST(LinkGuard, AFrameOfAnotherSessionIsForeign) {
  Pair p;
  p.handshake();
  // The plant of another pair on the same channels.
  hil::MemoryTransport other_side{p.bus->to_controller, p.bus->to_plant};
  hil::FrameEndpoint<hil::MemoryTransport> other_plant(other_side, hil::plant_guard(0x55555555, std::nullopt), msg::kSignals);
  ASSERT_TRUE(other_plant.send(sensor(1), 0));
  msg::SensorFrame s{};
  EXPECT_EQ(p.controller.receive(Pair::now() + 20'000'000, s), hil::RxStatus::kTimeout);
  EXPECT_EQ(p.controller.guard().counters().foreign, 1u);
}

TEST(LinkGuard, ARecordedFrameIsRefused) {
  Pair p;
  p.handshake();
  // What a bus log holds (tools/log/bus_log_writer.cpp encodes with the empty envelope: session 0), as
  // lcm-logplayer would put it on the bus.
  std::uint8_t buf[hil::kMaxEncodedSize];
  const int n = hil::encode(msg::any_of(command(1, 9.0)), msg::kSignals, 0, buf, sizeof buf);
  p.bus->to_plant.push(buf, n);
  msg::ActuatorFrame a{};
  EXPECT_EQ(p.plant.receive(Pair::now() + 20'000'000, a), hil::RxStatus::kTimeout);
  EXPECT_EQ(p.plant.guard().counters().recorded, 1u);
}

TEST(LinkGuard, SenderZeroIsNobodyAndCannotBeBoundTo) {
  Pair p;
  // Found by link_guard_fuzz: a handshake command from sender 0 bound the plant to "nobody", which left it
  // open to every sender of the session.
  std::uint8_t buf[hil::kMaxEncodedSize];
  const int n = hil::encode(msg::any_of(command(0, 7.0)), msg::kSignals, 0, buf, sizeof buf, hil::LinkEnvelope{0, kSession, 1, 0});
  p.bus->to_plant.push(buf, n);
  msg::ActuatorFrame a{};
  EXPECT_EQ(p.plant.receive(Pair::now() + 20'000'000, a), hil::RxStatus::kTimeout);
  EXPECT_EQ(p.plant.guard().counters().foreign, 1u);
  EXPECT_FALSE(p.plant.guard().bound());
}

TEST(LinkGuard, WithAKeyAForgerWhoCopiesTheEnvelopeChangesNothing) {
  Pair p(key(1));
  p.handshake();
  // The forger reads the bus, so it knows the session and the controller's id; it has no key (here: another
  // key). It sends three frames per tick, so its freshness values run ahead of the genuine ones: a forgery
  // that moved the receiver's freshness would lock the genuine controller out.
  hil::MemoryTransport forger_side{p.bus->to_plant, p.bus->to_controller};
  hil::FrameEndpoint<hil::MemoryTransport> forger(forger_side,
                                                  hil::controller_guard(kControllerId, kSession, key(99)), msg::kSignals);
  constexpr std::uint64_t kTicks = 200;
  for (std::uint64_t k = 1; k <= kTicks; ++k) {
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(forger.send(command(k, -100.0), 0));
    ASSERT_TRUE(p.controller.send(command(k, 3.0), 0));
    msg::ActuatorFrame a{};
    ASSERT_EQ(p.plant.receive(Pair::soon(), a), hil::RxStatus::kMessage) << k;
    EXPECT_EQ(a.tick, k);
    EXPECT_EQ(a.gimbal_torque_Nm[msg::kAxis2], 3.0) << "a forged command was acted on at tick " << k;
  }
  const hil::GuardCounters& c = p.plant.guard().counters();
  EXPECT_EQ(c.rejected(), 3 * kTicks) << "every forged frame refused";
  EXPECT_GE(c.bad_mac, 3 * kTicks - 3) << "refused for its MAC once its freshness runs ahead";
}

TEST(LinkGuard, WithAKeyAReplayedGenuineFrameIsRefused) {
  Pair p(key(1));
  p.handshake();
  ASSERT_TRUE(p.controller.send(command(1, 3.0), 0));
  // The attacker captured the frame and sends it again, byte for byte.
  std::uint8_t copy[hil::kMaxMessageBytes];
  const int n = p.bus->to_plant.pop(copy, Pair::soon());
  ASSERT_GT(n, 0);
  p.bus->to_plant.push(copy, n);
  p.bus->to_plant.push(copy, n);
  msg::ActuatorFrame a{};
  ASSERT_EQ(p.plant.receive(Pair::soon(), a), hil::RxStatus::kMessage);
  EXPECT_EQ(p.plant.receive(Pair::now() + 20'000'000, a), hil::RxStatus::kTimeout);
  EXPECT_EQ(p.plant.guard().counters().replayed, 1u);
}

TEST(LinkGuard, AFrameUnderAnotherKeyIsRefusedBeforeTheHandshake) {
  Pair p(key(1));
  // The tick-0 sensor frame of a plant with another key: the controller must not bind to it.
  hil::MemoryTransport other_side{p.bus->to_controller, p.bus->to_plant};
  hil::FrameEndpoint<hil::MemoryTransport> other_plant(other_side, hil::plant_guard(0x55555555, key(2)), msg::kSignals);
  ASSERT_TRUE(other_plant.send(sensor(0), 0));
  msg::SensorFrame s{};
  EXPECT_EQ(p.controller.receive(Pair::now() + 20'000'000, s), hil::RxStatus::kTimeout);
  EXPECT_EQ(p.controller.guard().counters().bad_mac, 1u);
  EXPECT_FALSE(p.controller.guard().bound());
  p.handshake();  // the genuine plant still binds it
  EXPECT_EQ(p.controller.guard().session(), kSession);
}

TEST(FrameOrderJump, ASequenceJumpCannotLockTheGenuinePeerOut) {
  hil::FrameOrder o;
  o.accept(10, 10);
  // A frame of the right tick whose sequence leaps 2^30 ahead: accepted, every genuine frame after it would
  // look stale.
  EXPECT_EQ(o.classify(11, 10u + (1u << 30), 11), hil::OrderVerdict::kJump);
  EXPECT_EQ(o.classify(11, 11, 11), hil::OrderVerdict::kExpected) << "the genuine frame still passes";
  o.accept(11, 11);
  // After lost frames the sequence may advance by the ticks between them (and a small slack).
  EXPECT_EQ(o.classify(15, 15, 15), hil::OrderVerdict::kExpected);
  EXPECT_EQ(o.classify(15, 11 + 4 + hil::kSequenceSlack, 15), hil::OrderVerdict::kExpected);
  EXPECT_EQ(o.classify(15, 11 + 4 + hil::kSequenceSlack + 1, 15), hil::OrderVerdict::kJump);
}

}  // namespace link_guard_test
}  // namespace gyrostab
