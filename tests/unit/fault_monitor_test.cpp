// The fault monitor (firmware/fault/fault_monitor.hpp): each cause — missing, stale, NaN/Inf, out of range,
// sensor-reported fault — is counted, held for one tick (hold_ticks = 1), and reaches the safe state at the
// second consecutive bad tick with the cause in the status bits; good frames pass untouched; recovery only
// after acknowledge() and a good frame.
#include "firmware/fault/fault_monitor.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "tests/support/alloc_counter.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab::firmware {
namespace fault_monitor_test {

using msg::ActuatorFrame;
using msg::bit;
using msg::FaultBit;
using msg::SensorFrame;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kLawTorque = 5.0;  // what the stand-in control law commands [N m]

// A plausible frame for controller tick k, every signal different and varying with k, sequence k + 100.
SensorFrame good_frame(std::uint64_t k) {
  SensorFrame f{};
  const double x = static_cast<double>(k % 1000) * 1e-4;
  f.tick = k;
  f.time_ns = static_cast<std::int64_t>(k) * 1'000'000;
  f.sample_time_ns = f.time_ns;
  f.sequence = static_cast<std::uint32_t>(k + 100);
  f.carrier_angle_rad[msg::kRoll] = 0.1 + x;
  f.carrier_angle_rad[msg::kPitch] = -0.02 - x;
  f.carrier_angle_rad[msg::kYaw] = 1.0 + x;
  f.carrier_rate_rad_s[msg::kRoll] = 0.05 + x;
  f.carrier_rate_rad_s[msg::kPitch] = -0.01;
  f.carrier_rate_rad_s[msg::kYaw] = 0.002;
  f.gimbal_angle_rad[msg::kAxis1] = 0.3 - x;
  f.gimbal_angle_rad[msg::kAxis2] = -0.4 + x;
  f.gimbal_rate_rad_s[msg::kAxis1] = 1.5 + x;
  f.gimbal_rate_rad_s[msg::kAxis2] = -0.7;
  f.motor_current_A[msg::kAxis1] = 2.0 + x;
  f.motor_current_A[msg::kAxis2] = -1.0;
  f.rotor_speed_rad_s = 600.0 + x;
  f.encoder_count[msg::kAxis1] = static_cast<std::int32_t>((k % 1000) * 3);
  f.encoder_count[msg::kAxis2] = -static_cast<std::int32_t>(k % 1000);
  return f;
}

bool same(const SensorFrame& a, const SensorFrame& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// One controller tick: check, a stand-in control law (torque kLawTorque on both axes, brake released, the
// sensor tick it used), apply.
struct TickResult {
  const SensorFrame* used{nullptr};
  ActuatorFrame command{};
};
TickResult tick(FaultMonitor& m, const SensorFrame* frame, std::uint64_t k) {
  TickResult r;
  r.used = m.check(frame, k);
  r.command.tick = k;
  if (r.used != nullptr) {
    r.command.sensor_tick = r.used->tick;
    r.command.gimbal_torque_Nm[msg::kAxis1] = kLawTorque;
    r.command.gimbal_torque_Nm[msg::kAxis2] = kLawTorque;
    r.command.motor_voltage_V[msg::kAxis1] = 12.0;
    r.command.motor_voltage_V[msg::kAxis2] = 12.0;
    r.command.precession_brake = 0.0;
  }
  m.apply(r.command);
  return r;
}
TickResult tick_good(FaultMonitor& m, std::uint64_t k) {
  const SensorFrame f = good_frame(k);
  return tick(m, &f, k);
}

bool is_safe_command(const ActuatorFrame& c) {
  return c.gimbal_torque_Nm[0] == 0.0 && c.gimbal_torque_Nm[1] == 0.0 && c.motor_voltage_V[0] == 0.0 &&
         c.motor_voltage_V[1] == 0.0 && c.precession_brake == 1.0 && c.cluster_rate_command_rad_s[0] == 0.0 &&
         c.cluster_rate_command_rad_s[1] == 0.0 && c.cluster_rate_command_rad_s[2] == 0.0 &&
         c.cluster_rate_command_rad_s[3] == 0.0 && msg::has(c.status, FaultBit::kSafeState);
}

// Writes `value` into value i of a frame (frame order, as the signal table lists them).
void set_signal(SensorFrame& f, std::size_t i, double value) {
  msg::set_signal_value(f, i, value);
}
constexpr std::size_t kSensorSignalCount = msg::SensorIndex::count;

// Ranges every good_frame() satisfies, narrow enough that each signal has a finite bound to break
// (encoder counts included).
FaultMonitorConfig narrow_config() {
  FaultMonitorConfig c;
  for (Range& r : c.ranges.carrier_angle_rad) r = {-1.5, 1.5};
  for (Range& r : c.ranges.carrier_rate_rad_s) r = {-1.0, 1.0};
  for (Range& r : c.ranges.gimbal_angle_rad) r = {-1.2, 1.2};
  for (Range& r : c.ranges.gimbal_rate_rad_s) r = {-5.0, 5.0};
  for (Range& r : c.ranges.motor_current_A) r = {-10.0, 10.0};
  c.ranges.rotor_speed_rad_s = {0.0, 700.0};
  for (Range& r : c.ranges.encoder_count) r = {-100'000.0, 100'000.0};
  return c;
}

std::uint64_t cause_count(const FaultCounters& c, FaultBit cause) {
  switch (cause) {
    case FaultBit::kSensorMissing:
      return c.missing;
    case FaultBit::kSensorStale:
      return c.stale;
    case FaultBit::kSensorNonFinite:
      return c.non_finite;
    case FaultBit::kSensorOutOfRange:
      return c.out_of_range;
    case FaultBit::kSensorReportedFault:
      return c.sensor_reported;
    default:
      return 0;
  }
}

// --- good frames ---------------------------------------------------------------------------------------

TEST(FaultMonitor, GoodFramesPassUntouched) {
  FaultMonitor m{narrow_config()};
  for (std::uint64_t k = 0; k < 1000; ++k) {
    const SensorFrame f = good_frame(k);
    const TickResult r = tick(m, &f, k);
    ASSERT_NE(r.used, nullptr) << "tick " << k;
    ASSERT_TRUE(same(*r.used, f)) << "tick " << k;
    ASSERT_EQ(r.command.status, 0u) << "tick " << k;
    ASSERT_EQ(r.command.gimbal_torque_Nm[msg::kAxis2], kLawTorque);
    ASSERT_EQ(r.command.precession_brake, 0.0);
    ASSERT_EQ(m.state(), MonitorState::kNormal);
  }
  const FaultCounters& c = m.counters();
  EXPECT_EQ(c.good_frames, 1000u);
  EXPECT_EQ(c.missing + c.stale + c.non_finite + c.out_of_range + c.sensor_reported, 0u);
  EXPECT_EQ(c.frames_lost, 0u);
  EXPECT_EQ(c.held_ticks + c.safe_ticks + c.trips, 0u);
}

TEST(FaultMonitor, StartsInTheSafeCommandUntilTheFirstGoodFrame) {
  FaultMonitor m;
  TickResult r = tick(m, nullptr, 0);
  EXPECT_EQ(r.used, nullptr);
  EXPECT_TRUE(is_safe_command(r.command));
  EXPECT_EQ(r.command.status,
            bit(FaultBit::kSafeState) | bit(FaultBit::kAwaitingFirstFrame) | bit(FaultBit::kSensorMissing));
  EXPECT_EQ(m.state(), MonitorState::kAwaitingFirstFrame);
  r = tick_good(m, 1);
  EXPECT_NE(r.used, nullptr);
  EXPECT_EQ(r.command.status, 0u);
  EXPECT_EQ(m.state(), MonitorState::kNormal);
  EXPECT_EQ(m.counters().trips, 0u);  // start-up is not a trip
}

// --- each cause: held one tick, safe at the second --------------------------------------------------------

struct CauseCase {
  std::string name;
  FaultBit cause;
  // The frame delivered at bad tick k (nullptr: none); `previous` is the last good frame delivered.
  std::function<bool(SensorFrame& out, std::uint64_t k, const SensorFrame& previous)> make;
  std::function<void(FaultMonitorConfig&)> configure = [](FaultMonitorConfig&) {};
  std::uint64_t tick_step = 1;  // controller tick increment into the first bad tick
};

std::vector<CauseCase> cause_cases() {
  std::vector<CauseCase> cases;
  cases.push_back({"missing", FaultBit::kSensorMissing,
                   [](SensorFrame&, std::uint64_t, const SensorFrame&) { return false; }});
  cases.push_back({"stale: sequence repeated", FaultBit::kSensorStale,
                   [](SensorFrame& f, std::uint64_t k, const SensorFrame& prev) {
                     f = good_frame(k);
                     f.sequence = prev.sequence;
                     return true;
                   }});
  cases.push_back({"stale: sequence went backwards", FaultBit::kSensorStale,
                   [](SensorFrame& f, std::uint64_t k, const SensorFrame& prev) {
                     f = good_frame(k);
                     f.sequence = prev.sequence - 5;
                     return true;
                   }});
  cases.push_back({"stale: tick not advancing", FaultBit::kSensorStale,
                   [](SensorFrame& f, std::uint64_t k, const SensorFrame& prev) {
                     f = good_frame(k);
                     f.tick = prev.tick;  // sequence advances, tick does not
                     return true;
                   },
                   [](FaultMonitorConfig& c) { c.max_age_ticks = 5; }});  // so age alone is no fault
  cases.push_back({"stale: older than max_age_ticks", FaultBit::kSensorStale,
                   [](SensorFrame& f, std::uint64_t k, const SensorFrame&) {
                     f = good_frame(k - 2);  // new (tick and sequence advance) but two ticks old
                     f.sequence += 50;
                     return true;
                   },
                   [](FaultMonitorConfig& c) { c.max_age_ticks = 1; }, 3});
  cases.push_back({"stale: stamped ahead of the controller", FaultBit::kSensorStale,
                   [](SensorFrame& f, std::uint64_t k, const SensorFrame&) {
                     f = good_frame(k + 1);
                     return true;
                   }});
  cases.push_back(
      {"NaN", FaultBit::kSensorNonFinite, [](SensorFrame& f, std::uint64_t k, const SensorFrame&) {
         f = good_frame(k);
         f.carrier_rate_rad_s[msg::kRoll] = kNaN;
         return true;
       }});
  cases.push_back(
      {"+Inf", FaultBit::kSensorNonFinite, [](SensorFrame& f, std::uint64_t k, const SensorFrame&) {
         f = good_frame(k);
         f.gimbal_angle_rad[msg::kAxis2] = kInf;
         return true;
       }});
  cases.push_back(
      {"-Inf", FaultBit::kSensorNonFinite, [](SensorFrame& f, std::uint64_t k, const SensorFrame&) {
         f = good_frame(k);
         f.rotor_speed_rad_s = -kInf;
         return true;
       }});
  cases.push_back(
      {"out of range", FaultBit::kSensorOutOfRange, [](SensorFrame& f, std::uint64_t k, const SensorFrame&) {
         f = good_frame(k);
         f.gimbal_angle_rad[msg::kAxis2] = 1.25;  // beyond the 1.2 rad end stop
         return true;
       }});
  cases.push_back({"drive fault reported", FaultBit::kSensorReportedFault,
                   [](SensorFrame& f, std::uint64_t k, const SensorFrame&) {
                     f = good_frame(k);
                     f.status = bit(msg::SensorStatusBit::kDriveFault);
                     return true;
                   }});
  return cases;
}

TEST(FaultMonitor, EachCauseIsHeldOneTickThenReachesTheSafeStateWithItsBit) {
  for (const CauseCase& c : cause_cases()) {
    SCOPED_TRACE(c.name);
    FaultMonitorConfig config = narrow_config();
    c.configure(config);
    FaultMonitor m{config};
    constexpr std::uint64_t kLastGood = 9;
    for (std::uint64_t k = 0; k <= kLastGood; ++k) ASSERT_EQ(tick_good(m, k).command.status, 0u);
    const SensorFrame last_good = good_frame(kLastGood);

    // First bad tick: held. The law runs on the last good frame; the command says so.
    std::uint64_t k = kLastGood + c.tick_step;
    SensorFrame bad{};
    bool delivered = c.make(bad, k, last_good);
    TickResult r = tick(m, delivered ? &bad : nullptr, k);
    EXPECT_EQ(m.state(), MonitorState::kHolding);
    ASSERT_NE(r.used, nullptr);
    EXPECT_TRUE(same(*r.used, last_good));
    EXPECT_EQ(r.command.sensor_tick, kLastGood);
    EXPECT_EQ(r.command.status, bit(FaultBit::kHoldingLastGood) | bit(c.cause));
    EXPECT_EQ(r.command.gimbal_torque_Nm[msg::kAxis2], kLawTorque);
    EXPECT_EQ(r.command.precession_brake, 0.0);
    EXPECT_EQ(m.causes(), bit(c.cause));
    EXPECT_EQ(cause_count(m.counters(), c.cause), 1u);
    EXPECT_EQ(m.counters().held_ticks, 1u);

    // Second bad tick: safe state, the cause latched in the status.
    ++k;
    delivered = c.make(bad, k, last_good);
    r = tick(m, delivered ? &bad : nullptr, k);
    EXPECT_EQ(m.state(), MonitorState::kSafe);
    EXPECT_EQ(r.used, nullptr);
    EXPECT_TRUE(is_safe_command(r.command));
    EXPECT_EQ(r.command.status, bit(FaultBit::kSafeState) | bit(c.cause));
    EXPECT_EQ(cause_count(m.counters(), c.cause), 2u);
    EXPECT_EQ(m.counters().trips, 1u);
    EXPECT_EQ(m.counters().safe_ticks, 1u);

    // Good frames afterwards do not release it (latched) and the reason stays.
    for (++k; k < 30; ++k) {
      r = tick_good(m, k);
      ASSERT_EQ(m.state(), MonitorState::kSafe);
      ASSERT_TRUE(is_safe_command(r.command));
      ASSERT_EQ(r.command.status, bit(FaultBit::kSafeState) | bit(c.cause));
    }
    EXPECT_EQ(m.counters().trips, 1u);
  }
}

TEST(FaultMonitor, OneBadTickIsBridgedAndNeverReachesTheSafeState) {
  for (const CauseCase& c : cause_cases()) {
    if (c.tick_step != 1) continue;  // the age case needs a tick gap; it is covered above
    SCOPED_TRACE(c.name);
    FaultMonitorConfig config = narrow_config();
    c.configure(config);
    FaultMonitor m{config};
    for (std::uint64_t k = 0; k < 10; ++k) tick_good(m, k);
    SensorFrame bad{};
    const bool delivered = c.make(bad, 10, good_frame(9));
    tick(m, delivered ? &bad : nullptr, 10);
    const TickResult r = tick_good(m, 11);
    EXPECT_EQ(m.state(), MonitorState::kNormal);
    EXPECT_EQ(r.command.status, 0u);
    ASSERT_NE(r.used, nullptr);
    EXPECT_EQ(r.used->tick, 11u);
    EXPECT_EQ(m.counters().trips, 0u);
    EXPECT_EQ(m.counters().held_ticks, 1u);
  }
}

TEST(FaultMonitor, HoldTicksSetsWhenTheSafeStateStarts) {
  for (std::uint32_t hold : {0u, 1u, 3u}) {
    SCOPED_TRACE(hold);
    FaultMonitorConfig config;
    config.hold_ticks = hold;
    FaultMonitor m{config};
    for (std::uint64_t k = 0; k < 10; ++k) tick_good(m, k);
    // Missing from tick 10 on: held at ticks 10 .. 10 + hold - 1, safe from tick 10 + hold.
    for (std::uint64_t k = 10; k < 10 + hold; ++k) {
      const TickResult r = tick(m, nullptr, k);
      ASSERT_EQ(m.state(), MonitorState::kHolding) << "tick " << k;
      ASSERT_NE(r.used, nullptr);
      ASSERT_EQ(r.used->tick, 9u);
    }
    const TickResult r = tick(m, nullptr, 10 + hold);
    EXPECT_EQ(m.state(), MonitorState::kSafe);
    EXPECT_TRUE(is_safe_command(r.command));
    EXPECT_EQ(m.counters().held_ticks, hold);
    EXPECT_EQ(m.counters().missing, hold + 1u);
  }
}

TEST(FaultMonitor, SafeStateReasonIsEveryCauseOfTheBadRun) {
  FaultMonitor m{narrow_config()};
  for (std::uint64_t k = 0; k < 10; ++k) tick_good(m, k);
  tick(m, nullptr, 10);  // missing
  SensorFrame nan = good_frame(11);
  nan.motor_current_A[msg::kAxis1] = kNaN;
  nan.rotor_speed_rad_s = 900.0;  // also out of range
  const TickResult r = tick(m, &nan, 11);
  EXPECT_EQ(r.command.status, bit(FaultBit::kSafeState) | bit(FaultBit::kSensorMissing) |
                                  bit(FaultBit::kSensorNonFinite) | bit(FaultBit::kSensorOutOfRange));
  EXPECT_EQ(m.counters().last_non_finite_signal, msg::SensorIndex::motor_current_A + msg::kAxis1);
  EXPECT_EQ(m.counters().last_out_of_range_signal, msg::SensorIndex::rotor_speed_rad_s);
  // Later causes are counted but do not change the latched reason.
  SensorFrame stale = good_frame(12);
  stale.sequence = nan.sequence;
  EXPECT_EQ(tick(m, &stale, 12).command.status, r.command.status);
  EXPECT_EQ(m.counters().stale, 1u);
}

// --- every signal is checked -------------------------------------------------------------------------------

TEST(FaultMonitor, EverySignalIsCheckedForRangeAndBoundsAreInclusive) {
  const FaultMonitorConfig config = narrow_config();
  for (std::size_t i = 0; i < kSensorSignalCount; ++i) {
    const auto id = static_cast<std::uint8_t>(i);
    SCOPED_TRACE(i);
    // The bound itself is in range.
    const Range range = range_at(config.ranges, i);
    FaultMonitor m{config};
    tick_good(m, 0);
    SensorFrame at_bound = good_frame(1);
    set_signal(at_bound, id, range.max);
    tick(m, &at_bound, 1);
    EXPECT_EQ(m.causes(), 0u);
    SensorFrame below = good_frame(2);
    set_signal(below, id, range.min);
    tick(m, &below, 2);
    EXPECT_EQ(m.causes(), 0u);
    // One step beyond it is not.
    SensorFrame beyond = good_frame(3);
    set_signal(beyond, id, range.max + 1.0);
    tick(m, &beyond, 3);
    EXPECT_EQ(m.causes(), bit(FaultBit::kSensorOutOfRange));
    EXPECT_EQ(m.counters().last_out_of_range_signal, id);
    SensorFrame under = good_frame(4);
    set_signal(under, id, range.min - 1.0);
    tick(m, &under, 4);
    EXPECT_EQ(m.state(), MonitorState::kSafe);
    EXPECT_EQ(m.status(), bit(FaultBit::kSafeState) | bit(FaultBit::kSensorOutOfRange));
    EXPECT_EQ(m.counters().out_of_range, 2u);
  }
}

TEST(FaultMonitor, EverySignalIsCheckedForNaN) {
  for (std::size_t i = 0; i < kSensorSignalCount; ++i) {
    const auto id = static_cast<std::uint8_t>(i);
    SCOPED_TRACE(i);
    FaultMonitor m{narrow_config()};
    tick_good(m, 0);
    SensorFrame f = good_frame(1);
    set_signal(f, id, kNaN);
    tick(m, &f, 1);
    EXPECT_EQ(m.causes(), bit(FaultBit::kSensorNonFinite));  // NaN is not also "out of range"
    EXPECT_EQ(m.counters().last_non_finite_signal, id);
    EXPECT_EQ(m.counters().out_of_range, 0u);
  }
}

// --- sequence tracking
// ---------------------------------------------------------------------------------------

TEST(FaultMonitor, SequenceJumpCountsLostFramesWithoutAFault) {
  FaultMonitor m;
  tick_good(m, 0);
  SensorFrame f = good_frame(1);
  f.sequence += 4;  // frames 101 .. 104 lost in transport
  tick(m, &f, 1);
  EXPECT_EQ(m.state(), MonitorState::kNormal);
  EXPECT_EQ(m.counters().frames_lost, 4u);
  EXPECT_EQ(m.causes(), 0u);
}

TEST(FaultMonitor, SequenceWrapsAt2To32) {
  FaultMonitor m;
  SensorFrame f = good_frame(0);
  f.sequence = 0xFFFFFFFFu;
  tick(m, &f, 0);
  f = good_frame(1);
  f.sequence = 0;
  tick(m, &f, 1);
  EXPECT_EQ(m.causes(), 0u);
  EXPECT_EQ(m.state(), MonitorState::kNormal);
  EXPECT_EQ(m.counters().frames_lost, 0u);
}

TEST(FaultMonitor, SaturatedRateGyroIsNotAFaultByDefault) {
  FaultMonitor m;
  tick_good(m, 0);
  SensorFrame f = good_frame(1);
  f.status = bit(msg::SensorStatusBit::kRateGyroSaturated);
  tick(m, &f, 1);
  EXPECT_EQ(m.causes(), 0u);
  f = good_frame(2);
  f.status = bit(msg::SensorStatusBit::kEncoderError);
  tick(m, &f, 2);
  EXPECT_EQ(m.causes(), bit(FaultBit::kSensorReportedFault));
}

// --- recovery ----------------------------------------------------------------------------------------------

void trip_by_missing_frames(FaultMonitor& m) {
  for (std::uint64_t k = 0; k < 10; ++k) tick_good(m, k);
  tick(m, nullptr, 10);
  tick(m, nullptr, 11);
  ASSERT_EQ(m.state(), MonitorState::kSafe);
}

TEST(FaultMonitor, RecoversOnlyAfterAcknowledgeAndAGoodFrame) {
  FaultMonitor m;
  trip_by_missing_frames(m);
  for (std::uint64_t k = 12; k < 100; ++k) tick_good(m, k);
  EXPECT_EQ(m.state(), MonitorState::kSafe);  // 88 good frames: still latched

  m.acknowledge();
  TickResult r = tick(m, nullptr, 100);  // the attempt meets a bad tick: refused
  EXPECT_EQ(m.state(), MonitorState::kSafe);
  EXPECT_EQ(m.counters().acknowledgements_refused, 1u);
  r = tick_good(m, 101);  // the refused attempt is used up
  EXPECT_EQ(m.state(), MonitorState::kSafe);

  m.acknowledge();
  r = tick_good(m, 102);
  EXPECT_EQ(m.state(), MonitorState::kNormal);
  ASSERT_NE(r.used, nullptr);
  EXPECT_TRUE(same(*r.used, good_frame(102)));
  EXPECT_EQ(r.command.status, 0u);
  EXPECT_EQ(r.command.gimbal_torque_Nm[msg::kAxis2], kLawTorque);
  EXPECT_EQ(m.counters().recoveries, 1u);

  // After recovery the full hold-then-safe sequence applies again.
  tick(m, nullptr, 103);
  EXPECT_EQ(m.state(), MonitorState::kHolding);
  tick(m, nullptr, 104);
  EXPECT_EQ(m.state(), MonitorState::kSafe);
  EXPECT_EQ(m.counters().trips, 2u);
}

TEST(FaultMonitor, AcknowledgeOutsideTheSafeStateIsIgnored) {
  FaultMonitor m;
  for (std::uint64_t k = 0; k < 10; ++k) tick_good(m, k);
  m.acknowledge();  // nothing to acknowledge: must not pre-arm a recovery
  tick(m, nullptr, 10);
  tick(m, nullptr, 11);
  tick_good(m, 12);
  EXPECT_EQ(m.state(), MonitorState::kSafe);
  EXPECT_EQ(m.counters().recoveries, 0u);
}

TEST(FaultMonitor, AcknowledgeResynchronisesARestartedSensorSide) {
  FaultMonitor m;
  trip_by_missing_frames(m);
  SensorFrame restarted = good_frame(12);
  restarted.sequence = 0;  // the plant restarted its counter: would be "going backwards"
  tick(m, &restarted, 12);
  EXPECT_EQ(m.causes(), bit(FaultBit::kSensorStale));
  m.acknowledge();
  restarted = good_frame(13);
  restarted.sequence = 1;
  tick(m, &restarted, 13);
  EXPECT_EQ(m.causes(), 0u);
  EXPECT_EQ(m.state(), MonitorState::kNormal);
}

TEST(FaultMonitor, CheckAndApplyAllocateNothing) {
  FaultMonitor m{narrow_config()};
  std::vector<SensorFrame> frames;
  for (std::uint64_t k = 0; k < 100'000; ++k) frames.push_back(good_frame(k));
  frames[500].rotor_speed_rad_s = kNaN;
  gyrostab::testing::AllocationCounter allocations;
  for (std::uint64_t k = 0; k < frames.size(); ++k) {
    const SensorFrame* in = (k % 1000 == 7) ? nullptr : &frames[k];
    ActuatorFrame out{};
    m.check(in, k);
    m.apply(out);
  }
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(m.counters().missing, 100u);
  EXPECT_EQ(m.counters().non_finite, 1u);
  EXPECT_EQ(m.state(), MonitorState::kNormal);
}

}  // namespace fault_monitor_test
}  // namespace gyrostab::firmware
