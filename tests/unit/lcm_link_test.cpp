// The pieces of the plant ⇄ controller link (the two-process LCM mode) without processes: the plant's
// actuator-frame checks, the frame-order rules, the endpoint's codec-level counting over the in-memory bus,
// the plant's lockstep wait (a bad command before the good one, a bad command alone, silence, late
// copies), the LCM
// transport over memq:// (an oversize message is measured and refused, not truncated), the latency histogram
// and the CLI parsers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "hil/lcm/frame_codec.hpp"
#include "hil/lcm/lcm_transport.hpp"
#include "hil/link/actuator_frame_check.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "hil/link/memory_bus.hpp"
#include "hil/rt/latency_histogram.hpp"
#include "tests/support/alloc_counter.hpp"
#include "tools/run/link_cli.hpp"
#include "tools/run/command_wait.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab {
namespace lcm_link_test {

constexpr std::uint64_t kSession = 0x2468ace0;
constexpr std::uint64_t kControllerId = 0x13579bdf;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

msg::ActuatorFrame command(std::uint64_t tick, double torque = 1.0) {
  msg::ActuatorFrame a{};
  a.tick = tick;
  a.sequence = static_cast<std::uint32_t>(tick);
  a.gimbal_torque_Nm[msg::kAxis2] = torque;
  return a;
}

TEST(ActuatorFrameCheck, EveryNonFiniteCommandAndEveryLimitIsRefused) {
  msg::ActuatorFrame limits = hil::ActuatorLimits::unlimited<msg::ActuatorFrame>();
  limits.gimbal_torque_Nm[0] = limits.gimbal_torque_Nm[1] = 10.0;
  limits.motor_voltage_V[0] = limits.motor_voltage_V[1] = 24.0;
  for (double& r : limits.cluster_rate_command_rad_s) r = 1.0;
  const hil::ActuatorLimits lim = hil::ActuatorLimits::of(limits);
  const msg::DeviceSignals& d = msg::kSignals;
  const auto check = [&](const msg::ActuatorFrame& a, const hil::ActuatorLimits& l) {
    return hil::check_actuator_values(msg::any_of(a), d, l);
  };
  EXPECT_EQ(check(command(0, 10.0), lim), hil::ActuatorVerdict::kOk) << "the limit itself is allowed";
  EXPECT_EQ(check(command(0, -10.0), lim), hil::ActuatorVerdict::kOk);
  for (std::size_t i = 0; i < d.commands.size(); ++i) {
    for (const double bad : {kNaN, kInf, -kInf}) {
      msg::ActuatorFrame a = command(0);
      msg::set_signal_value(a, i, bad);
      EXPECT_EQ(check(a, lim), hil::ActuatorVerdict::kNonFinite) << d.commands[i].name;
    }
  }
  msg::ActuatorFrame a = command(0, std::nextafter(10.0, 11.0));
  EXPECT_EQ(check(a, lim), hil::ActuatorVerdict::kOutOfRange);
  a = command(0);
  a.motor_voltage_V[0] = -24.5;
  EXPECT_EQ(check(a, lim), hil::ActuatorVerdict::kOutOfRange);
  for (std::size_t u = 0; u < msg::kClusterUnits; ++u) {
    a = command(0);
    a.cluster_rate_command_rad_s[u] = -1.0;
    EXPECT_EQ(check(a, lim), hil::ActuatorVerdict::kOk) << "the limit itself, unit " << u;
    a.cluster_rate_command_rad_s[u] = std::nextafter(-1.0, -2.0);
    EXPECT_EQ(check(a, lim), hil::ActuatorVerdict::kOutOfRange) << "unit " << u;
  }
  // Without the scene's limits, the signal table's range still holds: the brake in [0, 1], a torque within
  // the drive's plausible range (its ends allowed, one ulp beyond refused).
  for (const double brake : {-0.01, 1.01}) {
    a = command(0);
    a.precession_brake = brake;
    EXPECT_EQ(check(a, hil::ActuatorLimits{}), hil::ActuatorVerdict::kOutOfRange) << brake;
  }
  for (std::size_t i = 0; i < d.commands.size(); ++i) {
    const msg::SignalSpec& c = d.commands[i];
    a = command(0, 0.0);
    msg::set_signal_value(a, i, c.max);
    EXPECT_EQ(check(a, hil::ActuatorLimits{}), hil::ActuatorVerdict::kOk) << c.name << " at its maximum";
    msg::set_signal_value(a, i, std::nextafter(c.max, kInf));
    EXPECT_EQ(check(a, hil::ActuatorLimits{}), hil::ActuatorVerdict::kOutOfRange) << c.name << " past it";
    msg::set_signal_value(a, i, std::nextafter(c.min, -kInf));
    EXPECT_EQ(check(a, hil::ActuatorLimits{}), hil::ActuatorVerdict::kOutOfRange) << c.name << " below it";
  }
}

TEST(FrameOrder, ClassifiesAgainstTheExpectedTickAndTheLastAcceptedSequence) {
  hil::FrameOrder o;
  EXPECT_EQ(o.classify(0, 0, 0), hil::OrderVerdict::kExpected);
  o.accept(0, 0);
  EXPECT_EQ(o.classify(0, 0, 1), hil::OrderVerdict::kRepeated);
  EXPECT_EQ(o.classify(1, 1, 1), hil::OrderVerdict::kExpected);
  EXPECT_EQ(o.classify(1, 0, 1), hil::OrderVerdict::kStale) << "right tick, sequence not advancing";
  EXPECT_EQ(o.classify(3, 3, 1), hil::OrderVerdict::kAhead);
  o.accept(1, 1);
  EXPECT_EQ(o.classify(0, 7, 2), hil::OrderVerdict::kStale) << "older tick";
  // The sequence wraps at 2^32 (serial-number arithmetic).
  hil::FrameOrder w;
  w.accept(10, 0xFFFF'FFFFu);
  EXPECT_EQ(w.classify(11, 0u, 11), hil::OrderVerdict::kExpected);
  EXPECT_EQ(w.classify(11, 0xFFFF'FFFEu, 11), hil::OrderVerdict::kStale);
}

TEST(DriveWatchdog, IsZeroTorqueZeroVoltageBrakeReleased) {
  msg::ActuatorFrame z{};
  msg::from_any(hil::drive_watchdog_command(42), z);
  EXPECT_EQ(z.tick, 42u);
  EXPECT_EQ(z.gimbal_torque_Nm[0], 0.0);
  EXPECT_EQ(z.gimbal_torque_Nm[1], 0.0);
  EXPECT_EQ(z.motor_voltage_V[0], 0.0);
  EXPECT_EQ(z.motor_voltage_V[1], 0.0);
  EXPECT_EQ(z.precession_brake, 0.0);
}

struct Ends {
  std::unique_ptr<hil::MemoryBus> bus = std::make_unique<hil::MemoryBus>();
  hil::MemoryTransport plant_side{bus->to_controller, bus->to_plant};
  hil::MemoryTransport controller_side{bus->to_plant, bus->to_controller};
  hil::FrameEndpoint<hil::MemoryTransport> plant{plant_side, hil::plant_guard(kSession, std::nullopt), msg::kSignals};
  hil::FrameEndpoint<hil::MemoryTransport> controller{controller_side,
                                                      hil::controller_guard(kControllerId, kSession, std::nullopt), msg::kSignals};
};

TEST(FrameEndpoint, CountsCodecRejectionsAndPassesGoodFrames) {
  Ends e;
  std::uint8_t buf[hil::kMaxEncodedSize];
  const int n = hil::encode(msg::any_of(command(5)), msg::kSignals, 0, buf, sizeof buf, hil::LinkEnvelope{kControllerId, kSession, 1, 0});
  e.bus->to_plant.push(buf, n - 1);  // short
  buf[0] ^= 1;
  e.bus->to_plant.push(buf, n);  // fingerprint
  buf[0] ^= 1;
  msg::SensorFrame s{};
  std::uint8_t sbuf[hil::kMaxEncodedSize];
  e.bus->to_plant.push(sbuf, hil::encode(msg::any_of(s), msg::kSignals, 0, sbuf, sizeof sbuf));  // another type: its size differs
  e.bus->to_plant.push(buf, n);                                      // good
  msg::ActuatorFrame got{};
  ASSERT_EQ(e.plant.receive(hil::monotonic_ns() + 1'000'000'000, got), hil::RxStatus::kMessage);
  EXPECT_EQ(got.tick, 5u);
  const hil::LinkCounters& c = e.plant.counters();
  EXPECT_EQ(c.received, 4u);
  EXPECT_EQ(c.rejected_size, 2u);
  EXPECT_EQ(c.rejected_fingerprint, 1u);
  EXPECT_EQ(e.plant.receive(hil::monotonic_ns() + 1'000'000, got), hil::RxStatus::kTimeout);
  EXPECT_EQ(c.timeouts, 1u);
}

TEST(FrameEndpoint, SendAndReceiveDoNotAllocate) {
  Ends e;
  msg::SensorFrame s{};
  msg::ActuatorFrame a{};
  const testing::AllocationCounter count;
  for (int i = 0; i < 1000; ++i) {
    s.tick = static_cast<std::uint64_t>(i);
    ASSERT_TRUE(e.plant.send(s, i));
    ASSERT_EQ(e.controller.receive(hil::kNoDeadline, s), hil::RxStatus::kMessage);
    ASSERT_TRUE(e.controller.send(command(s.tick), i));
    ASSERT_EQ(e.plant.receive(hil::kNoDeadline, a), hil::RxStatus::kMessage);
  }
  EXPECT_EQ(count.count(), 0u);
}

// The plant's lockstep wait for the command of tick 7, with the controller's side scripted in advance.
struct Wait {
  Ends e;
  hil::FrameOrder order;
  tools::LinkSettings s;
  msg::ActuatorFrame got{};
  hil::SourceWatch watch;
  Wait() {
    s.resend_ns = 30'000'000;
    order.accept(6, 6);
  }
  tools::CommandWait run(std::int64_t lost_after_ns = 2'000'000'000) {
    const std::int64_t now = hil::monotonic_ns();
    msg::AnyActuatorFrame any{};
    const tools::CommandWait w = tools::wait_for_command(e.plant, order, hil::ActuatorLimits{}, msg::kSignals, 7,
                                                         hil::kNoDeadline, true, now + lost_after_ns, s, any, watch);
    msg::from_any(any, got);
    return w;
  }
};

TEST(PlantLockstepWait, ABadCommandBeforeTheGoodOneIsCountedAndTheGoodOneTaken) {
  Wait w;
  w.e.controller.send(command(7, kNaN), 0);
  w.e.controller.send(command(6), 0);  // repeated
  w.e.controller.send(command(3), 0);  // stale
  w.e.controller.send(command(9), 0);  // ahead
  w.e.controller.send(command(7, 2.5), 0);
  ASSERT_EQ(w.run(), tools::CommandWait::kAccepted);
  EXPECT_EQ(w.got.gimbal_torque_Nm[msg::kAxis2], 2.5);
  const hil::LinkCounters& c = w.e.plant.counters();
  EXPECT_EQ(c.rejected_non_finite, 1u);
  EXPECT_EQ(c.rejected_repeated, 1u);
  EXPECT_EQ(c.rejected_stale, 1u);
  EXPECT_EQ(c.rejected_ahead, 1u);
  EXPECT_EQ(c.accepted, 1u);
}

TEST(PlantLockstepWait, ABadCommandAloneEndsTheTickAfterOneResendIntervalWithoutResending) {
  Wait w;
  msg::ActuatorFrame bad = command(7);
  bad.precession_brake = 3.0;
  w.e.controller.send(bad, 0);
  const std::int64_t t0 = hil::monotonic_ns();
  ASSERT_EQ(w.run(), tools::CommandWait::kMissing);
  EXPECT_GE(hil::monotonic_ns() - t0, w.s.resend_ns);
  EXPECT_EQ(w.e.plant.counters().rejected_out_of_range, 1u);
  EXPECT_EQ(w.e.plant.counters().resent, 0u) << "the controller has answered; asking again changes nothing";
}

TEST(PlantLockstepWait, SilenceIsTheControllerLostAfterResends) {
  Wait w;
  w.e.plant.send(msg::SensorFrame{}, 0);  // what the resends repeat
  ASSERT_EQ(w.run(100'000'000), tools::CommandWait::kLost);
  EXPECT_GE(w.e.plant.counters().resent, 2u);  // every 30 ms within 100 ms
}

// Every tick, before the command, a copy of the command of two ticks ago arrives (a process replaying the bus
// late): refused as stale and counted, but no evidence of a second source while it repeats what was accepted;
// with other contents on 8 ticks in a row it is one (the genuine frames losing the race to a faster copier).
int lockstep_ticks_until_hijack(bool copies_differ) {
  Ends e;
  hil::FrameOrder order;
  tools::LinkSettings s;
  s.resend_ns = 30'000'000;
  hil::SourceWatch watch;
  for (std::uint64_t k = 0; k < 40; ++k) {
    if (k >= 2) e.controller.send(command(k - 2, copies_differ ? 3.0 : 1.0), 0);
    e.controller.send(command(k), 0);
    msg::AnyActuatorFrame any{};
    const tools::CommandWait w =
        tools::wait_for_command(e.plant, order, hil::ActuatorLimits{}, msg::kSignals, static_cast<std::int64_t>(k),
                                hil::kNoDeadline, true, hil::monotonic_ns() + 2'000'000'000, s, any, watch);
    EXPECT_EQ(w, tools::CommandWait::kAccepted) << "tick " << k;
    if (k == 0) e.plant.bind_to_last();
    watch.end_tick(static_cast<std::int64_t>(k), true);
    if (watch.hijacked()) return static_cast<int>(k);
  }
  EXPECT_EQ(e.plant.counters().rejected_stale, 38u);
  return -1;
}

TEST(PlantLockstepWait, LateCopiesOnEveryTickAreStaleButNotASecondSource) {
  EXPECT_EQ(lockstep_ticks_until_hijack(false), -1);
  EXPECT_EQ(lockstep_ticks_until_hijack(true), 2 + hil::SourceWatch::kStaleTicks - 1);
}

TEST(LcmTransport, MemqDeliversWholeMessagesAndMeasuresAnOversizeOne) {
  hil::LcmTransport t;
  std::string error;
  // memq:// is LCM's in-process provider: a message published on the subscribed channel comes back.
  ASSERT_TRUE(t.open("memq://", "GYROSTAB_ACTUATOR_unit", "GYROSTAB_ACTUATOR_unit", 10, error)) << error;
  hil::FrameEndpoint<hil::LcmTransport> ep(t, hil::plant_guard(kSession, std::nullopt), msg::kSignals);
  ASSERT_TRUE(ep.send(command(3), 3000));
  msg::ActuatorFrame a{};
  std::int64_t sim_us = 0;
  ASSERT_EQ(ep.receive(hil::monotonic_ns() + 1'000'000'000, a, &sim_us), hil::RxStatus::kMessage);
  EXPECT_EQ(a.tick, 3u);
  EXPECT_EQ(sim_us, 3000);
  std::vector<std::uint8_t> big(3 * hil::kMaxMessageBytes, 0);
  ASSERT_TRUE(t.publish(big.data(), static_cast<int>(big.size())));
  hil::Message m;
  ASSERT_EQ(t.receive(hil::monotonic_ns() + 1'000'000'000, m), hil::RxStatus::kMessage);
  EXPECT_EQ(m.size, static_cast<int>(big.size()));
  EXPECT_EQ(m.data, nullptr);
  ASSERT_TRUE(t.publish(big.data(), static_cast<int>(big.size())));
  EXPECT_EQ(ep.receive(hil::monotonic_ns() + 50'000'000, a), hil::RxStatus::kTimeout);
  EXPECT_EQ(ep.counters().rejected_size, 1u);
  EXPECT_EQ(t.receive(hil::monotonic_ns() + 1'000'000, m), hil::RxStatus::kTimeout);
}

TEST(LcmTransport, RefusesChannelSuffixesThatAreNotPlainNames) {
  EXPECT_TRUE(hil::valid_channel_suffix(""));
  EXPECT_TRUE(hil::valid_channel_suffix("_run-42"));
  for (const char* bad : {".", "a*", "a b", "x|y", "(", "\\"})
    EXPECT_FALSE(hil::valid_channel_suffix(bad)) << bad;
  EXPECT_FALSE(hil::valid_channel_suffix(std::string(41, 'a')));
}

TEST(LatencyHistogram, PercentilesToTheMicrosecondAndTheExactMax) {
  hil::LatencyHistogram h;
  for (int us = 1; us <= 100; ++us) h.add(us * 1000 - 500);  // 0.5, 1.5, ... 99.5 µs
  EXPECT_EQ(h.count(), 100u);
  EXPECT_EQ(h.quantile_ns(0.5), 50'000);
  EXPECT_EQ(h.quantile_ns(0.99), 99'000);
  EXPECT_EQ(h.max_ns(), 99'500);
  EXPECT_EQ(h.min_ns(), 500);
  h.add(50'000'000);  // beyond the bins: the max is exact, the top quantile is the max
  EXPECT_EQ(h.max_ns(), 50'000'000);
  EXPECT_EQ(h.quantile_ns(1.0), 50'000'000);
}

TEST(LinkCli, ParsesFaultWindowsAndJitter) {
  tools::FrameFault f;
  EXPECT_EQ(tools::parse_frame_fault("500:3", f), "");
  EXPECT_EQ(f.from, 500);
  EXPECT_EQ(f.count, 3);
  EXPECT_TRUE(f.covers(502));
  EXPECT_FALSE(f.covers(503));
  for (const char* bad : {"500", ":3", "a:3", "5:0", "-1:2", "5:2x"})
    EXPECT_NE(tools::parse_frame_fault(bad, f), "") << bad;
  tools::TransportOptions t;
  EXPECT_EQ(tools::parse_jitter("300", t), "");
  EXPECT_EQ(t.jitter_max_us, 300.0);
  EXPECT_EQ(t.jitter_probability, 1.0);
  EXPECT_EQ(tools::parse_jitter("2000@0.01", t), "");
  EXPECT_EQ(t.jitter_probability, 0.01);
  for (const char* bad : {"", "x", "-5", "10@0", "10@2", "10@", "10x"})
    EXPECT_NE(tools::parse_jitter(bad, t), "") << bad;
}

}  // namespace lcm_link_test
}  // namespace gyrostab
