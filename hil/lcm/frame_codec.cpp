// LCM marshalling of a device's frames, written out field by field: every field is a fixed-size big-endian
// integer or double, so the layout is the header, the signals and the trailer one after another (lcm-gen's
// encoder produces the same bytes: tests/unit/lcm_codec_test.cpp).
#include "hil/lcm/frame_codec.hpp"

#include <bit>
#include <cstring>

namespace gyrostab::hil {
namespace {

class Writer {
 public:
  explicit Writer(std::uint8_t* p) : p_(p) {}
  void u64(std::uint64_t v) {
    for (int i = 7; i >= 0; --i) *p_++ = static_cast<std::uint8_t>(v >> (8 * i));
  }
  void u32(std::uint32_t v) {
    for (int i = 3; i >= 0; --i) *p_++ = static_cast<std::uint8_t>(v >> (8 * i));
  }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }

 private:
  std::uint8_t* p_;
};

class Reader {
 public:
  explicit Reader(const std::uint8_t* p) : p_(p) {}
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = (v << 8) | *p_++;
    return v;
  }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | *p_++;
    return v;
  }
  double f64() { return std::bit_cast<double>(u64()); }

 private:
  const std::uint8_t* p_;
};

template <class Frame>
int encode_frame(const Frame& f, std::uint64_t fingerprint, std::size_t n, std::uint64_t third,
                 std::int64_t sim_time_us, std::uint8_t* buf, int capacity, const LinkEnvelope& e) {
  const int size = encoded_size(n);
  if (buf == nullptr || capacity < size || n > sizeof(f.signal) / sizeof(double)) return -1;
  Writer w(buf);
  w.u64(fingerprint);
  w.u64(f.tick);
  w.u64(static_cast<std::uint64_t>(f.time_ns));
  w.u64(third);
  w.u32(f.sequence);
  w.u32(f.status);
  for (std::size_t i = 0; i < n; ++i) w.f64(f.signal[i]);
  w.u64(static_cast<std::uint64_t>(sim_time_us));
  w.u64(e.scene);
  w.u64(e.sender);
  w.u64(e.session);
  w.u64(e.freshness);
  w.u64(e.mac);
  return size;
}

// Checks size and fingerprint, then reads the header (the third field returned) and the signals into `f`.
template <class Frame>
DecodeError decode_frame(const void* data, int size, std::uint64_t fingerprint, std::size_t n, Frame& out,
                         std::uint64_t& third, std::int64_t* sim_time_us, LinkEnvelope* envelope) {
  if (data == nullptr || n > sizeof(out.signal) / sizeof(double) || size != encoded_size(n)) {
    return DecodeError::kWrongSize;
  }
  Reader r(static_cast<const std::uint8_t*>(data));
  if (r.u64() != fingerprint) return DecodeError::kWrongFingerprint;
  Frame f{};
  f.tick = r.u64();
  f.time_ns = static_cast<std::int64_t>(r.u64());
  third = r.u64();
  f.sequence = r.u32();
  f.status = r.u32();
  for (std::size_t i = 0; i < n; ++i) f.signal[i] = r.f64();
  const auto t = static_cast<std::int64_t>(r.u64());
  LinkEnvelope e;
  e.scene = r.u64();
  e.sender = r.u64();
  e.session = r.u64();
  e.freshness = r.u64();
  e.mac = r.u64();
  out = f;
  if (sim_time_us != nullptr) *sim_time_us = t;
  if (envelope != nullptr) *envelope = e;
  return DecodeError::kOk;
}

}  // namespace

int encode(const msg::AnySensorFrame& f, const msg::DeviceSignals& d, std::int64_t sim_time_us, std::uint8_t* buf,
           int capacity, const LinkEnvelope& envelope) {
  return encode_frame(f, d.lcm_sensor_fingerprint, d.sensors.size(), static_cast<std::uint64_t>(f.sample_time_ns),
                      sim_time_us, buf, capacity, envelope);
}

int encode(const msg::AnyActuatorFrame& f, const msg::DeviceSignals& d, std::int64_t sim_time_us,
           std::uint8_t* buf, int capacity, const LinkEnvelope& envelope) {
  return encode_frame(f, d.lcm_actuator_fingerprint, d.commands.size(), f.sensor_tick, sim_time_us, buf, capacity,
                      envelope);
}

void write_envelope(std::uint8_t* buf, int size, const LinkEnvelope& e) {
  Writer w(buf + size - kEnvelopeEncodedSize);
  w.u64(e.sender);
  w.u64(e.session);
  w.u64(e.freshness);
  w.u64(e.mac);
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

DecodeError decode(const void* data, int size, const msg::DeviceSignals& d, msg::AnySensorFrame& out,
                   std::int64_t* sim_time_us, LinkEnvelope* envelope) {
  std::uint64_t third = 0;
  msg::AnySensorFrame f{};
  const DecodeError e =
      decode_frame(data, size, d.lcm_sensor_fingerprint, d.sensors.size(), f, third, sim_time_us, envelope);
  if (e != DecodeError::kOk) return e;
  f.sample_time_ns = static_cast<std::int64_t>(third);
  out = f;
  return e;
}

DecodeError decode(const void* data, int size, const msg::DeviceSignals& d, msg::AnyActuatorFrame& out,
                   std::int64_t* sim_time_us, LinkEnvelope* envelope) {
  std::uint64_t third = 0;
  msg::AnyActuatorFrame f{};
  const DecodeError e =
      decode_frame(data, size, d.lcm_actuator_fingerprint, d.commands.size(), f, third, sim_time_us, envelope);
  if (e != DecodeError::kOk) return e;
  f.sensor_tick = third;
  out = f;
  return e;
}

}  // namespace gyrostab::hil
