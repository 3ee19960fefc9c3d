// The LCM frame codec (hil/lcm/frame_codec.hpp): bit-exact round trips (NaN payloads, signed zeros, wrapped
// unsigned fields), every size but the right one refused, a foreign fingerprint refused, and encode/decode
// allocation-free (the lockstep and real-time loops call them every tick).
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "gyrostab_msg/actuator_frame_t.hpp"
#include "gyrostab_msg/sensor_frame_t.hpp"
#include "hil/lcm/frame_codec.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gyrostab::hil {
namespace lcm_codec_test {

// A quiet NaN with a payload (and the sign bit set) and a signalling NaN: a codec that went through a float
// conversion or an arithmetic copy would canonicalise them.
const double kPayloadNaN = std::bit_cast<double>(std::uint64_t{0xFFF8'0000'DEAD'BEEFull});
const double kSignallingNaN = std::bit_cast<double>(std::uint64_t{0x7FF0'0000'0000'0001ull});

msg::SensorFrame filled_sensor() {
  msg::SensorFrame f{};
  f.tick = 0xFEDC'BA98'7654'3210ull;  // top bit set: travels as a negative int64
  f.time_ns = -123'456'789'012'345;
  f.sample_time_ns = 987'654'321;
  f.sequence = 0xFFFF'FFFEu;  // top bit set: travels as a negative int32
  f.status = 0x8000'0005u;
  f.carrier_angle_rad[0] = kPayloadNaN;
  f.carrier_angle_rad[1] = -0.0;
  f.carrier_angle_rad[2] = std::numeric_limits<double>::denorm_min();
  f.carrier_rate_rad_s[0] = std::numeric_limits<double>::infinity();
  f.carrier_rate_rad_s[1] = -std::numeric_limits<double>::max();
  f.carrier_rate_rad_s[2] = kSignallingNaN;
  f.gimbal_angle_rad[0] = 0.1;
  f.gimbal_angle_rad[1] = -0.2;
  f.gimbal_rate_rad_s[0] = 1.0 / 3.0;
  f.gimbal_rate_rad_s[1] = -1e-300;
  f.motor_current_A[0] = 12.5;
  f.motor_current_A[1] = -7.25;
  f.rotor_speed_rad_s = 3141.592653589793;
  f.encoder_count[0] = std::numeric_limits<std::int32_t>::min();
  f.encoder_count[1] = 123456;
  return f;
}

msg::ActuatorFrame filled_actuator() {
  msg::ActuatorFrame a{};
  a.tick = 0x8000'0000'0000'0001ull;
  a.time_ns = 42;
  a.sensor_tick = ~std::uint64_t{0};
  a.sequence = 0x8000'0000u;
  a.status = 0xFFFF'FFFFu;
  a.gimbal_torque_Nm[0] = kPayloadNaN;
  a.gimbal_torque_Nm[1] = -0.0;
  a.motor_voltage_V[0] = 24.0;
  a.motor_voltage_V[1] = kSignallingNaN;
  a.precession_brake = 0.75;
  return a;
}

template <class T>
bool same_bytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

TEST(LcmCodec, EncodedSizesMatchTheGeneratedTypesAndFitOneDatagram) {
  EXPECT_EQ(kSensorEncodedSize, gyrostab_msg::sensor_frame_t{}.getEncodedSize());
  EXPECT_EQ(kActuatorEncodedSize, gyrostab_msg::actuator_frame_t{}.getEncodedSize());
  EXPECT_EQ(kSensorEncodedSize, 256);
  EXPECT_EQ(kActuatorEncodedSize, 152);
  // LCM fragments messages whose channel name + payload exceed one ~1400-byte datagram.
  EXPECT_LT(kSensorEncodedSize, 1400);
  EXPECT_LT(kActuatorEncodedSize, 1400);
}

TEST(LcmCodec, SensorFrameRoundTripsBitExact) {
  const msg::SensorFrame in = filled_sensor();
  std::array<std::uint8_t, 256> buf{};
  ASSERT_EQ(encode(in, -77, buf.data(), static_cast<int>(buf.size())), kSensorEncodedSize);
  msg::SensorFrame out{};
  std::int64_t sim_us = 0;
  ASSERT_EQ(decode(buf.data(), kSensorEncodedSize, out, &sim_us), DecodeError::kOk);
  EXPECT_TRUE(same_bytes(in, out));
  EXPECT_EQ(sim_us, -77);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(out.carrier_angle_rad[0]), 0xFFF8'0000'DEAD'BEEFull);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(out.carrier_rate_rad_s[2]), 0x7FF0'0000'0000'0001ull);
  EXPECT_TRUE(std::signbit(out.carrier_angle_rad[1]));
}

TEST(LcmCodec, ActuatorFrameRoundTripsBitExact) {
  const msg::ActuatorFrame in = filled_actuator();
  std::array<std::uint8_t, kActuatorEncodedSize> buf{};
  ASSERT_EQ(encode(in, 1'000'000, buf.data(), kActuatorEncodedSize), kActuatorEncodedSize);
  msg::ActuatorFrame out{};
  std::int64_t sim_us = 0;
  ASSERT_EQ(decode(buf.data(), kActuatorEncodedSize, out, &sim_us), DecodeError::kOk);
  EXPECT_TRUE(same_bytes(in, out));
  EXPECT_EQ(sim_us, 1'000'000);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(out.gimbal_torque_Nm[0]), 0xFFF8'0000'DEAD'BEEFull);
}

TEST(LcmCodec, WireBytesAreTheGeneratedEncoding) {
  // The codec must produce what lcm-gen's own encode() produces (lcm-spy, lcm-logplayer, other languages).
  const msg::ActuatorFrame a = filled_actuator();
  std::array<std::uint8_t, kActuatorEncodedSize> ours{};
  const LinkEnvelope env{0x11223344, 0x55667788, 0x8000'0000'0000'0001ull, 0xFEDC'BA98'7654'3210ull};
  ASSERT_EQ(encode(a, 5, ours.data(), kActuatorEncodedSize, env), kActuatorEncodedSize);
  gyrostab_msg::actuator_frame_t w{};
  w.sender = static_cast<std::int64_t>(env.sender);
  w.session = static_cast<std::int64_t>(env.session);
  w.freshness = static_cast<std::int64_t>(env.freshness);
  w.mac = static_cast<std::int64_t>(env.mac);
  w.tick = static_cast<std::int64_t>(a.tick);
  w.time_ns = a.time_ns;
  w.sensor_tick = static_cast<std::int64_t>(a.sensor_tick);
  w.sequence = static_cast<std::int32_t>(a.sequence);
  w.status = static_cast<std::int32_t>(a.status);
  std::memcpy(w.gimbal_torque_Nm, a.gimbal_torque_Nm, sizeof(w.gimbal_torque_Nm));
  std::memcpy(w.motor_voltage_V, a.motor_voltage_V, sizeof(w.motor_voltage_V));
  w.precession_brake = a.precession_brake;
  w.sim_time_us = 5;
  std::array<std::uint8_t, kActuatorEncodedSize> theirs{};
  ASSERT_EQ(w.encode(theirs.data(), 0, kActuatorEncodedSize), kActuatorEncodedSize);
  EXPECT_EQ(ours, theirs);
  // The endpoint writes the envelope into an encoded frame: the same bytes as encoding it.
  std::array<std::uint8_t, kActuatorEncodedSize> later{};
  ASSERT_EQ(encode(a, 5, later.data(), kActuatorEncodedSize), kActuatorEncodedSize);
  write_envelope(later.data(), kActuatorEncodedSize, env);
  EXPECT_EQ(later, theirs);
  LinkEnvelope back{};
  msg::ActuatorFrame decoded{};
  ASSERT_EQ(decode(later.data(), kActuatorEncodedSize, decoded, nullptr, &back), DecodeError::kOk);
  EXPECT_EQ(back.sender, env.sender);
  EXPECT_EQ(back.session, env.session);
  EXPECT_EQ(back.freshness, env.freshness);
  EXPECT_EQ(back.mac, env.mac);
  // Big-endian fingerprint first.
  std::uint64_t fp = 0;
  for (int i = 0; i < 8; ++i) fp = (fp << 8) | ours[static_cast<std::size_t>(i)];
  EXPECT_EQ(fp, static_cast<std::uint64_t>(gyrostab_msg::actuator_frame_t::getHash()));
}

TEST(LcmCodec, EncodeRefusesAShortBuffer) {
  std::array<std::uint8_t, 256> buf{};
  for (int cap = 0; cap < kSensorEncodedSize; ++cap) {
    EXPECT_EQ(encode(filled_sensor(), 0, buf.data(), cap), -1) << cap;
  }
  for (int cap = 0; cap < kActuatorEncodedSize; ++cap) {
    EXPECT_EQ(encode(filled_actuator(), 0, buf.data(), cap), -1) << cap;
  }
  EXPECT_EQ(encode(filled_sensor(), 0, nullptr, 256), -1);
}

TEST(LcmCodec, EverySizeButTheEncodedSizeIsRefusedAndLeavesTheFrameUntouched) {
  std::vector<std::uint8_t> buf(512, 0);
  ASSERT_EQ(encode(filled_sensor(), 9, buf.data(), static_cast<int>(buf.size())), kSensorEncodedSize);
  const msg::SensorFrame sentinel = [] {
    msg::SensorFrame s{};
    s.tick = 99;
    s.rotor_speed_rad_s = 1.5;
    return s;
  }();
  for (int size = -1; size <= static_cast<int>(buf.size()); ++size) {
    if (size == kSensorEncodedSize) continue;
    msg::SensorFrame out = sentinel;
    std::int64_t sim_us = -5;
    EXPECT_EQ(decode(buf.data(), size, out, &sim_us), DecodeError::kWrongSize) << size;
    EXPECT_TRUE(same_bytes(out, sentinel)) << size;
    EXPECT_EQ(sim_us, -5);
  }
  ASSERT_EQ(encode(filled_actuator(), 9, buf.data(), static_cast<int>(buf.size())), kActuatorEncodedSize);
  for (int size = -1; size <= static_cast<int>(buf.size()); ++size) {
    if (size == kActuatorEncodedSize) continue;
    msg::ActuatorFrame out{};
    out.tick = 7;
    EXPECT_EQ(decode(buf.data(), size, out), DecodeError::kWrongSize) << size;
    EXPECT_EQ(out.tick, 7u);
  }
  msg::SensorFrame s{};
  EXPECT_EQ(decode(nullptr, kSensorEncodedSize, s), DecodeError::kWrongSize);
}

TEST(LcmCodec, AnotherTypeOrAFlippedFingerprintBitIsRefused) {
  // A sensor frame's bytes cut to the actuator size still carry the sensor fingerprint.
  std::array<std::uint8_t, kSensorEncodedSize> buf{};
  ASSERT_EQ(encode(filled_sensor(), 0, buf.data(), kSensorEncodedSize), kSensorEncodedSize);
  msg::ActuatorFrame a{};
  EXPECT_EQ(decode(buf.data(), kActuatorEncodedSize, a), DecodeError::kWrongFingerprint);
  for (int bit = 0; bit < 64; ++bit) {
    std::array<std::uint8_t, kSensorEncodedSize> bad = buf;
    bad[static_cast<std::size_t>(bit / 8)] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    msg::SensorFrame out{};
    out.tick = 3;
    EXPECT_EQ(decode(bad.data(), kSensorEncodedSize, out), DecodeError::kWrongFingerprint) << bit;
    EXPECT_EQ(out.tick, 3u);
  }
}

TEST(LcmCodec, DescribeNamesEveryError) {
  for (const DecodeError e :
       {DecodeError::kOk, DecodeError::kWrongSize, DecodeError::kWrongFingerprint, DecodeError::kMalformed}) {
    EXPECT_NE(std::string(describe(e)), "unknown decode error");
  }
  EXPECT_STREQ(describe(DecodeError::kWrongFingerprint), "wrong fingerprint");
}

TEST(LcmCodec, EncodeAndDecodeDoNotAllocate) {
  std::array<std::uint8_t, kSensorEncodedSize> sbuf{};
  std::array<std::uint8_t, kActuatorEncodedSize> abuf{};
  msg::SensorFrame s = filled_sensor();
  msg::ActuatorFrame a = filled_actuator();
  // The generated getHash() initialises a function-local static on first use: do that outside the count.
  ASSERT_EQ(encode(s, 0, sbuf.data(), kSensorEncodedSize), kSensorEncodedSize);
  ASSERT_EQ(encode(a, 0, abuf.data(), kActuatorEncodedSize), kActuatorEncodedSize);
  const testing::AllocationCounter c;
  int ok = 0;
  for (int i = 0; i < 1000; ++i) {
    s.tick = static_cast<std::uint64_t>(i);
    a.tick = static_cast<std::uint64_t>(i);
    ok += encode(s, i, sbuf.data(), kSensorEncodedSize) == kSensorEncodedSize;
    ok += encode(a, i, abuf.data(), kActuatorEncodedSize) == kActuatorEncodedSize;
    ok += decode(sbuf.data(), kSensorEncodedSize, s) == DecodeError::kOk;
    ok += decode(abuf.data(), kActuatorEncodedSize, a) == DecodeError::kOk;
    ok += decode(sbuf.data(), kSensorEncodedSize - 1, s) == DecodeError::kWrongSize;
    ok += decode(abuf.data(), kActuatorEncodedSize, s) == DecodeError::kWrongSize;
  }
  EXPECT_EQ(c.count(), 0u);
  EXPECT_EQ(ok, 6000);
}

}  // namespace lcm_codec_test
}  // namespace gyrostab::hil
