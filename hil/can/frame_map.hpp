// The CAN bus of a gyrostab device: which frames carry the interface contract (firmware/msg/sensor_frame.hpp,
// actuator_frame.hpp), with identifier, length, sender node, and every signal's position, type, scaling,
// offset, unit and range. One constexpr table: the codec (frame_codec.hpp), the DBC file (dbc_writer.hpp),
// the bus-load check (bus_load.hpp) and docs/can.md all derive from it; tests/unit/can_frame_map_test.cpp
// checks that it covers every byte of the contract exactly once.
//
// Physical layer: CAN FD, 11-bit identifiers, bit-rate switch (1 Mbit/s arbitration, 5 Mbit/s data by
// default). Why FD and raw IEEE-754 doubles (docs/can.md has the arithmetic): lockstep runs over CAN must be
// bit-identical to in-process runs, so the controller must see exactly the doubles the plant computed. A
// classic 8-byte frame carries one double next to its CRC and counter, so a tick would need ~30 classic frames
// (30 k frames/s at 1 kHz: four times what 1 Mbit/s carries); scaled integers would need every mode,
// in-process included, to quantize the same way. FD frames of up to 64 bytes carry the doubles unchanged.
// Every signal therefore has factor 1 and offset 0; the range is the plausible physical range (the sensor
// ranges are firmware/fault/sensor_ranges.hpp's defaults), checked and counted by the decoder, while the
// decision about an implausible value stays with the firmware's fault monitor, exactly as in-process.
//
// The bus poses as the hardware. Nodes:
//   sensor_hub   frame header (tick, times, sequence, status) and the rotor speed pick-off; always present
//   imu          carrier attitude and rate (ship, monorail car, platform)
//   drive1/2     one gimbal drive per axis: feedback (angle, rate, winding current, encoder) and command
//   cluster      the gimbal electronics of a multi-gyro cluster (a CMG cluster's four units): the units'
//                gimbal angles and rates, and their gimbal rate commands
//   controller   the firmware: command header (tick, times, status, precession brake); always present
// A device has the nodes of its hardware (device_nodes, tools/run/can_transport.hpp): a single-gimbal damper
// has no drive1. The plant refuses to run a device that fills a field of a node it does not have (the value
// would be lost on the bus and lockstep would no longer be bit-identical).
//
// Every frame begins with the same 4-byte envelope (E2E-style protection, as AUTOSAR E2E profile 1 lays out):
//   byte 0      CRC-8 SAE J1850 (crc8.hpp) over the identifier (2 bytes, low byte first) and bytes 1..len-1
//   byte 1      bits 0-3: alive counter, +1 (mod 16) per frame sent on this identifier; bits 4-7: zero
//   bytes 2-3   tick tag: the low 16 bits of the tick the frame belongs to (the header frames also carry the
//               full 64-bit tick), so the receiver assembles a tick's frames and never mixes ticks
// Unused bytes up to the FD length are zero (covered by the CRC).
//
// The two header frames (SENSOR_HUB, CONTROLLER_CMD) end with the link envelope of the set, the one every
// plant ⇄ controller link carries (hil/link/link_guard.hpp, docs/transport.md):
//   bytes 44-47 sender id, 48-51 session id (both 32-bit: the ids are drawn as 32-bit values),
//   bytes 52-55 the low 32 bits of the sender's freshness counter (SecOC's truncated freshness value),
//   bytes 56-63 the MAC over the whole set (link_seal.hpp says which bytes); without a key an unkeyed
//               SipHash over the same bytes, which binds the body frames to their header.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

#include "firmware/fault/sensor_ranges.hpp"
#include "firmware/msg/actuator_frame.hpp"
#include "firmware/msg/sensor_frame.hpp"

