// The CAN FD maps generated from the signal tables (gyrostab_signals/<device>_can.hpp, tools/signals/
// can_layout.py) are faithful carriers of their device's frames, for every map of the build and the tests' own
// device: every byte of the generic sensor and actuator frame the device fills is carried by exactly one signal
// of its direction, signals never overlap and fit their frame, lengths are valid CAN FD lengths without slack,
// identifiers are unique standard ids, each direction's header comes last, and each value rides on the node
// its table names, with its table's range and unit. A device's bus carries its whole map.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>
#include <vector>

#include "hil/can/can_frame.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/frame_map.hpp"
#include "tests/unit/can_test_maps.hpp"

namespace gyrostab::can {
namespace can_frame_map_test {

using testing::test_can_maps;

TEST(CanFrameMap, EveryTableHasAMapFoundByItsDeviceName) {
  ASSERT_EQ(std::size(kAllCanMaps), std::size(msg::kAllDeviceSignals));
  for (const msg::DeviceSignals* d : msg::kAllDeviceSignals) {
    const CanMap* m = find_can_map(d->device);
    ASSERT_NE(m, nullptr) << d->device;
    EXPECT_EQ(m->signals, d) << d->device;
  }
  EXPECT_EQ(find_can_map("no_such_device"), nullptr);
  std::set<std::uint64_t> fingerprints;
  for (const CanMap* m : test_can_maps()) EXPECT_TRUE(fingerprints.insert(m->fingerprint).second) << m->device;
}

TEST(CanFrameMap, IdentifiersAreUniqueStandardIds) {
  for (const CanMap* map : test_can_maps()) {
    std::set<std::uint32_t> ids;
    for (const MessageSpec& m : map->messages) {
      EXPECT_LE(m.id, 0x7FFu) << map->device << " " << m.name;
      EXPECT_TRUE(ids.insert(m.id).second) << map->device << " " << m.name << " reuses id " << m.id;
    }
    EXPECT_LE(map->messages.size(), kMaxMessages);
  }
}

TEST(CanFrameMap, LengthsAreCanFdLengthsWithoutSlack) {
  for (const CanMap* map : test_can_maps()) {
    for (const MessageSpec& m : map->messages) {
      EXPECT_TRUE(fd_length_valid(m.length)) << map->device << " " << m.name;
      // The smallest FD length that holds the signals (bus load); the headers are 64 bytes (link envelope).
      EXPECT_EQ(m.length, m.header ? kHeaderLength : fd_round_up(used_bytes(m))) << map->device << " " << m.name;
    }
  }
}

TEST(CanFrameMap, EveryMessageStartsWithTheEnvelopeAndTheHeadersEndWithTheLinkEnvelope) {
  for (const CanMap* map : test_can_maps()) {
    for (const MessageSpec& m : map->messages) {
      SCOPED_TRACE(std::string(map->device) + " " + std::string(m.name));
      ASSERT_GE(m.signals.size(), 3u);
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
      if (!m.header) continue;
      ASSERT_GE(m.signals.size(), 7u);
      const SignalSpec* link = &m.signals[m.signals.size() - 4];
      const std::size_t at[] = {kLinkSenderByte, kLinkSessionByte, kLinkFreshnessByte, kLinkMacByte};
      const char* names[] = {"link_sender", "link_session", "link_freshness", "link_mac"};
      for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(link[i].name, names[i]);
        EXPECT_EQ(link[i].start_bit, 8 * at[i]);
        EXPECT_EQ(link[i].field_offset, kEnvelope);
      }
    }
  }
}

TEST(CanFrameMap, SignalsFitTheirFrameAndNeverOverlap) {
  for (const CanMap* map : test_can_maps()) {
    for (const MessageSpec& m : map->messages) {
      SCOPED_TRACE(std::string(map->device) + " " + std::string(m.name));
      std::array<bool, 8 * kFdMaxData> used{};
      std::set<std::string_view> names;
      for (const SignalSpec& s : m.signals) {
        EXPECT_TRUE(names.insert(s.name).second) << s.name << " twice";
        ASSERT_LE(s.start_bit + s.bit_length, 8 * m.length) << s.name;
        for (int b = s.start_bit; b < s.start_bit + s.bit_length; ++b) {
          EXPECT_FALSE(used[static_cast<std::size_t>(b)]) << s.name << " overlaps at bit " << b;
          used[static_cast<std::size_t>(b)] = true;
        }
        if (s.field_offset >= 0) {
          // Frame signals are whole bytes at byte positions (the codec copies them bytewise, bit for bit).
          EXPECT_EQ(s.start_bit % 8, 0) << s.name;
          EXPECT_EQ(s.bit_length % 8, 0) << s.name;
          EXPECT_EQ(s.factor, 1.0) << s.name;
          EXPECT_EQ(s.offset, 0.0) << s.name;
          // A double is 64 bits; an integer value 8, 16 or 32 (exact in a double).
          if (s.kind == SignalKind::kDouble) {
            EXPECT_EQ(s.bit_length, 64) << s.name;
          }
          if (s.integer) {
            EXPECT_NE(s.kind, SignalKind::kDouble) << s.name;
            EXPECT_LE(s.bit_length, 32) << s.name;
          }
        }
        EXPECT_LT(s.min, s.max) << s.name;
      }
    }
  }
}

// Each byte of the part of a generic frame the device fills is carried by exactly one signal of that
// direction.
void expect_covered_once(const CanMap& map, Direction d) {
  const std::size_t size = whole_bus(map).frame_bytes(d);
  std::vector<int> cover(size, 0);
  for (const MessageSpec& m : map.messages) {
    if (m.direction != d) continue;
    for (const SignalSpec& s : m.signals) {
      if (s.field_offset < 0) continue;
      ASSERT_LE(static_cast<std::size_t>(s.field_offset) + field_bytes(s), size) << m.name << "." << s.name;
      for (std::size_t i = 0; i < field_bytes(s); ++i) ++cover[static_cast<std::size_t>(s.field_offset) + i];
    }
  }
  for (std::size_t i = 0; i < size; ++i)
    EXPECT_EQ(cover[i], 1) << map.device << (d == Direction::kSensor ? " sensor" : " actuator") << " byte " << i;
}

TEST(CanFrameMap, EveryMapCoversItsDevicesFramesExactlyOnce) {
  for (const CanMap* map : test_can_maps()) {
    expect_covered_once(*map, Direction::kSensor);
    expect_covered_once(*map, Direction::kActuator);
  }
}

TEST(CanFrameMap, EachValueRidesOnItsTablesNodeWithItsTablesRangeAndUnit) {
  for (const CanMap* map : test_can_maps()) {
    for (Direction d : {Direction::kSensor, Direction::kActuator}) {
      const std::span<const msg::SignalSpec> specs =
          d == Direction::kSensor ? map->signals->sensors : map->signals->commands;
      const auto values = testing::values_on(whole_bus(*map), d);
      ASSERT_EQ(values.size(), specs.size());
      for (std::size_t i = 0; i < specs.size(); ++i) {
        SCOPED_TRACE(std::string(map->device) + " value " + std::to_string(i) + " " + std::string(specs[i].name));
        ASSERT_NE(values[i].signal, nullptr);
        EXPECT_EQ(values[i].message->node, specs[i].node);
        EXPECT_EQ(values[i].signal->min, specs[i].min);
        EXPECT_EQ(values[i].signal->max, specs[i].max);
        EXPECT_EQ(values[i].signal->unit, specs[i].unit);
        const std::string name = specs[i].count == 1 ? std::string(specs[i].name)
                                                     : std::string(specs[i].name) + "_" + std::to_string(specs[i].element + 1);
        EXPECT_EQ(values[i].signal->name, name);
      }
    }
  }
}

TEST(CanFrameMap, EachDirectionHasOneHeaderCarryingTheTickItComesLastAndHasTheHighestId) {
  for (const CanMap* map : test_can_maps()) {
    for (Direction d : {Direction::kSensor, Direction::kActuator}) {
      SCOPED_TRACE(std::string(map->device) + (d == Direction::kSensor ? " sensor" : " actuator"));
      int headers = 0;
      int last_index = -1, header_index = -1;
      std::uint32_t highest = 0;
      for (std::size_t i = 0; i < map->messages.size(); ++i) {
        const MessageSpec& m = map->messages[i];
        if (m.direction != d) continue;
        last_index = static_cast<int>(i);
        highest = std::max(highest, m.id);
        if (!m.header) continue;
        ++headers;
        header_index = static_cast<int>(i);
        EXPECT_EQ(m.name, d == Direction::kSensor ? "SENSOR_HUB" : "CONTROLLER_CMD");
        EXPECT_EQ(m.node, d == Direction::kSensor ? "sensor_hub" : "controller");
        bool has_tick = false;
        for (const SignalSpec& s : m.signals) has_tick |= s.field_offset == 0 && s.bit_length == 64;
        EXPECT_TRUE(has_tick) << m.name;
      }
      EXPECT_EQ(headers, 1);
      EXPECT_EQ(header_index, last_index);
      EXPECT_EQ(map->messages[static_cast<std::size_t>(header_index)].id, highest);
    }
  }
}

TEST(CanFrameMap, ADeviceBusCarriesItsWholeMap) {
  for (const CanMap* map : test_can_maps()) {
    const DeviceBus bus = whole_bus(*map);
    EXPECT_EQ(bus.frames(Direction::kSensor) + bus.frames(Direction::kActuator), map->messages.size())
        << map->device;
    EXPECT_EQ(bus.mask(Direction::kSensor) & bus.mask(Direction::kActuator), 0u) << map->device;
    EXPECT_EQ(bus.mask(Direction::kSensor) | bus.mask(Direction::kActuator),
              (std::uint32_t{1} << map->messages.size()) - 1u)
        << map->device;
  }
}

}  // namespace can_frame_map_test
}  // namespace gyrostab::can
