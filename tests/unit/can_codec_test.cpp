// CAN FD codec (hil/can/frame_codec.hpp) over every map of the build and the tests' own device: frames cross
// the bus bit for bit (NaN payloads, -0.0, subnormals and infinities as doubles; integers up to their types'
// extremes), the encoder refuses what cannot travel exactly (a value that rides as an integer but is not one of
// its type), and every kind of bad frame is
// rejected with its cause and counted, without disturbing the set of the tick it arrives in.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "hil/can/frame_codec.hpp"
#include "sim/random/seeded_rng.hpp"
#include "tests/unit/can_test_maps.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab::can {
namespace can_codec_test {

using testing::same_bits;

TEST(CanCodec, FramesCrossEveryBusBitForBit) {
  random::SeededRng rng(42, 1);
  for (const testing::TestBus& b : testing::test_buses()) {
    SCOPED_TRACE(b.label);
    FrameEncoder se(b.bus, Direction::kSensor), ae(b.bus, Direction::kActuator);
    SetAssembler srx(b.bus, Direction::kSensor), arx(b.bus, Direction::kActuator);
    std::array<CanFrame, kMaxMessagesPerDirection> frames{};
    for (std::uint64_t tick = 0; tick < 40; ++tick) {  // > 16: the alive counters wrap
      const msg::AnySensorFrame s = testing::random_sensor(b.bus, tick, rng);
      std::size_t n = se.encode(s, frames);
      ASSERT_EQ(n, se.frames_per_set());
      ASSERT_EQ(n, b.bus.frames(Direction::kSensor));
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(srx.accept(frames[i]), FrameError::kNone) << "tick " << tick << " frame " << i;
        EXPECT_EQ(srx.ready(), i + 1 == n);
      }
      msg::AnySensorFrame s_out{};
      ASSERT_TRUE(srx.take(s_out));
      EXPECT_TRUE(same_bits(s_out, s)) << "tick " << tick;

      const msg::AnyActuatorFrame a = testing::random_actuator(b.bus, tick, rng);
      n = ae.encode(a, frames);
      ASSERT_EQ(n, b.bus.frames(Direction::kActuator));
      EXPECT_TRUE(b.bus.messages()[static_cast<std::size_t>(b.bus.index_of(frames[n - 1].id))].header)
          << "the header goes last";
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(arx.accept(frames[i]), FrameError::kNone);
      msg::AnyActuatorFrame a_out{};
      ASSERT_TRUE(arx.take(a_out));
      EXPECT_TRUE(same_bits(a_out, a)) << "tick " << tick;
    }
    EXPECT_EQ(srx.counters().rejected_total() + arx.counters().rejected_total(), 0u);
    EXPECT_EQ(srx.counters().sets_completed, 40u);
  }
}

TEST(CanCodec, TheUnionFixtureTypedFramesCrossWithTheirEncoderCountsAsInt32) {
  const DeviceBus bus = whole_bus(union_fixture::kCanMap);
  FrameEncoder enc(bus, Direction::kSensor);
  SetAssembler rx(bus, Direction::kSensor);
  msg::SensorFrame f{};
  f.tick = 7;
  f.encoder_count[0] = -2147483648.0;
  f.encoder_count[1] = 2147483647.0;
  f.gimbal_angle_rad[1] = -0.0;
  std::array<CanFrame, kMaxMessagesPerDirection> frames{};
  const std::size_t n = enc.encode(f, frames);
  ASSERT_EQ(n, 6u);
  const MessageSpec* drive1 = testing::message_named(union_fixture::kCanMap, "DRIVE1_FB");
  ASSERT_NE(drive1, nullptr);
  ASSERT_EQ(drive1->length, 32) << "four values, the encoder count as int32";
  for (std::size_t i = 0; i < n; ++i) {
    if (frames[i].id == drive1->id) {
      EXPECT_EQ(frames[i].data[28], 0x00);
      EXPECT_EQ(frames[i].data[31], 0x80) << "-2^31 as a little-endian int32 at bytes 28-31";
    }
    ASSERT_EQ(rx.accept(frames[i]), FrameError::kNone);
  }
  msg::SensorFrame out{};
  ASSERT_TRUE(rx.take(out));
  EXPECT_TRUE(same_bits(out, f));
}