namespace gyrostab::can {

// What a signal's raw bits are (all little-endian, "Intel" byte order in DBC terms).
enum class SignalKind : std::uint8_t { kUnsigned, kSigned, kDouble };

// Which contract struct a message carries: sensor messages go from the plant's nodes to the controller,
// actuator messages from the controller to the drive nodes.
enum class Direction : std::uint8_t { kSensor, kActuator };

// Node presence bits (NodeSet). The sensor hub and the controller are always on the bus.
enum NodeBit : std::uint8_t {
  kNodeImu = 1u << 0,
  kNodeDrive1 = 1u << 1,
  kNodeDrive2 = 1u << 2,
  kNodeCluster = 1u << 3,
};
using NodeSet = std::uint8_t;
inline constexpr NodeSet kAllNodes = kNodeImu | kNodeDrive1 | kNodeDrive2 | kNodeCluster;

struct SignalSpec {
  std::string_view name;      // DBC signal name
  std::uint16_t start_bit;    // position of the least significant bit in the payload (bit 0 = byte 0 bit 0)
  std::uint8_t bit_length;    // 64 for doubles
  SignalKind kind;
  int field_offset;           // byte offset of the contract field it carries (sizeof = bit_length / 8); -1: envelope
  double factor;              // physical = raw · factor + offset
  double offset;
  double min;                 // plausible physical range [unit]
  double max;
  std::string_view unit;
  std::string_view comment;
};

struct MessageSpec {
  std::uint32_t id;           // 11-bit identifier; lower = higher priority on the bus
  std::string_view name;
  std::string_view sender;    // node name (DBC BU_)
  Direction direction;
  std::uint8_t length;        // FD data length [bytes]
  NodeSet requires_node;      // 0: always present; else present when the device has this node
  bool header;                // carries the contract header (full tick): sent last in its tick's set
  std::span<const SignalSpec> signals;
  std::string_view comment;
};

// Envelope (every message).
inline constexpr int kEnvelope = -1;
inline constexpr std::size_t kCrcByte = 0;
inline constexpr std::size_t kAliveByte = 1;
inline constexpr std::size_t kTickTagByte = 2;
inline constexpr std::size_t kEnvelopeBytes = 4;
inline constexpr std::uint8_t kAliveMask = 0x0F;

// Link envelope (header frames only).
inline constexpr std::size_t kLinkSenderByte = 44;
inline constexpr std::size_t kLinkSessionByte = 48;
inline constexpr std::size_t kLinkFreshnessByte = 52;
inline constexpr std::size_t kLinkMacByte = 56;
inline constexpr std::size_t kLinkFreshnessBytes = 4;
inline constexpr std::uint8_t kHeaderLength = 64;

namespace detail {
constexpr double kU64Max = 18446744073709551615.0;
constexpr double kI64Min = -9223372036854775808.0;
constexpr double kI64Max = 9223372036854775807.0;
constexpr double kU32Max = 4294967295.0;
constexpr double kI32Min = -2147483648.0;
constexpr double kI32Max = 2147483647.0;
constexpr firmware::SensorRanges kR{};  // the firmware's default plausible ranges

template <class T>
constexpr int off(std::size_t struct_offset, std::size_t index = 0) {
  return static_cast<int>(struct_offset + index * sizeof(T));
}
#define GYROSTAB_CAN_SOFF(field) offsetof(msg::SensorFrame, field)
#define GYROSTAB_CAN_AOFF(field) offsetof(msg::ActuatorFrame, field)

#define GYROSTAB_CAN_ENVELOPE                                                                             \
  SignalSpec{"crc", 0, 8, SignalKind::kUnsigned, kEnvelope, 1, 0, 0, 255, "",                               \
             "CRC-8 SAE J1850 (poly 0x1D, init 0xFF, xorout 0xFF) over the identifier (low byte first) "    \
             "and bytes 1..len-1"},                                                                         \
      SignalSpec{"alive", 8, 4, SignalKind::kUnsigned, kEnvelope, 1, 0, 0, 15, "",                          \
                 "alive counter: +1 mod 16 per frame on this identifier"},                                 \
      SignalSpec{"tick_tag", 16, 16, SignalKind::kUnsigned, kEnvelope, 1, 0, 0, 65535, "tick",              \
                 "low 16 bits of the controller tick this frame belongs to"}

#define GYROSTAB_CAN_LINK_ENVELOPE                                                                        \
  SignalSpec{"link_sender", 352, 32, SignalKind::kUnsigned, kEnvelope, 1, 0, 1, kU32Max, "",                 \
             "sender id of this set (hil/link/link_guard.hpp)"},                                            \
      SignalSpec{"link_session", 384, 32, SignalKind::kUnsigned, kEnvelope, 1, 0, 1, kU32Max, "",            \
                 "session id drawn by the plant at start-up"},                                              \
      SignalSpec{"link_freshness", 416, 32, SignalKind::kUnsigned, kEnvelope, 1, 0, 0, kU32Max, "",          \
                 "low 32 bits of the sender's freshness counter (SecOC)"},                                  \
      SignalSpec{"link_mac", 448, 64, SignalKind::kUnsigned, kEnvelope, 1, 0, 0, kU64Max, "",                \
                 "SipHash-2-4 MAC over the set (keyed with --key-file, else unkeyed)"}

// Sensor side ------------------------------------------------------------------------------------------------
inline constexpr SignalSpec kSensorHubSignals[] = {
    GYROSTAB_CAN_ENVELOPE,
    {"sensor_status", 32, 32, SignalKind::kUnsigned, off<std::uint32_t>(GYROSTAB_CAN_SOFF(status)), 1, 0, 0, kU32Max,
     "bits", "SensorStatusBit set (firmware/msg/fault_bits.hpp)"},
    {"sensor_tick", 64, 64, SignalKind::kUnsigned, off<std::uint64_t>(GYROSTAB_CAN_SOFF(tick)), 1, 0, 0, kU64Max, "tick",
     "controller tick this sensor frame belongs to"},
    {"sensor_time", 128, 64, SignalKind::kSigned, off<std::int64_t>(GYROSTAB_CAN_SOFF(time_ns)), 1, 0, kI64Min, kI64Max,
     "ns", "publish time on the plant's clock"},
    {"sample_time", 192, 64, SignalKind::kSigned, off<std::int64_t>(GYROSTAB_CAN_SOFF(sample_time_ns)), 1, 0, kI64Min,
     kI64Max, "ns", "when the signals were sampled"},
    {"sensor_sequence", 256, 32, SignalKind::kUnsigned, off<std::uint32_t>(GYROSTAB_CAN_SOFF(sequence)), 1, 0, 0,
     kU32Max, "", "publisher's frame counter, wraps at 2^32"},
    {"rotor_speed", 288, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(rotor_speed_rad_s)), 1, 0,
     kR.rotor_speed_rad_s.min, kR.rotor_speed_rad_s.max, "rad/s", "rotor spin speed relative to the innermost gimbal"},
    GYROSTAB_CAN_LINK_ENVELOPE,
};

inline constexpr SignalSpec kImuSignals[] = {
    GYROSTAB_CAN_ENVELOPE,
    {"carrier_roll", 32, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(carrier_angle_rad), msg::kRoll), 1, 0,
     kR.carrier_angle_rad[0].min, kR.carrier_angle_rad[0].max, "rad", "carrier roll angle phi"},
    {"carrier_pitch", 96, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(carrier_angle_rad), msg::kPitch), 1,
     0, kR.carrier_angle_rad[1].min, kR.carrier_angle_rad[1].max, "rad", "carrier pitch angle theta"},
    {"carrier_yaw", 160, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(carrier_angle_rad), msg::kYaw), 1, 0,
     kR.carrier_angle_rad[2].min, kR.carrier_angle_rad[2].max, "rad", "carrier yaw angle psi"},
    {"carrier_rate_roll", 224, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(carrier_rate_rad_s), msg::kRoll),
     1, 0, kR.carrier_rate_rad_s[0].min, kR.carrier_rate_rad_s[0].max, "rad/s", "carrier angular velocity, x"},
    {"carrier_rate_pitch", 288, 64, SignalKind::kDouble,
     off<double>(GYROSTAB_CAN_SOFF(carrier_rate_rad_s), msg::kPitch), 1, 0, kR.carrier_rate_rad_s[1].min,
     kR.carrier_rate_rad_s[1].max, "rad/s", "carrier angular velocity, y"},
    {"carrier_rate_yaw", 352, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(carrier_rate_rad_s), msg::kYaw),
     1, 0, kR.carrier_rate_rad_s[2].min, kR.carrier_rate_rad_s[2].max, "rad/s", "carrier angular velocity, z"},
};

