// The interface contract (firmware/msg/): the layout the transports (LCM, CAN) and logs rely on, on the typed
// frames generated from a table — the tests' union fixture (tests/signals/union_fixture_signals.toml; a
// device's LCM types, CAN map and DBC file are generated from its table the same way). A failure here means
// the wire format changed. And every registered device has a table of its own: its signals and CAN map are
// found by its name (tools/signals/device_signals.hpp, device_can_map.hpp).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <type_traits>

#include "firmware/msg/fault_bits.hpp"
#include "tests/support/union_frames.hpp"
#include "tools/devices/registry.hpp"
#include "tools/signals/device_can_map.hpp"
#include "tools/signals/device_signals.hpp"

namespace gyrostab::msg {
namespace contract_test {

template <class T>
bool all_bytes_zero(const T& value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (unsigned char b : bytes) {
    if (b != 0) return false;
  }
  return true;
}

TEST(Contract, FramesAreTriviallyCopyableStandardLayoutAggregates) {
  EXPECT_TRUE(std::is_trivially_copyable_v<SensorFrame>);
  EXPECT_TRUE(std::is_standard_layout_v<SensorFrame>);
  EXPECT_TRUE(std::is_aggregate_v<SensorFrame>);
  EXPECT_TRUE(std::is_trivially_copyable_v<ActuatorFrame>);
  EXPECT_TRUE(std::is_standard_layout_v<ActuatorFrame>);
  EXPECT_TRUE(std::is_aggregate_v<ActuatorFrame>);
}

TEST(Contract, SensorFrameHasTheWireLayout) {
  EXPECT_EQ(sizeof(SensorFrame), 216u);
  EXPECT_EQ(alignof(SensorFrame), 8u);
  EXPECT_EQ(offsetof(SensorFrame, tick), 0u);
  EXPECT_EQ(offsetof(SensorFrame, time_ns), 8u);
  EXPECT_EQ(offsetof(SensorFrame, sample_time_ns), 16u);
  EXPECT_EQ(offsetof(SensorFrame, sequence), 24u);
  EXPECT_EQ(offsetof(SensorFrame, status), 28u);
  EXPECT_EQ(offsetof(SensorFrame, carrier_angle_rad), 32u);
  EXPECT_EQ(offsetof(SensorFrame, carrier_rate_rad_s), 56u);
  EXPECT_EQ(offsetof(SensorFrame, gimbal_angle_rad), 80u);
  EXPECT_EQ(offsetof(SensorFrame, gimbal_rate_rad_s), 96u);
  EXPECT_EQ(offsetof(SensorFrame, motor_current_A), 112u);
  EXPECT_EQ(offsetof(SensorFrame, rotor_speed_rad_s), 128u);
  // Encoder counts are doubles in the frame like every value (integers, exact; on CAN they ride as int32).
  EXPECT_EQ(offsetof(SensorFrame, encoder_count), 136u);
  EXPECT_EQ(sizeof(SensorFrame::encoder_count), 16u);
  EXPECT_EQ(offsetof(SensorFrame, cluster_gimbal_angle_rad), 152u);
  EXPECT_EQ(offsetof(SensorFrame, cluster_gimbal_rate_rad_s), 184u);
}

TEST(Contract, ActuatorFrameHasTheWireLayout) {
  EXPECT_EQ(sizeof(ActuatorFrame), 104u);
  EXPECT_EQ(alignof(ActuatorFrame), 8u);
  EXPECT_EQ(offsetof(ActuatorFrame, tick), 0u);
  EXPECT_EQ(offsetof(ActuatorFrame, time_ns), 8u);
  EXPECT_EQ(offsetof(ActuatorFrame, sensor_tick), 16u);
  EXPECT_EQ(offsetof(ActuatorFrame, sequence), 24u);
  EXPECT_EQ(offsetof(ActuatorFrame, status), 28u);
  EXPECT_EQ(offsetof(ActuatorFrame, gimbal_torque_Nm), 32u);
  EXPECT_EQ(offsetof(ActuatorFrame, motor_voltage_V), 48u);
  EXPECT_EQ(offsetof(ActuatorFrame, precession_brake), 64u);
  EXPECT_EQ(offsetof(ActuatorFrame, cluster_rate_command_rad_s), 72u);
}

// No padding: the members' sizes add up to the struct's, so every byte on the wire is a field (logs of the
// same run are byte-identical, no uninitialized padding leaks into them).
TEST(Contract, FramesHaveNoPadding) {
  const SensorFrame s{};
  const std::size_t sensor_members = sizeof s.tick + sizeof s.time_ns + sizeof s.sample_time_ns +
                                     sizeof s.sequence + sizeof s.status + sizeof s.carrier_angle_rad +
                                     sizeof s.carrier_rate_rad_s + sizeof s.gimbal_angle_rad +
                                     sizeof s.gimbal_rate_rad_s + sizeof s.motor_current_A +
                                     sizeof s.rotor_speed_rad_s + sizeof s.encoder_count +
                                     sizeof s.cluster_gimbal_angle_rad + sizeof s.cluster_gimbal_rate_rad_s;
  EXPECT_EQ(sensor_members, sizeof(SensorFrame));
  const ActuatorFrame a{};
  const std::size_t actuator_members = sizeof a.tick + sizeof a.time_ns + sizeof a.sensor_tick +
                                       sizeof a.sequence + sizeof a.status + sizeof a.gimbal_torque_Nm +
                                       sizeof a.motor_voltage_V + sizeof a.precession_brake +
                                       sizeof a.cluster_rate_command_rad_s;
  EXPECT_EQ(actuator_members, sizeof(ActuatorFrame));
}

TEST(Contract, DefaultFramesAreAllZeroBytes) {
  EXPECT_TRUE(all_bytes_zero(SensorFrame{}));
  EXPECT_TRUE(all_bytes_zero(ActuatorFrame{}));
}

TEST(Contract, SensorFrameSurvivesAByteCopyBitForBit) {
  SensorFrame s{};
  s.tick = 0x0123456789ABCDEFu;
  s.time_ns = -1'234'567'890'123;
  s.sample_time_ns = 987'654'321;
  s.sequence = 0xFFFFFFFEu;
  s.status = bit(SensorStatusBit::kDriveFault);
  s.carrier_angle_rad[kRoll] = 0.1;
  s.carrier_angle_rad[kPitch] = -0.2;
  s.carrier_angle_rad[kYaw] = 3.0;
  s.carrier_rate_rad_s[kRoll] = -0.05;
  s.carrier_rate_rad_s[kPitch] = 1e-9;
  s.carrier_rate_rad_s[kYaw] = -0.0;  // sign of zero must survive
  s.gimbal_angle_rad[kAxis1] = 0.7;
  s.gimbal_angle_rad[kAxis2] = -1.1;
  s.gimbal_rate_rad_s[kAxis1] = 12.5;
  s.gimbal_rate_rad_s[kAxis2] = -3.25;
  s.motor_current_A[kAxis1] = 4.0;
  s.motor_current_A[kAxis2] = -2.5;
  s.rotor_speed_rad_s = 628.3185307179586;
  s.encoder_count[kAxis1] = -2147483647 - 1;
  s.encoder_count[kAxis2] = 2147483647;

  unsigned char wire[sizeof(SensorFrame)];
  std::memcpy(wire, &s, sizeof wire);
  SensorFrame r{};
  std::memcpy(&r, wire, sizeof wire);

  EXPECT_EQ(r.tick, s.tick);
  EXPECT_EQ(r.time_ns, s.time_ns);
  EXPECT_EQ(r.sample_time_ns, s.sample_time_ns);
  EXPECT_EQ(r.sequence, s.sequence);
  EXPECT_EQ(r.status, s.status);
  for (std::size_t i = 0; i < kCarrierAxes; ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(r.carrier_angle_rad[i]),
              std::bit_cast<std::uint64_t>(s.carrier_angle_rad[i]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(r.carrier_rate_rad_s[i]),
              std::bit_cast<std::uint64_t>(s.carrier_rate_rad_s[i]));
  }
  for (std::size_t i = 0; i < kGimbalAxes; ++i) {
    EXPECT_EQ(r.gimbal_angle_rad[i], s.gimbal_angle_rad[i]);
    EXPECT_EQ(r.gimbal_rate_rad_s[i], s.gimbal_rate_rad_s[i]);
    EXPECT_EQ(r.motor_current_A[i], s.motor_current_A[i]);
    EXPECT_EQ(r.encoder_count[i], s.encoder_count[i]);
  }
  EXPECT_EQ(r.rotor_speed_rad_s, s.rotor_speed_rad_s);
  EXPECT_TRUE(std::signbit(r.carrier_rate_rad_s[kYaw]));
  EXPECT_EQ(std::memcmp(&r, &s, sizeof s), 0);
}

TEST(Contract, ActuatorFrameSurvivesAByteCopyBitForBit) {
  ActuatorFrame a{};
  a.tick = 42;
  a.time_ns = 42'000'000;
  a.sensor_tick = 41;
  a.sequence = 7;
  a.status = bit(FaultBit::kSafeState) | bit(FaultBit::kSensorMissing);
  a.gimbal_torque_Nm[kAxis1] = -150.0;
  a.gimbal_torque_Nm[kAxis2] = 2.5e4;
  a.motor_voltage_V[kAxis1] = 24.0;
  a.motor_voltage_V[kAxis2] = -12.0;
  a.precession_brake = 0.5;
  unsigned char wire[sizeof(ActuatorFrame)];
  std::memcpy(wire, &a, sizeof wire);
  ActuatorFrame r{};
  std::memcpy(&r, wire, sizeof wire);
  EXPECT_EQ(r.tick, 42u);
  EXPECT_EQ(r.sensor_tick, 41u);
  EXPECT_EQ(r.status, a.status);
  EXPECT_EQ(r.gimbal_torque_Nm[kAxis2], 2.5e4);
  EXPECT_EQ(r.motor_voltage_V[kAxis2], -12.0);
  EXPECT_EQ(r.precession_brake, 0.5);
  EXPECT_EQ(std::memcmp(&r, &a, sizeof a), 0);
}

// Bit positions are part of the wire format: a renumbering breaks every recorded log and the DBC file.
TEST(Contract, FaultBitPositionsAreFixed) {
  EXPECT_EQ(bit(FaultBit::kSensorMissing), 1u << 0);
  EXPECT_EQ(bit(FaultBit::kSensorStale), 1u << 1);
  EXPECT_EQ(bit(FaultBit::kSensorNonFinite), 1u << 2);
  EXPECT_EQ(bit(FaultBit::kSensorOutOfRange), 1u << 3);
  EXPECT_EQ(bit(FaultBit::kSensorReportedFault), 1u << 4);
  EXPECT_EQ(bit(FaultBit::kHoldingLastGood), 1u << 8);
  EXPECT_EQ(bit(FaultBit::kSafeState), 1u << 9);
  EXPECT_EQ(bit(FaultBit::kAwaitingFirstFrame), 1u << 10);
  EXPECT_EQ(bit(SensorStatusBit::kRateGyroSaturated), 1u << 0);
  EXPECT_EQ(bit(SensorStatusBit::kEncoderError), 1u << 1);
  EXPECT_EQ(bit(SensorStatusBit::kDriveFault), 1u << 2);
  EXPECT_EQ(bit(SensorStatusBit::kRotorSpeedInvalid), 1u << 3);
}

TEST(Contract, CauseMaskIsExactlyTheCauseBits) {
  const std::uint32_t causes = bit(FaultBit::kSensorMissing) | bit(FaultBit::kSensorStale) |
                               bit(FaultBit::kSensorNonFinite) | bit(FaultBit::kSensorOutOfRange) |
                               bit(FaultBit::kSensorReportedFault);
  EXPECT_EQ(kFaultCauseMask, causes);
  EXPECT_EQ(kFaultCauseMask & bit(FaultBit::kSafeState), 0u);
  EXPECT_EQ(kFaultCauseMask & bit(FaultBit::kHoldingLastGood), 0u);
  EXPECT_EQ(kFaultCauseMask & bit(FaultBit::kAwaitingFirstFrame), 0u);
  // Control laws own bits 16-31: the monitor must stay below them.
  EXPECT_LT(bit(FaultBit::kAwaitingFirstFrame), 1u << 16);
}

TEST(Contract, AxisIndicesFollowTheBook) {
  // Magnus ch. 14: axis 2 carries β (precession / case angle) in every device.
  EXPECT_EQ(kAxis1, 0u);
  EXPECT_EQ(kAxis2, 1u);
  EXPECT_EQ(kGimbalAxes, 2u);
  EXPECT_EQ(kRoll, 0u);
  EXPECT_EQ(kPitch, 1u);
  EXPECT_EQ(kYaw, 2u);
  EXPECT_EQ(kCarrierAxes, 3u);
  EXPECT_EQ(std::size(SensorFrame{}.gimbal_angle_rad), kGimbalAxes);
  EXPECT_EQ(std::size(SensorFrame{}.carrier_rate_rad_s), kCarrierAxes);
  EXPECT_EQ(std::size(ActuatorFrame{}.gimbal_torque_Nm), kGimbalAxes);
}

TEST(Contract, EveryRegisteredDeviceHasASignalTableAndACanMap) {
  ASSERT_FALSE(tools::devices().empty());
  for (const tools::DeviceDescriptor* d : tools::devices()) {
    const DeviceSignals* signals = tools::find_device_signals(d->name);
    ASSERT_NE(signals, nullptr) << d->name << " has no signal table";
    EXPECT_EQ(signals->device, d->name);
    const can::CanMap* map = tools::find_device_can_map(d->name);
    ASSERT_NE(map, nullptr) << d->name << " has no CAN map";
    EXPECT_EQ(map->signals, signals) << d->name;
  }
  // No fallback: a name no table declares has no signals and no map.
  EXPECT_EQ(tools::find_device_signals("no_such_device"), nullptr);
  EXPECT_EQ(tools::find_device_can_map("no_such_device"), nullptr);
  EXPECT_EQ(tools::find_device_signals("union_fixture"), nullptr) << "a test fixture is never a device";
}

}  // namespace contract_test
}  // namespace gyrostab::msg
