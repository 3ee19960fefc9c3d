// The CAN frame map (hil/can/frame_map.hpp) is a faithful carrier of the interface contract: every byte of
// SensorFrame and ActuatorFrame is carried by exactly one signal of its direction, signals never overlap,
// fit their frame, use valid CAN FD lengths and unique identifiers, and each direction's header comes last.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>

#include "hil/can/can_frame.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/frame_map.hpp"

namespace gyrostab::can {
namespace can_frame_map_test {

TEST(CanFrameMap, IdentifiersAreUniqueStandardIds) {
  std::set<std::uint32_t> ids;
  for (const MessageSpec& m : kMessages) {
    EXPECT_LE(m.id, 0x7FFu) << m.name;
    EXPECT_TRUE(ids.insert(m.id).second) << m.name << " reuses id " << m.id;
  }
}

TEST(CanFrameMap, LengthsAreCanFdLengthsWithoutSlack) {
  for (const MessageSpec& m : kMessages) {
    EXPECT_TRUE(fd_length_valid(m.length)) << m.name;
    // The smallest FD length that holds the signals: no frame is longer than it must be (bus load).
    EXPECT_EQ(m.length, fd_round_up(used_bytes(m))) << m.name;
  }
}

TEST(CanFrameMap, EveryMessageStartsWithTheEnvelope) {
  for (const MessageSpec& m : kMessages) {
    ASSERT_GE(m.signals.size(), 3u) << m.name;
    EXPECT_EQ(m.signals[0].name, "crc");
    EXPECT_EQ(m.signals[0].start_bit, 8 * kCrcByte);
    EXPECT_EQ(m.signals[0].bit_length, 8);
    EXPECT_EQ(m.signals[1].name, "alive");
    EXPECT_EQ(m.signals[1].start_bit, 8 * kAliveByte);
    EXPECT_EQ(m.signals[1].bit_length, 4);
    EXPECT_EQ(m.signals[2].name, "tick_tag");
    EXPECT_EQ(m.signals[2].start_bit, 8 * kTickTagByte);
    EXPECT_EQ(m.signals[2].bit_length, 16);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(m.signals[i].field_offset, kEnvelope);
  }
}

TEST(CanFrameMap, SignalsFitTheirFrameAndNeverOverlap) {
  for (const MessageSpec& m : kMessages) {
    std::array<bool, 8 * kFdMaxData> used{};
    std::set<std::string_view> names;
    for (const SignalSpec& s : m.signals) {
      EXPECT_TRUE(names.insert(s.name).second) << m.name << "." << s.name << " twice";
      ASSERT_LE(s.start_bit + s.bit_length, 8 * m.length) << m.name << "." << s.name;
      for (int b = s.start_bit; b < s.start_bit + s.bit_length; ++b) {
        EXPECT_FALSE(used[static_cast<std::size_t>(b)]) << m.name << "." << s.name << " overlaps at bit " << b;
        used[static_cast<std::size_t>(b)] = true;
      }
      if (s.field_offset >= 0) {
        // Contract signals are whole bytes at byte positions (the codec copies them bytewise, bit for bit).
        EXPECT_EQ(s.start_bit % 8, 0) << m.name << "." << s.name;
        EXPECT_EQ(s.bit_length % 8, 0) << m.name << "." << s.name;
        EXPECT_EQ(s.factor, 1.0) << m.name << "." << s.name;
        EXPECT_EQ(s.offset, 0.0) << m.name << "." << s.name;
        EXPECT_EQ(s.kind == SignalKind::kDouble, s.bit_length == 64 && s.kind == SignalKind::kDouble);
      }
      EXPECT_LT(s.min, s.max) << m.name << "." << s.name;
    }
  }
}

// Each byte of a contract struct is carried by exactly one signal of that struct's direction, and the
// signal's type matches the field's size.
void expect_contract_covered_once(Direction d, std::size_t size) {
  std::vector<int> cover(size, 0);
  for (const MessageSpec& m : kMessages) {
    if (m.direction != d) continue;
    for (const SignalSpec& s : m.signals) {
      if (s.field_offset < 0) continue;
      ASSERT_LE(static_cast<std::size_t>(s.field_offset) + s.bit_length / 8u, size) << m.name << "." << s.name;
      for (int i = 0; i < s.bit_length / 8; ++i) ++cover[static_cast<std::size_t>(s.field_offset + i)];
    }
  }
  for (std::size_t i = 0; i < size; ++i) EXPECT_EQ(cover[i], 1) << "contract byte " << i;
}

TEST(CanFrameMap, SensorFrameIsCoveredExactlyOnce) {
  expect_contract_covered_once(Direction::kSensor, sizeof(msg::SensorFrame));
}

TEST(CanFrameMap, ActuatorFrameIsCoveredExactlyOnce) {
  expect_contract_covered_once(Direction::kActuator, sizeof(msg::ActuatorFrame));
}

TEST(CanFrameMap, EachDirectionHasOneHeaderCarryingTheTickAndItComesLast) {
  for (Direction d : {Direction::kSensor, Direction::kActuator}) {
    int headers = 0;
    int last_index = -1, header_index = -1;
    for (std::size_t i = 0; i < kMessageCount; ++i) {
      if (kMessages[i].direction != d) continue;
      last_index = static_cast<int>(i);
      if (kMessages[i].header) {
        ++headers;
        header_index = static_cast<int>(i);
        EXPECT_EQ(kMessages[i].requires_node, 0) << "the header is always on the bus";
        bool has_tick = false;
        for (const SignalSpec& s : kMessages[i].signals) has_tick |= s.field_offset == 0 && s.bit_length == 64;
        EXPECT_TRUE(has_tick) << kMessages[i].name;
      }
    }
    EXPECT_EQ(headers, 1);
    EXPECT_EQ(header_index, last_index);
  }
}

TEST(CanFrameMap, SensorRangesAreTheFirmwareDefaults) {
  const firmware::SensorRanges r{};
  const int i = message_index(0x182);
  ASSERT_GE(i, 0);
  const MessageSpec& m = kMessages[static_cast<std::size_t>(i)];
  EXPECT_EQ(m.signals[3].name, "gimbal_angle_2");
  EXPECT_EQ(m.signals[3].min, r.gimbal_angle_rad[msg::kAxis2].min);
  EXPECT_EQ(m.signals[3].max, r.gimbal_angle_rad[msg::kAxis2].max);
}

TEST(CanFrameMap, MessageMasksFollowTheNodes) {
  // A single-gimbal damper (imu + drive2): sensor = IMU, DRIVE2_FB, SENSOR_HUB; commands = DRIVE2, CONTROLLER.
  const NodeSet damper = kNodeImu | kNodeDrive2;
  int sensors = 0, commands = 0;
  for (std::size_t i = 0; i < kMessageCount; ++i) {
    if ((message_mask(Direction::kSensor, damper) >> i) & 1u) ++sensors;
    if ((message_mask(Direction::kActuator, damper) >> i) & 1u) ++commands;
  }
  EXPECT_EQ(sensors, 3);
  EXPECT_EQ(commands, 2);
  EXPECT_EQ(message_mask(Direction::kSensor, 0) & message_mask(Direction::kActuator, kAllNodes), 0u);
}

}  // namespace can_frame_map_test
}  // namespace gyrostab::can
