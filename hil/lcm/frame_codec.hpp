// A device's frames ⇄ LCM wire bytes, for any device: the layout comes from the device's signal table
// (msg::DeviceSignals, generated from tools/devices/<device>/<device>_signals.toml together with the LCM types
// `gyrostab_msg.<device>_sensor_t` / `_actuator_t` that lcm-gen compiles; docs/protocol.md).
//
// Wire layout (LCM marshalling of those types): the 8-byte big-endian type fingerprint; the header (tick,
// time_ns, sample_time_ns or sensor_tick as int64; sequence, status as int32); the device's signals as 64-bit
// IEEE-754 doubles, big-endian, in table order (an array element by element); sim_time_us; the link's envelope
// (sender, session, freshness, mac as int64), preceded by the sender's scene hash (`scene`). Doubles travel as their bit patterns, so every value — NaN
// payloads and signed zeros included — survives a round trip bit for bit; the receiver, not the codec, decides
// what is acceptable (hil/link/actuator_frame_check.hpp, the fault monitor). Unsigned header fields travel as
// the signed LCM type of the same width, modulo 2^n. tests/unit/lcm_codec_test.cpp checks the bytes against
// lcm-gen's own encoder for every device.
//
// Allocation-free: encodes into the caller's buffer, decodes into the caller's frame.
#pragma once

#include <cstdint>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/signal_spec.hpp"
#include "hil/link/link_guard.hpp"

namespace gyrostab::hil {

inline constexpr int kEnvelopeEncodedSize = 4 * 8;  // sender .. mac
// Fingerprint, header, sim_time_us, the scene hash and the envelope: what every frame carries besides its
// signals.
inline constexpr int kFixedEncodedSize = 8 + 3 * 8 + 2 * 4 + 8 + 8 + kEnvelopeEncodedSize;  // 88
constexpr int encoded_size(std::size_t signals) { return kFixedEncodedSize + 8 * static_cast<int>(signals); }
inline int sensor_encoded_size(const msg::DeviceSignals& d) { return encoded_size(d.sensors.size()); }
inline int actuator_encoded_size(const msg::DeviceSignals& d) { return encoded_size(d.commands.size()); }
// The largest frame any device can have (a transmit buffer for every device).
inline constexpr int kMaxEncodedSize = encoded_size(msg::kMaxSensorSignals);
// The bytes a frame's MAC covers: everything before `session` (the session and the freshness value enter the
// authenticator's header, the MAC is what it makes).
constexpr int mac_covered_bytes(int encoded_size) { return encoded_size - 3 * 8; }
// The data ids of the two directions (hil/link/link_guard.hpp): what a MAC says a frame is for.
inline constexpr std::uint32_t kSensorDataId = 0x53454E53;    // "SENS"
inline constexpr std::uint32_t kActuatorDataId = 0x41435455;  // "ACTU"

// Encodes `f` (the device's first signals, the simulated time of its tick and the link's envelope) into
// buf[0, capacity). Returns the bytes written or -1 if capacity is too small.
int encode(const msg::AnySensorFrame& f, const msg::DeviceSignals& device, std::int64_t sim_time_us,
           std::uint8_t* buf, int capacity, const LinkEnvelope& envelope = {});
int encode(const msg::AnyActuatorFrame& f, const msg::DeviceSignals& device, std::int64_t sim_time_us,
           std::uint8_t* buf, int capacity, const LinkEnvelope& envelope = {});
// Overwrites the envelope of an encoded frame (the endpoint secures a frame after encoding it).
void write_envelope(std::uint8_t* buf, int size, const LinkEnvelope& envelope);

enum class DecodeError {
  kOk,
  kWrongSize,         // size differs from the type's encoded size (truncated, padded, another type)
  kWrongFingerprint,  // the first 8 bytes are not this type's fingerprint (another type, device or version)
  kMalformed,         // reserved for a body the codec cannot read (every fixed-size body of the right size can)
};
const char* describe(DecodeError e);

// Decodes exactly one message of `size` bytes. On anything but kOk, the outputs are unchanged; on kOk the
// frame's signals past the device's are zero.
DecodeError decode(const void* data, int size, const msg::DeviceSignals& device, msg::AnySensorFrame& out,
                   std::int64_t* sim_time_us = nullptr, LinkEnvelope* envelope = nullptr);
DecodeError decode(const void* data, int size, const msg::DeviceSignals& device, msg::AnyActuatorFrame& out,
                   std::int64_t* sim_time_us = nullptr, LinkEnvelope* envelope = nullptr);

}  // namespace gyrostab::hil
