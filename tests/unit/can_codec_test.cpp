// CAN FD codec (hil/can/frame_codec.hpp): contract frames cross the frame map bit for bit (NaN payloads and
// -0.0 included), and every kind of bad frame is rejected with its cause and counted, without disturbing the
// set of the tick it arrives in.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "hil/can/frame_codec.hpp"
#include "sim/random/seeded_rng.hpp"

namespace gyrostab::can {
namespace can_codec_test {

using msg::ActuatorFrame;
using msg::SensorFrame;

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

SensorFrame sample_sensor(std::uint64_t tick, random::SeededRng& rng) {
  SensorFrame f{};
  f.tick = tick;
  f.time_ns = static_cast<std::int64_t>(tick) * 1'000'000 + 17;
  f.sample_time_ns = f.time_ns - 250'000;
  f.sequence = static_cast<std::uint32_t>(tick * 7u);
  f.status = 0x5u;
  for (double& v : f.carrier_angle_rad) v = rng.uniform() - 0.5;
  for (double& v : f.carrier_rate_rad_s) v = 3.0 * (rng.uniform() - 0.5);
  for (double& v : f.gimbal_angle_rad) v = rng.uniform();
  for (double& v : f.gimbal_rate_rad_s) v = 100.0 * (rng.uniform() - 0.5);
  for (double& v : f.motor_current_A) v = rng.uniform() * 10.0;
  f.rotor_speed_rad_s = 600.0 + rng.uniform();
  f.encoder_count[0] = -123456;
  f.encoder_count[1] = static_cast<std::int32_t>(tick);
  for (double& v : f.cluster_gimbal_angle_rad) v = 6.0 * (rng.uniform() - 0.5);
  for (double& v : f.cluster_gimbal_rate_rad_s) v = rng.uniform() - 0.5;
  return f;
}

ActuatorFrame sample_actuator(std::uint64_t tick) {
  ActuatorFrame a{};
  a.tick = tick;
  a.time_ns = static_cast<std::int64_t>(tick) * 1'000'000;
  a.sensor_tick = tick == 0 ? 0 : tick - 1;
  a.sequence = static_cast<std::uint32_t>(tick);
  a.status = 0x300u;
  a.gimbal_torque_Nm[0] = -0.0;
  a.gimbal_torque_Nm[1] = 1.0e6 / 3.0;
  a.motor_voltage_V[0] = 12.5;
  a.motor_voltage_V[1] = -std::numeric_limits<double>::denorm_min();
  a.precession_brake = 1.0;
  a.cluster_rate_command_rad_s[0] = -0.0;
  a.cluster_rate_command_rad_s[1] = 0.25;
  a.cluster_rate_command_rad_s[2] = -1.0 / 3.0;
  a.cluster_rate_command_rad_s[3] = std::numeric_limits<double>::denorm_min();
  return a;
}

TEST(CanCodec, SensorFramesCrossBitForBitForEveryNodeSet) {
  random::SeededRng rng(42, 1);
  for (NodeSet nodes = 0; nodes <= kAllNodes; ++nodes) {
    FrameEncoder enc(Direction::kSensor, nodes);
    SetAssembler rx(Direction::kSensor, nodes);
    std::array<CanFrame, kMaxMessagesPerDirection> frames{};
    for (std::uint64_t tick = 0; tick < 40; ++tick) {  // > 16: the alive counters wrap
      SensorFrame f = sample_sensor(tick, rng);
      if ((nodes & kNodeImu) == 0) {
        for (double& v : f.carrier_angle_rad) v = 0.0;
        for (double& v : f.carrier_rate_rad_s) v = 0.0;
      }
      for (std::size_t a = 0; a < 2; ++a) {
        if ((nodes & (a == 0 ? kNodeDrive1 : kNodeDrive2)) != 0) continue;
        f.gimbal_angle_rad[a] = f.gimbal_rate_rad_s[a] = f.motor_current_A[a] = 0.0;
        f.encoder_count[a] = 0;
      }
      if ((nodes & kNodeCluster) == 0) {
        for (double& v : f.cluster_gimbal_angle_rad) v = 0.0;
        for (double& v : f.cluster_gimbal_rate_rad_s) v = 0.0;
      }
      const std::size_t n = enc.encode(f, frames);
      ASSERT_EQ(n, enc.frames_per_set());
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(rx.accept(frames[i]), FrameError::kNone) << "nodes " << int(nodes) << " tick " << tick;
        EXPECT_EQ(rx.ready(), i + 1 == n);
      }
      SensorFrame out{};
      ASSERT_TRUE(rx.take(out));
      EXPECT_TRUE(same_bits(out, f)) << "nodes " << int(nodes) << " tick " << tick;
    }
    EXPECT_EQ(rx.counters().rejected_total(), 0u);
    EXPECT_EQ(rx.counters().sets_completed, 40u);
  }
}

TEST(CanCodec, ActuatorFramesCrossBitForBitIncludingNegativeZeroAndDenormals) {
  FrameEncoder enc(Direction::kActuator, kAllNodes);
  SetAssembler rx(Direction::kActuator, kAllNodes);
  std::array<CanFrame, kMaxMessagesPerDirection> frames{};
  for (std::uint64_t tick = 0; tick < 20; ++tick) {
    const ActuatorFrame a = sample_actuator(tick);
    const std::size_t n = enc.encode(a, frames);
    ASSERT_EQ(n, 4u);
    EXPECT_TRUE(frames[n - 1].id == 0x080) << "the header goes last";
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(rx.accept(frames[i]), FrameError::kNone);
    ActuatorFrame out{};
    ASSERT_TRUE(rx.take(out));
    EXPECT_TRUE(same_bits(out, a));
    EXPECT_TRUE(std::signbit(out.gimbal_torque_Nm[0]));
    EXPECT_TRUE(std::signbit(out.cluster_rate_command_rad_s[0]));
  }
}

TEST(CanCodec, NaNPayloadsPassUnchangedAndAreCounted) {
  FrameEncoder enc(Direction::kSensor, kAllNodes);
  SetAssembler rx(Direction::kSensor, kAllNodes);
  random::SeededRng rng(7, 1);
  SensorFrame f = sample_sensor(0, rng);
  f.carrier_angle_rad[0] = std::bit_cast<double>(0x7FF8'0000'DEAD'BEEFull);  // a NaN with a payload
  f.gimbal_rate_rad_s[1] = 5000.0;                                            // beyond the ±1000 rad/s range
  std::array<CanFrame, kMaxMessagesPerDirection> frames{};
  const std::size_t n = enc.encode(f, frames);
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(rx.accept(frames[i]), FrameError::kNone);
  SensorFrame out{};
  ASSERT_TRUE(rx.take(out));
  EXPECT_TRUE(same_bits(out, f)) << "the firmware's fault monitor decides, exactly as in-process";
  EXPECT_EQ(rx.counters().non_finite_values, 1u);
  EXPECT_EQ(rx.counters().out_of_range_values, 1u);
}

TEST(CanCodec, EncoderRefusesAValueOfAnAbsentNode) {
  FrameEncoder enc(Direction::kSensor, kNodeImu | kNodeDrive2);
  SensorFrame f{};
  f.gimbal_angle_rad[msg::kAxis1] = 0.1;  // axis 1 has no drive on this device
  std::array<CanFrame, kMaxMessagesPerDirection> frames{};
  FieldViolation v;
  EXPECT_EQ(enc.encode(f, frames, &v), 0u);
  EXPECT_EQ(v.message, "DRIVE1_FB");
  EXPECT_EQ(v.signal, "gimbal_angle_1");
  f.gimbal_angle_rad[msg::kAxis1] = -0.0;  // a sign bit is a value too: it would not survive the bus
  EXPECT_EQ(enc.encode(f, frames, &v), 0u);
  f.gimbal_angle_rad[msg::kAxis1] = 0.0;
  EXPECT_EQ(enc.encode(f, frames, &v), 3u);
}

// Fixture: one good sensor set of tick k, to corrupt one frame at a time.
class CanBadFrames : public ::testing::Test {
 protected:
  std::size_t make_set(std::uint64_t tick) {
    random::SeededRng rng(tick + 1, 1);
    frame_ = sample_sensor(tick, rng);
    return enc_.encode(frame_, frames_);
  }
  void resign(CanFrame& c) { c.data[kCrcByte] = frame_crc(c.id, c.data, c.len); }
  FrameError feed(const CanFrame& c) { return rx_.accept(c); }

  FrameEncoder enc_{Direction::kSensor, kAllNodes};
  SetAssembler rx_{Direction::kSensor, kAllNodes};
  SensorFrame frame_{};
  std::array<CanFrame, kMaxMessagesPerDirection> frames_{};
};

TEST_F(CanBadFrames, EachCauseIsRejectedAndCountedAndTheSetStillCompletes) {
  ASSERT_EQ(make_set(0), 6u);
  CanFrame bad = frames_[0];  // DRIVE1_FB
  struct Case {
    FrameError want;
    void (*mutate)(CanFrame&);
  };
  const Case cases[] = {
      {FrameError::kErrorFrame, [](CanFrame& c) { c.flags |= kFlagError; }},
      {FrameError::kRemote, [](CanFrame& c) { c.flags |= kFlagRemote; }},
      {FrameError::kExtendedId, [](CanFrame& c) { c.flags |= kFlagExtended; }},
      {FrameError::kUnknownId, [](CanFrame& c) { c.id = 0x555; }},
      {FrameError::kWrongDirection, [](CanFrame& c) { c.id = 0x080; }},
      {FrameError::kNotFd, [](CanFrame& c) { c.flags = 0; c.len = 8; }},
      {FrameError::kWrongLength, [](CanFrame& c) { c.len = 48; }},
      {FrameError::kBadCrc, [](CanFrame& c) { c.data[5] ^= 0x01; }},
  };
  std::uint64_t rejected = 0;
  for (const Case& k : cases) {
    CanFrame c = bad;
    k.mutate(c);
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
  CanFrame imu = frames_[4];
  ASSERT_EQ(imu.id, 0x190u);
  imu.data[60] = 0xAA;  // padding after byte 52
  resign(imu);
  EXPECT_EQ(feed(imu), FrameError::kReservedBits);
  rejected += 2;
  EXPECT_EQ(rx_.counters().rejected_total(), rejected);
  EXPECT_FALSE(rx_.ready());
  // None of that disturbed the good frames of the tick (alive counters untouched by rejected frames).
  for (const CanFrame& c : frames_) ASSERT_EQ(feed(c), FrameError::kNone);
  SensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  EXPECT_TRUE(same_bits(out, frame_));
}

TEST_F(CanBadFrames, AbsentNodeFrameIsRejected) {
  SetAssembler damper(Direction::kSensor, kNodeImu | kNodeDrive2);
  make_set(0);
  EXPECT_EQ(damper.accept(frames_[0]), FrameError::kAbsentNode);  // DRIVE1_FB
}

TEST_F(CanBadFrames, RepeatedCounterIsStaleAndSkippedCounterResynchronises) {
  make_set(0);
  for (const CanFrame& c : frames_) ASSERT_EQ(feed(c), FrameError::kNone);
  SensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  // The same DRIVE1_FB frame again, unchanged (a stuck sender or a replayed buffer): stale.
  EXPECT_EQ(feed(frames_[0]), FrameError::kCounterRepeated);
  make_set(1);
  make_set(2);  // tick 1's frames are lost: tick 2's counters are two ahead
  EXPECT_EQ(feed(frames_[0]), FrameError::kCounterSkipped);
  for (std::size_t i = 1; i < 6; ++i) EXPECT_EQ(feed(frames_[i]), FrameError::kCounterSkipped);
  EXPECT_FALSE(rx_.ready()) << "tick 2's set was rejected frame by frame";
  make_set(3);  // resynchronised: the next frames in sequence are accepted again
  for (const CanFrame& c : frames_) ASSERT_EQ(feed(c), FrameError::kNone);
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 3u);
  EXPECT_EQ(rx_.counters().count(FrameError::kCounterRepeated), 1u);
  EXPECT_EQ(rx_.counters().count(FrameError::kCounterSkipped), 6u);
}

TEST_F(CanBadFrames, HeaderTickMustMatchItsTag) {
  make_set(5);
  CanFrame h = frames_[5];
  ASSERT_EQ(h.id, 0x1A0u);
  h.data[2] ^= 0x01;  // tag says tick 4
  resign(h);
  EXPECT_EQ(feed(h), FrameError::kTickMismatch);
}

TEST_F(CanBadFrames, ANewerTickAbandonsAnIncompleteSet) {
  make_set(0);
  ASSERT_EQ(feed(frames_[0]), FrameError::kNone);
  ASSERT_EQ(feed(frames_[1]), FrameError::kNone);  // tick 0 lacks IMU and the header
  make_set(1);
  for (const CanFrame& c : frames_) ASSERT_EQ(feed(c), FrameError::kNone);
  SensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 1u);
  EXPECT_EQ(rx_.counters().sets_abandoned, 1u);
}

TEST_F(CanBadFrames, FramesOfASkippedTickAreLateButTheLastTakenTickMayRepeat) {
  make_set(0);
  for (const CanFrame& c : frames_) ASSERT_EQ(feed(c), FrameError::kNone);
  SensorFrame out{};
  ASSERT_TRUE(rx_.take(out));
  // A lockstep resend of tick 0 (new alive counters): delivered again, the loop's order check sees a repeat.
  make_set(0);
  for (const CanFrame& c : frames_) ASSERT_EQ(feed(c), FrameError::kNone);
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 0u);
  // The loop gave up on ticks 1 and 2 (stepped them without a set); tick 1's frames arrive afterwards.
  rx_.skip_through(2);
  make_set(1);
  for (const CanFrame& c : frames_) EXPECT_EQ(feed(c), FrameError::kLate);
  EXPECT_FALSE(rx_.ready());
  make_set(3);
  for (const CanFrame& c : frames_) ASSERT_EQ(feed(c), FrameError::kNone);
  ASSERT_TRUE(rx_.take(out));
  EXPECT_EQ(out.tick, 3u);
}

}  // namespace can_codec_test
}  // namespace gyrostab::can