TEST(CanCodec, NaNPayloadsPassUnchangedAndAreCounted) {
  const DeviceBus bus = whole_bus(union_fixture::kCanMap);
  FrameEncoder enc(bus, Direction::kSensor);
  SetAssembler rx(bus, Direction::kSensor);
  msg::SensorFrame f{};
  f.carrier_angle_rad[0] = std::bit_cast<double>(0x7FF8'0000'DEAD'BEEFull);  // a NaN with a payload
  f.gimbal_rate_rad_s[1] = 5000.0;                                            // beyond the ±1000 rad/s range
  std::array<CanFrame, kMaxMessagesPerDirection> frames{};
  const std::size_t n = enc.encode(f, frames);
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(rx.accept(frames[i]), FrameError::kNone);
  msg::SensorFrame out{};
  ASSERT_TRUE(rx.take(out));
  EXPECT_TRUE(same_bits(out, f)) << "the firmware's fault monitor decides, exactly as in-process";
  EXPECT_EQ(rx.counters().non_finite_values, 1u);
  EXPECT_EQ(rx.counters().out_of_range_values, 1u);
}

TEST(CanCodec, EncoderRefusesAValueThatIsNotAnIntegerOfItsType) {
  for (const testing::TestBus& b : testing::test_buses()) {
    for (Direction d : {Direction::kSensor, Direction::kActuator}) {
      const auto values = testing::values_on(b.bus, d);
      for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i].signal == nullptr || !values[i].signal->integer) continue;
        const SignalSpec& s = *values[i].signal;
        SCOPED_TRACE(b.label + " " + std::string(s.name));
        const double top = s.kind == SignalKind::kSigned ? std::ldexp(1.0, s.bit_length - 1) : std::ldexp(1.0, s.bit_length);
        const double bottom = s.kind == SignalKind::kSigned ? -top - 1.0 : -1.0;
        for (double bad : {0.5, -0.0, top, bottom, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(), 1e300}) {
          FrameEncoder enc(b.bus, d);
          std::array<CanFrame, kMaxMessagesPerDirection> frames{};
          FieldViolation v;
          std::size_t n = 0;
          if (d == Direction::kSensor) {
            msg::AnySensorFrame f{};
            f.signal[i] = bad;
            n = enc.encode(f, frames, &v);
          } else {
            msg::AnyActuatorFrame f{};
            f.signal[i] = bad;
            n = enc.encode(f, frames, &v);
          }
          EXPECT_EQ(n, 0u) << bad;
          EXPECT_EQ(v.cause, FieldViolation::Cause::kNotInteger);
          EXPECT_EQ(v.message, values[i].message->name);
          EXPECT_EQ(v.signal, s.name);
          EXPECT_TRUE(std::bit_cast<std::uint64_t>(v.value) == std::bit_cast<std::uint64_t>(bad)) << bad;
        }
      }
    }
  }
}

TEST(CanCodec, ARefusedFrameAdvancesNoAliveCounter) {
  const DeviceBus bus = whole_bus(union_fixture::kCanMap);
  FrameEncoder enc(bus, Direction::kSensor);
  SetAssembler rx(bus, Direction::kSensor);
  std::array<CanFrame, kMaxMessagesPerDirection> frames{};
  msg::SensorFrame f{};
  f.encoder_count[0] = 0.25;
  EXPECT_EQ(enc.encode(f, frames), 0u);
  f.encoder_count[0] = 3.0;
  for (std::uint64_t k = 0; k < 2; ++k) {
    f.tick = k;
    const std::size_t n = enc.encode(f, frames);
    ASSERT_EQ(n, 6u);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_EQ(frames[i].data[kAliveByte], k);
      ASSERT_EQ(rx.accept(frames[i]), FrameError::kNone);
    }
    msg::SensorFrame out{};
    ASSERT_TRUE(rx.take(out));
  }
}

// Fixture: one good sensor set of tick k of the union fixture's bus, to corrupt one frame at a time.
class CanBadFrames : public ::testing::Test {
 protected:
  std::size_t make_set(std::uint64_t tick) {
    random::SeededRng rng(tick + 1, 1);
    frame_ = testing::random_sensor(bus_, tick, rng);
    return enc_.encode(frame_, frames_);
  }
  void resign(CanFrame& c) { c.data[kCrcByte] = frame_crc(c.id, c.data, c.len); }
  FrameError feed(const CanFrame& c) { return rx_.accept(c); }
  std::uint32_t id_of(std::string_view name) const { return testing::message_named(*bus_.map, name)->id; }

  DeviceBus bus_ = whole_bus(union_fixture::kCanMap);
  FrameEncoder enc_{bus_, Direction::kSensor};
  SetAssembler rx_{bus_, Direction::kSensor};
  msg::AnySensorFrame frame_{};
  std::array<CanFrame, kMaxMessagesPerDirection> frames_{};
};

