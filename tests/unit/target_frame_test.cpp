// The target link's frames (firmware/link/target_frame.hpp, cobs.hpp, crc32.hpp): round trips, and every
// refusal cause of the decoder with the alive-counter rules of CAN.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "firmware/link/cobs.hpp"
#include "firmware/link/crc32.hpp"
#include "firmware/link/target_frame.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab {
namespace {
constexpr firmware::link::TargetFrameSizes kUnionSizes{sizeof(msg::SensorFrame), sizeof(msg::ActuatorFrame)};
}  // namespace
namespace target_frame_test {

using firmware::link::TargetFrameDecoder;
using firmware::link::TargetFrameEncoder;
using firmware::link::TargetFrameKind;
using firmware::link::TargetFrameView;
using firmware::link::TargetRxVerdict;

std::vector<std::uint8_t> bytes(std::span<const std::uint8_t> s) { return {s.begin(), s.end()}; }

// The frame's COBS bytes without the closing zero.
std::span<const std::uint8_t> body(const std::vector<std::uint8_t>& wire) {
  return std::span<const std::uint8_t>(wire.data(), wire.size() - 1);
}

msg::SensorFrame sample(std::uint64_t tick) {
  msg::SensorFrame f{};
  f.tick = tick;
  f.sequence = static_cast<std::uint32_t>(tick);
  f.carrier_rate_rad_s[msg::kRoll] = 0.125 * static_cast<double>(tick) - 3.0;
  f.gimbal_angle_rad[msg::kAxis2] = -1e-300;
  return f;
}

TEST(TargetFrame, Crc32CheckValue) {
  const char* text = "123456789";
  EXPECT_EQ(firmware::link::crc32(std::span(reinterpret_cast<const std::uint8_t*>(text), 9)), 0xCBF43926u);
}

TEST(TargetFrame, CobsRoundTripsEveryLengthAndHasNoZero) {
  for (std::size_t n = 0; n < 600; n += (n < 260 ? 1 : 37)) {
    std::vector<std::uint8_t> in(n);
    for (std::size_t i = 0; i < n; ++i) in[i] = static_cast<std::uint8_t>((i * 7) % 5 == 0 ? 0 : i * 13 + 1);
    std::vector<std::uint8_t> enc(firmware::link::cobs_max_encoded(n));
    const std::size_t m = firmware::link::cobs_encode(in, enc);
    ASSERT_GT(m, 0u);
    ASSERT_LE(m, n + n / 254 + 1);
    for (std::size_t i = 0; i < m; ++i) ASSERT_NE(enc[i], 0) << "n=" << n;
    std::vector<std::uint8_t> dec(n + 1);
    const long d = firmware::link::cobs_decode(std::span<const std::uint8_t>(enc.data(), m), dec);
    ASSERT_EQ(d, static_cast<long>(n));
    dec.resize(n);
    EXPECT_EQ(dec, in);
  }
}

TEST(TargetFrame, SensorFrameRoundTripsBitForBit) {
  TargetFrameEncoder enc(0x1234, 0xABCD);
  TargetFrameDecoder dec(/*from_host=*/true, kUnionSizes);
  for (std::uint64_t k = 0; k < 40; ++k) {  // the alive counter wraps twice
    const msg::SensorFrame f = sample(k);
    const auto wire = bytes(enc.encode(TargetFrameKind::kSensor, f));
    ASSERT_EQ(wire.back(), 0);
    std::span<const std::uint8_t> frame;
    bool complete = false;
    for (const std::uint8_t b : wire) complete = dec.collect(b, frame) || complete;
    ASSERT_TRUE(complete);
    TargetFrameView v;
    ASSERT_EQ(dec.judge(frame, v), TargetRxVerdict::kOk) << k;
    EXPECT_EQ(v.kind, TargetFrameKind::kSensor);
    EXPECT_EQ(v.sender, 0x1234u);
    EXPECT_EQ(v.session, 0xABCDu);
    EXPECT_EQ(v.freshness, k + 1);
    ASSERT_EQ(v.payload.size(), sizeof f);
    EXPECT_EQ(std::memcmp(v.payload.data(), &f, sizeof f), 0);
  }
  EXPECT_EQ(dec.counters().accepted, 40u);
  EXPECT_EQ(dec.counters().refused(), 0u);
}

TEST(TargetFrame, EveryRefusalCauseIsCounted) {
  TargetFrameEncoder enc(7, 9);
  TargetFrameDecoder dec(/*from_host=*/true, kUnionSizes);
  TargetFrameView v;
  const auto first = bytes(enc.encode(TargetFrameKind::kSensor, sample(0)));
  ASSERT_EQ(dec.judge(body(first), v), TargetRxVerdict::kOk);
  // The same bytes again: the alive counter did not advance.
  EXPECT_EQ(dec.judge(body(first), v), TargetRxVerdict::kRepeated);
  // One counter value never sent: skipped; the next in sequence is accepted again.
  (void)enc.encode(TargetFrameKind::kSensor, sample(1));
  EXPECT_EQ(dec.judge(body(bytes(enc.encode(TargetFrameKind::kSensor, sample(2)))), v), TargetRxVerdict::kSkipped);
  EXPECT_EQ(dec.judge(body(bytes(enc.encode(TargetFrameKind::kSensor, sample(3)))), v), TargetRxVerdict::kOk);
  // A changed byte: CRC (or framing when it hits a COBS length byte).
  auto bad = bytes(enc.encode(TargetFrameKind::kSensor, sample(4)));
  bad[60] = static_cast<std::uint8_t>(bad[60] == 0xFF ? 0xFE : bad[60] + 1);
  const TargetRxVerdict r = dec.judge(body(bad), v);
  EXPECT_TRUE(r == TargetRxVerdict::kCrc || r == TargetRxVerdict::kFraming) << describe(r);
  // A kind the host does not send.
  EXPECT_EQ(dec.judge(body(bytes(enc.encode(TargetFrameKind::kActuator, msg::ActuatorFrame{}))), v),
            TargetRxVerdict::kKind);
  // The wrong payload length for the kind.
  EXPECT_EQ(dec.judge(body(bytes(enc.encode(TargetFrameKind::kSensor, msg::ActuatorFrame{}))), v),
            TargetRxVerdict::kLength);
  // Too short to hold a header.
  const std::uint8_t tiny[] = {3, 1, 2};
  EXPECT_EQ(dec.judge(tiny, v), TargetRxVerdict::kLength);
  // A zero inside, or a block past the end: not COBS.
  const std::uint8_t broken[] = {5, 1, 2};
  EXPECT_EQ(dec.judge(broken, v), TargetRxVerdict::kFraming);
  // Bound to session 9 and sender 7: another session's frame is foreign.
  dec.bind(9, 7);
  TargetFrameEncoder other(7, 10);
  EXPECT_EQ(dec.judge(body(bytes(other.encode(TargetFrameKind::kSensor, sample(5)))), v), TargetRxVerdict::kForeign);
  const auto& c = dec.counters();
  EXPECT_EQ(c.accepted, 2u);
  EXPECT_EQ(c.repeated, 1u);
  EXPECT_EQ(c.skipped, 1u);
  EXPECT_EQ(c.crc + c.framing, 2u);
  EXPECT_EQ(c.kind, 1u);
  EXPECT_EQ(c.length, 2u);
  EXPECT_EQ(c.foreign, 1u);
}

TEST(TargetFrame, ReservedBitsAreRefused) {
  TargetFrameEncoder enc(7, 9);
  TargetFrameDecoder dec(/*from_host=*/true, kUnionSizes);
  // Rebuild a frame with a high nibble in the alive byte and a valid CRC.
  std::vector<std::uint8_t> raw(firmware::link::kTargetHeaderBytes + firmware::link::kTargetCrcBytes);
  raw[0] = static_cast<std::uint8_t>(TargetFrameKind::kStop);
  raw[1] = 0x10;
  firmware::link::put_u32(&raw[2], 7);
  firmware::link::put_u32(&raw[6], 9);
  const std::size_t n = raw.size() - 4;
  firmware::link::put_u32(&raw[n], firmware::link::crc32(std::span<const std::uint8_t>(raw.data(), n)));
  std::vector<std::uint8_t> wire(firmware::link::cobs_max_encoded(raw.size()));
  wire.resize(firmware::link::cobs_encode(raw, wire));
  TargetFrameView v;
  EXPECT_EQ(dec.judge(wire, v), TargetRxVerdict::kReservedBits);
}

TEST(TargetFrame, OverlongFrameIsDroppedUpToItsZero) {
  TargetFrameDecoder dec(/*from_host=*/true, kUnionSizes);
  std::span<const std::uint8_t> frame;
  for (std::size_t i = 0; i < firmware::link::kMaxTargetWire + 10; ++i) ASSERT_FALSE(dec.collect(0x41, frame));
  EXPECT_FALSE(dec.collect(0, frame));
  EXPECT_EQ(dec.counters().framing, 1u);
  EXPECT_GT(dec.counters().overflow, 0u);
  // The stream resynchronises: the next frame decodes.
  TargetFrameEncoder enc(7, 9);
  bool complete = false;
  for (const std::uint8_t b : enc.encode(TargetFrameKind::kStop, nullptr, 0)) complete = dec.collect(b, frame) || complete;
  ASSERT_TRUE(complete);
  TargetFrameView v;
  EXPECT_EQ(dec.judge(frame, v), TargetRxVerdict::kOk);
}

}  // namespace target_frame_test
}  // namespace gyrostab
