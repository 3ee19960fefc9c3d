// The LCM frame codec (hil/lcm/frame_codec.hpp) on every device's signal table: the bytes are lcm-gen's own
// encoding of the generated types (fingerprint, size, every field), round trips are bit-exact (NaN payloads,
// signed zeros, wrapped unsigned header fields), every size but the right one and any other fingerprint are
// refused with the frame untouched, and encode/decode do not allocate (the loops call them every tick).
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "gyrostab_signals/all_devices.hpp"
#include "gyrostab_signals/all_lcm_types.hpp"
#include "hil/lcm/frame_codec.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gyrostab::hil {
namespace lcm_codec_test {

// A quiet NaN with a payload (and the sign bit set) and a signalling NaN: a codec that went through a float
// conversion or an arithmetic copy would canonicalise them.
const double kPayloadNaN = std::bit_cast<double>(std::uint64_t{0xFFF8'0000'DEAD'BEEFull});
const double kSignallingNaN = std::bit_cast<double>(std::uint64_t{0x7FF0'0000'0000'0001ull});
const double kAwkward[] = {kPayloadNaN,
                           -0.0,
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::max(),
                           kSignallingNaN,
                           1.0 / 3.0,
                           -1e-300};

msg::AnySensorFrame filled_sensor(const msg::DeviceSignals& d) {
  msg::AnySensorFrame f{};
  f.tick = 0xFEDC'BA98'7654'3210ull;  // top bit set: travels as a negative int64
  f.time_ns = -123'456'789'012'345;
  f.sample_time_ns = 987'654'321;
  f.sequence = 0xFFFF'FFFEu;  // top bit set: travels as a negative int32
  f.status = 0x8000'0005u;
  for (std::size_t i = 0; i < d.sensors.size(); ++i) f.signal[i] = kAwkward[i % std::size(kAwkward)];
  return f;
}

msg::AnyActuatorFrame filled_actuator(const msg::DeviceSignals& d) {
  msg::AnyActuatorFrame a{};
  a.tick = 0x8000'0000'0000'0001ull;
  a.time_ns = 42;
  a.sensor_tick = ~std::uint64_t{0};
  a.sequence = 0x8000'0000u;
  a.status = 0xFFFF'FFFFu;
  for (std::size_t i = 0; i < d.commands.size(); ++i) a.signal[i] = kAwkward[(i + 3) % std::size(kAwkward)];
  return a;
}

template <class T>
bool same_bytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

std::uint64_t fingerprint_of(const std::uint8_t* p) {
  std::uint64_t fp = 0;
  for (int i = 0; i < 8; ++i) fp = (fp << 8) | p[i];
  return fp;
}

// lcm-gen's class decodes our bytes and encodes them again: the same bytes, so every field sits where
// lcm-gen puts it (lcm-spy, lcm-logplayer and the other languages' bindings read what we write).
template <class Generated>
void expect_generated_encoding(const std::vector<std::uint8_t>& ours, const std::string& what) {
  Generated g{};
  ASSERT_EQ(g.decode(ours.data(), 0, static_cast<int>(ours.size())), static_cast<int>(ours.size())) << what;
  std::vector<std::uint8_t> theirs(ours.size());
  ASSERT_EQ(g.encode(theirs.data(), 0, static_cast<int>(theirs.size())), static_cast<int>(theirs.size())) << what;
  EXPECT_EQ(ours, theirs) << what;
  EXPECT_EQ(fingerprint_of(ours.data()), static_cast<std::uint64_t>(Generated::getHash())) << what;
}

TEST(LcmCodec, EveryDeviceMatchesLcmGensTypesByteForByte) {
  int devices = 0;
  msg::for_each_lcm_type([&]<class S, class A>(const msg::DeviceSignals& d, msg::LcmTypes<S, A>) {
    const std::string name(d.device);
    ++devices;
    EXPECT_EQ(sensor_encoded_size(d), S{}.getEncodedSize()) << name;
    EXPECT_EQ(actuator_encoded_size(d), A{}.getEncodedSize()) << name;
    EXPECT_EQ(d.lcm_sensor_fingerprint, static_cast<std::uint64_t>(S::getHash())) << name;
    EXPECT_EQ(d.lcm_actuator_fingerprint, static_cast<std::uint64_t>(A::getHash())) << name;
    EXPECT_LT(sensor_encoded_size(d), 1400) << name << ": one UDP datagram, never fragmented";

    const LinkEnvelope env{0x11223344, 0x55667788, 0x8000'0000'0000'0001ull, 0xFEDC'BA98'7654'3210ull};
    std::vector<std::uint8_t> s(static_cast<std::size_t>(sensor_encoded_size(d)));
    ASSERT_EQ(encode(filled_sensor(d), d, -77, s.data(), static_cast<int>(s.size()), env),
              static_cast<int>(s.size()));
    expect_generated_encoding<S>(s, name + " sensor");
    std::vector<std::uint8_t> a(static_cast<std::size_t>(actuator_encoded_size(d)));
    ASSERT_EQ(encode(filled_actuator(d), d, 5, a.data(), static_cast<int>(a.size()), env),
              static_cast<int>(a.size()));
    expect_generated_encoding<A>(a, name + " actuator");

    // The endpoint writes the envelope into an encoded frame: the same bytes as encoding it with it.
    std::vector<std::uint8_t> later(a.size());
    ASSERT_EQ(encode(filled_actuator(d), d, 5, later.data(), static_cast<int>(later.size())),
              static_cast<int>(later.size()));
    write_envelope(later.data(), static_cast<int>(later.size()), env);
    EXPECT_EQ(later, a) << name;
    LinkEnvelope back{};
    msg::AnyActuatorFrame decoded{};
    ASSERT_EQ(decode(later.data(), static_cast<int>(later.size()), d, decoded, nullptr, &back), DecodeError::kOk);
    EXPECT_EQ(back.sender, env.sender);
    EXPECT_EQ(back.session, env.session);
    EXPECT_EQ(back.freshness, env.freshness);
    EXPECT_EQ(back.mac, env.mac);
  });
  EXPECT_GE(devices, 1);
}

TEST(LcmCodec, FramesRoundTripBitExact) {
  for (const msg::DeviceSignals* d : msg::kAllDeviceSignals) {
    const msg::AnySensorFrame in = filled_sensor(*d);
    std::array<std::uint8_t, kMaxEncodedSize> buf{};
    const int n = encode(in, *d, -77, buf.data(), kMaxEncodedSize);
    ASSERT_EQ(n, sensor_encoded_size(*d));
    msg::AnySensorFrame out{};
    std::int64_t sim_us = 0;
    ASSERT_EQ(decode(buf.data(), n, *d, out, &sim_us), DecodeError::kOk);
    EXPECT_TRUE(same_bytes(in, out)) << d->device;
    EXPECT_EQ(sim_us, -77);

    const msg::AnyActuatorFrame ain = filled_actuator(*d);
    const int m = encode(ain, *d, 1'000'000, buf.data(), kMaxEncodedSize);
    ASSERT_EQ(m, actuator_encoded_size(*d));
    msg::AnyActuatorFrame aout{};
    ASSERT_EQ(decode(buf.data(), m, *d, aout, &sim_us), DecodeError::kOk);
    EXPECT_TRUE(same_bytes(ain, aout)) << d->device;
    EXPECT_EQ(sim_us, 1'000'000);
  }
}

TEST(LcmCodec, EncodeRefusesAShortBuffer) {
  for (const msg::DeviceSignals* d : msg::kAllDeviceSignals) {
    std::array<std::uint8_t, kMaxEncodedSize> buf{};
    for (int cap = 0; cap < sensor_encoded_size(*d); ++cap) {
      EXPECT_EQ(encode(filled_sensor(*d), *d, 0, buf.data(), cap), -1) << cap;
    }
    for (int cap = 0; cap < actuator_encoded_size(*d); ++cap) {
      EXPECT_EQ(encode(filled_actuator(*d), *d, 0, buf.data(), cap), -1) << cap;
    }
    EXPECT_EQ(encode(filled_sensor(*d), *d, 0, nullptr, kMaxEncodedSize), -1);
  }
}

TEST(LcmCodec, EverySizeButTheEncodedSizeIsRefusedAndLeavesTheFrameUntouched) {
  const msg::DeviceSignals& d = *msg::kAllDeviceSignals[0];
  std::vector<std::uint8_t> buf(512, 0);
  const int n = encode(filled_sensor(d), d, 9, buf.data(), static_cast<int>(buf.size()));
  ASSERT_EQ(n, sensor_encoded_size(d));
  msg::AnySensorFrame sentinel{};
  sentinel.tick = 99;
  sentinel.signal[0] = 1.5;
  for (int size = -1; size <= static_cast<int>(buf.size()); ++size) {
    if (size == n) continue;
    msg::AnySensorFrame out = sentinel;
    std::int64_t sim_us = -5;
    EXPECT_EQ(decode(buf.data(), size, d, out, &sim_us), DecodeError::kWrongSize) << size;
    EXPECT_TRUE(same_bytes(out, sentinel)) << size;
    EXPECT_EQ(sim_us, -5);
  }
  const int m = encode(filled_actuator(d), d, 9, buf.data(), static_cast<int>(buf.size()));
  for (int size = -1; size <= static_cast<int>(buf.size()); ++size) {
    if (size == m) continue;
    msg::AnyActuatorFrame out{};
    out.tick = 7;
    EXPECT_EQ(decode(buf.data(), size, d, out), DecodeError::kWrongSize) << size;
    EXPECT_EQ(out.tick, 7u);
  }
  msg::AnySensorFrame s{};
  EXPECT_EQ(decode(nullptr, n, d, s), DecodeError::kWrongSize);
}

TEST(LcmCodec, AnotherTypeOrAFlippedFingerprintBitIsRefused) {
  const msg::DeviceSignals& d = *msg::kAllDeviceSignals[0];
  std::array<std::uint8_t, kMaxEncodedSize> buf{};
  const int n = encode(filled_sensor(d), d, 0, buf.data(), kMaxEncodedSize);
  for (int bit = 0; bit < 64; ++bit) {
    std::array<std::uint8_t, kMaxEncodedSize> bad = buf;
    bad[static_cast<std::size_t>(bit / 8)] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    msg::AnySensorFrame out{};
    out.tick = 3;
    EXPECT_EQ(decode(bad.data(), n, d, out), DecodeError::kWrongFingerprint) << bit;
    EXPECT_EQ(out.tick, 3u);
  }
  // A frame of one device is never taken for another's: where two sizes agree the fingerprints differ.
  for (const msg::DeviceSignals* a : msg::kAllDeviceSignals) {
    for (const msg::DeviceSignals* b : msg::kAllDeviceSignals) {
      if (a == b) continue;
      const int k = encode(filled_sensor(*a), *a, 0, buf.data(), kMaxEncodedSize);
      msg::AnySensorFrame out{};
      EXPECT_NE(decode(buf.data(), k, *b, out), DecodeError::kOk) << a->device << " as " << b->device;
    }
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
  const msg::DeviceSignals& d = *msg::kAllDeviceSignals[0];
  std::array<std::uint8_t, kMaxEncodedSize> sbuf{};
  std::array<std::uint8_t, kMaxEncodedSize> abuf{};
  msg::AnySensorFrame s = filled_sensor(d);
  msg::AnyActuatorFrame a = filled_actuator(d);
  const int ns = sensor_encoded_size(d), na = actuator_encoded_size(d);
  const testing::AllocationCounter c;
  int ok = 0;
  for (int i = 0; i < 1000; ++i) {
    s.tick = static_cast<std::uint64_t>(i);
    a.tick = static_cast<std::uint64_t>(i);
    ok += encode(s, d, i, sbuf.data(), kMaxEncodedSize) == ns;
    ok += encode(a, d, i, abuf.data(), kMaxEncodedSize) == na;
    ok += decode(sbuf.data(), ns, d, s) == DecodeError::kOk;
    ok += decode(abuf.data(), na, d, a) == DecodeError::kOk;
    ok += decode(sbuf.data(), ns - 1, d, s) == DecodeError::kWrongSize;
  }
  EXPECT_EQ(c.count(), 0u);
  EXPECT_EQ(ok, 5000);
}

}  // namespace lcm_codec_test
}  // namespace gyrostab::hil