TEST_F(CanBadFrames, EachCauseIsRejectedAndCountedAndTheSetStillCompletes) {
  const std::size_t n = make_set(0);
  ASSERT_EQ(n, 6u);
  CanFrame bad = frames_[1];  // DRIVE1_FB
  ASSERT_EQ(bad.id, id_of("DRIVE1_FB"));
  const std::uint32_t command_id = id_of("CONTROLLER_CMD");
  struct Case {
    FrameError want;
    void (*mutate)(CanFrame&, std::uint32_t);
  };
  const Case cases[] = {
      {FrameError::kErrorFrame, [](CanFrame& c, std::uint32_t) { c.flags |= kFlagError; }},
      {FrameError::kRemote, [](CanFrame& c, std::uint32_t) { c.flags |= kFlagRemote; }},
      {FrameError::kExtendedId, [](CanFrame& c, std::uint32_t) { c.flags |= kFlagExtended; }},
      {FrameError::kUnknownId, [](CanFrame& c, std::uint32_t) { c.id = 0x555; }},
      {FrameError::kWrongDirection, [](CanFrame& c, std::uint32_t cmd) { c.id = cmd; }},
      {FrameError::kNotFd, [](CanFrame& c, std::uint32_t) { c.flags = 0; c.len = 8; }},
      {FrameError::kWrongLength, [](CanFrame& c, std::uint32_t) { c.len = 48; }},
      {FrameError::kBadCrc, [](CanFrame& c, std::uint32_t) { c.data[5] ^= 0x01; }},
  };
  std::uint64_t rejected = 0;
  for (const Case& k : cases) {
    CanFrame c = bad;
    k.mutate(c, command_id);
    EXPECT_EQ(feed(c), k.want) << frame_error_name(k.want);
    EXPECT_EQ(rx_.counters().count(k.want), 1u) << frame_error_name(k.want);
    EXPECT_EQ(rx_.counters().last_error, k.want);
    ++rejected;
  }
  // Reserved bits with a valid CRC (a sender that sets them is broken, not the bus).
  CanFrame r = bad;
  r.data[kAliveByte] |= 0x80;
  resign(r);
  EXPECT_EQ(feed(r), FrameError::kReservedBits);
  // Padding: DRIVE1_FB uses all its 32 bytes, the IMU frame 52 of its 64.
  CanFrame imu = frames_[0];
  ASSERT_EQ(imu.id, id_of("IMU_FB"));
  imu.data[60] = 0xAA;  // padding after byte 52
  resign(imu);
  EXPECT_EQ(feed(imu), FrameError::kReservedBits);
  rejected += 2;
  EXPECT_EQ(rx_.counters().rejected_total(), rejected);
  EXPECT_FALSE(rx_.ready());
  // None of that disturbed the good frames of the tick (alive counters untouched by rejected frames).
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(feed(frames_[i]), FrameError::kNone);
  msg::AnySensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  EXPECT_TRUE(same_bits(out, frame_));
}

TEST_F(CanBadFrames, RepeatedCounterIsStaleAndSkippedCounterResynchronises) {
  make_set(0);
  for (std::size_t i = 0; i < 6; ++i) ASSERT_EQ(feed(frames_[i]), FrameError::kNone);
  msg::AnySensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  // The same DRIVE1_FB frame again, unchanged (a stuck sender or a replayed buffer): stale.
  EXPECT_EQ(feed(frames_[1]), FrameError::kCounterRepeated);
  make_set(1);
  make_set(2);  // tick 1's frames are lost: tick 2's counters are two ahead
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(feed(frames_[i]), FrameError::kCounterSkipped);
  EXPECT_FALSE(rx_.ready()) << "tick 2's set was rejected frame by frame";
  make_set(3);  // resynchronised: the next frames in sequence are accepted again
  for (std::size_t i = 0; i < 6; ++i) ASSERT_EQ(feed(frames_[i]), FrameError::kNone);
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 3u);
  // DRIVE1_FB was repeated once, then its frame of tick 2 and every other frame of tick 2 skipped.
  EXPECT_EQ(rx_.counters().count(FrameError::kCounterRepeated), 1u);
  EXPECT_EQ(rx_.counters().count(FrameError::kCounterSkipped), 6u);
}

TEST_F(CanBadFrames, HeaderTickMustMatchItsTag) {
  make_set(5);
  CanFrame h = frames_[5];
  ASSERT_EQ(h.id, id_of("SENSOR_HUB"));
  h.data[2] ^= 0x01;  // tag says tick 4
  resign(h);
  EXPECT_EQ(feed(h), FrameError::kTickMismatch);
}

TEST_F(CanBadFrames, ANewerTickAbandonsAnIncompleteSet) {
  make_set(0);
  ASSERT_EQ(feed(frames_[0]), FrameError::kNone);
  ASSERT_EQ(feed(frames_[1]), FrameError::kNone);  // tick 0 lacks the other frames and the header
  make_set(1);
  for (std::size_t i = 0; i < 6; ++i) ASSERT_EQ(feed(frames_[i]), FrameError::kNone);
  msg::AnySensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 1u);
  EXPECT_EQ(rx_.counters().sets_abandoned, 1u);
}

TEST_F(CanBadFrames, FramesOfASkippedTickAreLateButTheLastTakenTickMayRepeat) {
  make_set(0);
  for (std::size_t i = 0; i < 6; ++i) ASSERT_EQ(feed(frames_[i]), FrameError::kNone);
  msg::AnySensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  // A lockstep resend of tick 0 (new alive counters): delivered again, the loop's order check sees a repeat.
  make_set(0);
  for (std::size_t i = 0; i < 6; ++i) ASSERT_EQ(feed(frames_[i]), FrameError::kNone);
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 0u);
  // The loop gave up on ticks 1 and 2 (stepped them without a set); tick 1's frames arrive afterwards.
  rx_.skip_through(2);
  make_set(1);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(feed(frames_[i]), FrameError::kLate);
  EXPECT_FALSE(rx_.ready());
  make_set(3);
  for (std::size_t i = 0; i < 6; ++i) ASSERT_EQ(feed(frames_[i]), FrameError::kNone);
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 3u);
}

}  // namespace can_codec_test
}  // namespace gyrostab::can