#define GYROSTAB_CAN_DRIVE_FEEDBACK(n, axis)                                                                     \
  {                                                                                                             \
    GYROSTAB_CAN_ENVELOPE,                                                                                      \
        {"gimbal_angle_" #n, 32, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(gimbal_angle_rad), axis), \
         1, 0, kR.gimbal_angle_rad[axis].min, kR.gimbal_angle_rad[axis].max, "rad",                             \
         "gimbal angle of axis " #n " from neutral"},                                                           \
        {"gimbal_rate_" #n, 96, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(gimbal_rate_rad_s), axis), \
         1, 0, kR.gimbal_rate_rad_s[axis].min, kR.gimbal_rate_rad_s[axis].max, "rad/s",                         \
         "gimbal rate of axis " #n " relative to the carrier"},                                                 \
        {"motor_current_" #n, 160, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_SOFF(motor_current_A), axis), \
         1, 0, kR.motor_current_A[axis].min, kR.motor_current_A[axis].max, "A",                                 \
         "torque motor winding current of axis " #n},                                                           \
        {"encoder_count_" #n, 224, 64, SignalKind::kDouble,                                                      \
         off<double>(GYROSTAB_CAN_SOFF(encoder_count), axis), 1, 0, kI32Min, kI32Max, "counts",                 \
         "raw motor-side encoder count of axis " #n ", wraps at 2^32 (an integer, exact as a double)"},         \
  }
inline constexpr SignalSpec kDrive1FeedbackSignals[] = GYROSTAB_CAN_DRIVE_FEEDBACK(1, msg::kAxis1);
inline constexpr SignalSpec kDrive2FeedbackSignals[] = GYROSTAB_CAN_DRIVE_FEEDBACK(2, msg::kAxis2);

// A cluster's four units, one double each at bytes 4, 12, 20, 28 (FD length 48: 36 bytes used).
#define GYROSTAB_CAN_CLUSTER_SIGNAL(field, name, i, lo, hi, unit, what)                                         \
  SignalSpec {                                                                                                \
    name #i, static_cast<std::uint16_t>(32 + 64 * ((i) - 1)), 64, SignalKind::kDouble,                        \
        off<double>(field, (i) - 1), 1, 0, lo, hi, unit, what " of cluster unit " #i                          \
  }
#define GYROSTAB_CAN_CLUSTER_FOUR(field, name, lo, hi, unit, what)                                             \
  GYROSTAB_CAN_ENVELOPE, GYROSTAB_CAN_CLUSTER_SIGNAL(field, name, 1, lo, hi, unit, what),                     \
      GYROSTAB_CAN_CLUSTER_SIGNAL(field, name, 2, lo, hi, unit, what),                                        \
      GYROSTAB_CAN_CLUSTER_SIGNAL(field, name, 3, lo, hi, unit, what),                                        \
      GYROSTAB_CAN_CLUSTER_SIGNAL(field, name, 4, lo, hi, unit, what)
static_assert(msg::kClusterUnits == 4, "the cluster frames carry four units");
inline constexpr SignalSpec kClusterAngleSignals[] = {
    GYROSTAB_CAN_CLUSTER_FOUR(GYROSTAB_CAN_SOFF(cluster_gimbal_angle_rad), "cluster_gimbal_angle_",
                              kR.cluster_gimbal_angle_rad[0].min, kR.cluster_gimbal_angle_rad[0].max, "rad",
                              "gimbal angle")};
inline constexpr SignalSpec kClusterRateSignals[] = {
    GYROSTAB_CAN_CLUSTER_FOUR(GYROSTAB_CAN_SOFF(cluster_gimbal_rate_rad_s), "cluster_gimbal_rate_",
                              kR.cluster_gimbal_rate_rad_s[0].min, kR.cluster_gimbal_rate_rad_s[0].max, "rad/s",
                              "gimbal rate relative to the carrier")};

// Actuator side ----------------------------------------------------------------------------------------------
// Plausible command ranges: beyond what any shipped device's drive can deliver (the ship damper's precession
// torque is of the order of 1e6 N m).
inline constexpr double kTorqueLimitNm = 1e7;
inline constexpr double kVoltageLimitV = 1e3;

inline constexpr SignalSpec kControllerCommandSignals[] = {
    GYROSTAB_CAN_ENVELOPE,
    {"controller_status", 32, 32, SignalKind::kUnsigned, off<std::uint32_t>(GYROSTAB_CAN_AOFF(status)), 1, 0, 0,
     kU32Max, "bits", "FaultBit set (firmware/msg/fault_bits.hpp); bit 9 = safe state: every drive to zero torque"},
    {"command_tick", 64, 64, SignalKind::kUnsigned, off<std::uint64_t>(GYROSTAB_CAN_AOFF(tick)), 1, 0, 0, kU64Max,
     "tick", "controller tick at which this command was computed"},
    {"command_time", 128, 64, SignalKind::kSigned, off<std::int64_t>(GYROSTAB_CAN_AOFF(time_ns)), 1, 0, kI64Min,
     kI64Max, "ns", "publish time on the controller's clock"},
    {"command_sensor_tick", 192, 64, SignalKind::kUnsigned, off<std::uint64_t>(GYROSTAB_CAN_AOFF(sensor_tick)), 1, 0,
     0, kU64Max, "tick", "tick of the sensor frame the command was computed from"},
    {"command_sequence", 256, 32, SignalKind::kUnsigned, off<std::uint32_t>(GYROSTAB_CAN_AOFF(sequence)), 1, 0, 0,
     kU32Max, "", "controller's frame counter, wraps at 2^32"},
    {"precession_brake", 288, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_AOFF(precession_brake)), 1, 0, 0.0,
     1.0, "", "precession brake on axis 2: 0 released, 1 full brake"},
    GYROSTAB_CAN_LINK_ENVELOPE,
};

#define GYROSTAB_CAN_DRIVE_COMMAND(n, axis)                                                                      \
  {                                                                                                             \
    GYROSTAB_CAN_ENVELOPE,                                                                                      \
        {"gimbal_torque_" #n, 32, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_AOFF(gimbal_torque_Nm), axis), \
         1, 0, -kTorqueLimitNm, kTorqueLimitNm, "N m", "commanded torque on gimbal axis " #n},                  \
        {"motor_voltage_" #n, 96, 64, SignalKind::kDouble, off<double>(GYROSTAB_CAN_AOFF(motor_voltage_V), axis), \
         1, 0, -kVoltageLimitV, kVoltageLimitV, "V", "commanded terminal voltage of the axis " #n " motor"},     \
  }
inline constexpr SignalSpec kDrive1CommandSignals[] = GYROSTAB_CAN_DRIVE_COMMAND(1, msg::kAxis1);
inline constexpr SignalSpec kDrive2CommandSignals[] = GYROSTAB_CAN_DRIVE_COMMAND(2, msg::kAxis2);

// Beyond any CMG's gimbal rate limit (the shipped scenes' is 1 rad/s).
inline constexpr double kClusterRateLimit = 1e3;
inline constexpr SignalSpec kClusterCommandSignals[] = {
    GYROSTAB_CAN_CLUSTER_FOUR(GYROSTAB_CAN_AOFF(cluster_rate_command_rad_s), "cluster_rate_command_",
                              -kClusterRateLimit, kClusterRateLimit, "rad/s", "commanded gimbal rate")};

#undef GYROSTAB_CAN_CLUSTER_FOUR
#undef GYROSTAB_CAN_CLUSTER_SIGNAL
#undef GYROSTAB_CAN_DRIVE_COMMAND
#undef GYROSTAB_CAN_DRIVE_FEEDBACK
#undef GYROSTAB_CAN_ENVELOPE
#undef GYROSTAB_CAN_LINK_ENVELOPE
#undef GYROSTAB_CAN_AOFF
#undef GYROSTAB_CAN_SOFF
}  // namespace detail

// The map. Within a direction, the header message comes last: it is sent last in a tick's set, so a receiver
// that has it has seen the rest unless a frame was lost.
inline constexpr MessageSpec kMessages[] = {
    {0x101, "DRIVE1_CMD", "controller", Direction::kActuator, 20, kNodeDrive1, false, detail::kDrive1CommandSignals,
     "torque and voltage command to the axis-1 gimbal drive"},
    {0x102, "DRIVE2_CMD", "controller", Direction::kActuator, 20, kNodeDrive2, false, detail::kDrive2CommandSignals,
     "torque and voltage command to the axis-2 gimbal drive"},
    {0x103, "CLUSTER_CMD", "controller", Direction::kActuator, 48, kNodeCluster, false,
     detail::kClusterCommandSignals, "gimbal rate commands to the four units of the cluster"},
    {0x080, "CONTROLLER_CMD", "controller", Direction::kActuator, kHeaderLength, 0, true,
     detail::kControllerCommandSignals,
     "command header: tick, times, status (safe state), precession brake, link envelope; completes the tick's "
     "command set"},
    {0x181, "DRIVE1_FB", "drive1", Direction::kSensor, 48, kNodeDrive1, false, detail::kDrive1FeedbackSignals,
     "axis-1 gimbal drive feedback: angle, rate, winding current, encoder"},
    {0x182, "DRIVE2_FB", "drive2", Direction::kSensor, 48, kNodeDrive2, false, detail::kDrive2FeedbackSignals,
     "axis-2 gimbal drive feedback: angle, rate, winding current, encoder"},
    {0x183, "CLUSTER_ANGLE_FB", "cluster", Direction::kSensor, 48, kNodeCluster, false, detail::kClusterAngleSignals,
     "gimbal angles of the four units of the cluster"},
    {0x184, "CLUSTER_RATE_FB", "cluster", Direction::kSensor, 48, kNodeCluster, false, detail::kClusterRateSignals,
     "gimbal rates of the four units of the cluster"},
    {0x190, "IMU", "imu", Direction::kSensor, 64, kNodeImu, false, detail::kImuSignals,
     "carrier attitude (roll, pitch, yaw) and angular velocity"},
    {0x1A0, "SENSOR_HUB", "sensor_hub", Direction::kSensor, kHeaderLength, 0, true, detail::kSensorHubSignals,
     "sensor frame header: tick, times, sequence, status, rotor speed, link envelope; completes the tick's sensor "
     "set"},
};
inline constexpr std::size_t kMessageCount = sizeof(kMessages) / sizeof(kMessages[0]);
inline constexpr std::size_t kMaxMessagesPerDirection = 6;
inline constexpr std::string_view kNodeNames[] = {"sensor_hub", "imu", "drive1", "drive2", "cluster", "controller"};

// Index of the message with this identifier in kMessages, or -1. O(kMessageCount).
constexpr int message_index(std::uint32_t id) {
  for (std::size_t i = 0; i < kMessageCount; ++i)
    if (kMessages[i].id == id) return static_cast<int>(i);
  return -1;
}

constexpr bool message_present(const MessageSpec& m, NodeSet nodes) {
  return m.requires_node == 0 || (nodes & m.requires_node) != 0;
}

// Bit i set: kMessages[i] is part of a tick's set in this direction for this node set.
constexpr std::uint32_t message_mask(Direction d, NodeSet nodes) {
  std::uint32_t mask = 0;
  for (std::size_t i = 0; i < kMessageCount; ++i)
    if (kMessages[i].direction == d && message_present(kMessages[i], nodes)) mask |= 1u << i;
  return mask;
}

static_assert(kMessageCount <= 32, "message masks are 32-bit");
static_assert(std::numeric_limits<double>::is_iec559, "the bus carries IEEE-754 doubles");

}  // namespace gyrostab::can
