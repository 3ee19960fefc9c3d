// The frame codec over lcm-gen's generated types. The size and fingerprint are checked here, before the
// generated decoder runs, so a rejection says why (the generated decode() only returns -1).
#include "hil/lcm/frame_codec.hpp"

#include <cstring>

#include "gyrostab_msg/actuator_frame_t.hpp"
#include "gyrostab_msg/sensor_frame_t.hpp"

namespace gyrostab::hil {
namespace {

// The generated classes hold exactly the wire fields (no pointers, no strings): a field added to a .lcm file
// without updating kSensorEncodedSize / kActuatorEncodedSize fails here; the unit test compares the constants
// with the generated getEncodedSize().
static_assert(sizeof(gyrostab_msg::sensor_frame_t) == 248,
              "sensor_frame_t changed: update kSensorEncodedSize");
static_assert(sizeof(gyrostab_msg::actuator_frame_t) == 144,
              "actuator_frame_t changed: update kActuatorEncodedSize");

template <std::size_t N, class T>
void copy_array(T (&dst)[N], const T (&src)[N]) {
  std::memcpy(dst, src, sizeof(dst));
}

void to_wire(const msg::SensorFrame& f, std::int64_t sim_time_us, gyrostab_msg::sensor_frame_t& w) {
  // C++20: unsigned → signed of the same width is modulo 2^n, i.e. the bit pattern is kept.
  w.tick = static_cast<std::int64_t>(f.tick);
  w.time_ns = f.time_ns;
  w.sample_time_ns = f.sample_time_ns;
  w.sequence = static_cast<std::int32_t>(f.sequence);
  w.status = static_cast<std::int32_t>(f.status);
  copy_array(w.carrier_angle_rad, f.carrier_angle_rad);
  copy_array(w.carrier_rate_rad_s, f.carrier_rate_rad_s);
  copy_array(w.gimbal_angle_rad, f.gimbal_angle_rad);
  copy_array(w.gimbal_rate_rad_s, f.gimbal_rate_rad_s);
  copy_array(w.motor_current_A, f.motor_current_A);
  w.rotor_speed_rad_s = f.rotor_speed_rad_s;
  copy_array(w.encoder_count, f.encoder_count);
  copy_array(w.cluster_gimbal_angle_rad, f.cluster_gimbal_angle_rad);
  copy_array(w.cluster_gimbal_rate_rad_s, f.cluster_gimbal_rate_rad_s);
  w.sim_time_us = sim_time_us;
}

void from_wire(const gyrostab_msg::sensor_frame_t& w, msg::SensorFrame& f) {
  f.tick = static_cast<std::uint64_t>(w.tick);
  f.time_ns = w.time_ns;
  f.sample_time_ns = w.sample_time_ns;
  f.sequence = static_cast<std::uint32_t>(w.sequence);
  f.status = static_cast<std::uint32_t>(w.status);
  copy_array(f.carrier_angle_rad, w.carrier_angle_rad);
  copy_array(f.carrier_rate_rad_s, w.carrier_rate_rad_s);
  copy_array(f.gimbal_angle_rad, w.gimbal_angle_rad);
  copy_array(f.gimbal_rate_rad_s, w.gimbal_rate_rad_s);
  copy_array(f.motor_current_A, w.motor_current_A);
  f.rotor_speed_rad_s = w.rotor_speed_rad_s;
  copy_array(f.encoder_count, w.encoder_count);
  copy_array(f.cluster_gimbal_angle_rad, w.cluster_gimbal_angle_rad);
  copy_array(f.cluster_gimbal_rate_rad_s, w.cluster_gimbal_rate_rad_s);
}

void to_wire(const msg::ActuatorFrame& f, std::int64_t sim_time_us, gyrostab_msg::actuator_frame_t& w) {
  w.tick = static_cast<std::int64_t>(f.tick);
  w.time_ns = f.time_ns;
  w.sensor_tick = static_cast<std::int64_t>(f.sensor_tick);
  w.sequence = static_cast<std::int32_t>(f.sequence);
  w.status = static_cast<std::int32_t>(f.status);
  copy_array(w.gimbal_torque_Nm, f.gimbal_torque_Nm);
  copy_array(w.motor_voltage_V, f.motor_voltage_V);
  w.precession_brake = f.precession_brake;
  copy_array(w.cluster_rate_command_rad_s, f.cluster_rate_command_rad_s);
  w.sim_time_us = sim_time_us;
}

void from_wire(const gyrostab_msg::actuator_frame_t& w, msg::ActuatorFrame& f) {
  f.tick = static_cast<std::uint64_t>(w.tick);
  f.time_ns = w.time_ns;
  f.sensor_tick = static_cast<std::uint64_t>(w.sensor_tick);
  f.sequence = static_cast<std::uint32_t>(w.sequence);
  f.status = static_cast<std::uint32_t>(w.status);
  copy_array(f.gimbal_torque_Nm, w.gimbal_torque_Nm);
  copy_array(f.motor_voltage_V, w.motor_voltage_V);
  f.precession_brake = w.precession_brake;
  copy_array(f.cluster_rate_command_rad_s, w.cluster_rate_command_rad_s);
}

template <class Wire>
void envelope_to_wire(const LinkEnvelope& e, Wire& w) {
  w.sender = static_cast<std::int64_t>(e.sender);
  w.session = static_cast<std::int64_t>(e.session);
  w.freshness = static_cast<std::int64_t>(e.freshness);
  w.mac = static_cast<std::int64_t>(e.mac);
}

template <class Wire>
LinkEnvelope envelope_from_wire(const Wire& w) {
  return {static_cast<std::uint64_t>(w.sender), static_cast<std::uint64_t>(w.session),
          static_cast<std::uint64_t>(w.freshness), static_cast<std::uint64_t>(w.mac)};
}

template <class Wire, class Frame>
int encode_as(const Frame& f, std::int64_t sim_time_us, std::uint8_t* buf, int capacity, int expected,
              const LinkEnvelope& envelope) {
  if (buf == nullptr || capacity < expected) return -1;
  Wire w{};
  to_wire(f, sim_time_us, w);
  envelope_to_wire(envelope, w);
  const int n = w.encode(buf, 0, capacity);
  return n == expected ? n : -1;
}

template <class Wire, class Frame>
DecodeError decode_as(const void* data, int size, Frame& out, std::int64_t* sim_time_us, LinkEnvelope* envelope,
                      int expected) {
  if (data == nullptr || size != expected) return DecodeError::kWrongSize;
  // The fingerprint is the first 8 bytes, big-endian (LCM marshalling).
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::uint64_t fingerprint = 0;
  for (int i = 0; i < 8; ++i) fingerprint = (fingerprint << 8) | bytes[i];
  if (fingerprint != static_cast<std::uint64_t>(Wire::getHash())) return DecodeError::kWrongFingerprint;
  Wire w{};
  if (w._decodeNoHash(data, 8, size - 8) != size - 8) return DecodeError::kMalformed;
  from_wire(w, out);
  if (sim_time_us != nullptr) *sim_time_us = w.sim_time_us;
  if (envelope != nullptr) *envelope = envelope_from_wire(w);
  return DecodeError::kOk;
}

}  // namespace

int encode(const msg::SensorFrame& f, std::int64_t sim_time_us, std::uint8_t* buf, int capacity,
           const LinkEnvelope& envelope) {
  return encode_as<gyrostab_msg::sensor_frame_t>(f, sim_time_us, buf, capacity, kSensorEncodedSize, envelope);
}

int encode(const msg::ActuatorFrame& f, std::int64_t sim_time_us, std::uint8_t* buf, int capacity,
           const LinkEnvelope& envelope) {
  return encode_as<gyrostab_msg::actuator_frame_t>(f, sim_time_us, buf, capacity, kActuatorEncodedSize, envelope);
}

void write_envelope(std::uint8_t* buf, int size, const LinkEnvelope& e) {
  // The envelope is the last four int64 fields, big-endian (LCM marshalling).
  const std::uint64_t v[4] = {e.sender, e.session, e.freshness, e.mac};
  std::uint8_t* p = buf + size - kEnvelopeEncodedSize;
  for (const std::uint64_t x : v) {
    for (int i = 7; i >= 0; --i) *p++ = static_cast<std::uint8_t>(x >> (8 * i));
  }
}

const char* describe(DecodeError e) {
  switch (e) {
    case DecodeError::kOk:
      return "ok";
    case DecodeError::kWrongSize:
      return "wrong size";
    case DecodeError::kWrongFingerprint:
      return "wrong fingerprint";
    case DecodeError::kMalformed:
      return "malformed";
  }
  return "unknown decode error";
}

DecodeError decode(const void* data, int size, msg::SensorFrame& out, std::int64_t* sim_time_us,
                   LinkEnvelope* envelope) {
  return decode_as<gyrostab_msg::sensor_frame_t>(data, size, out, sim_time_us, envelope, kSensorEncodedSize);
}

DecodeError decode(const void* data, int size, msg::ActuatorFrame& out, std::int64_t* sim_time_us,
                   LinkEnvelope* envelope) {
  return decode_as<gyrostab_msg::actuator_frame_t>(data, size, out, sim_time_us, envelope, kActuatorEncodedSize);
}

}  // namespace gyrostab::hil
