#include "hil/can/frame_codec.hpp"

#include <bit>
#include <cmath>
#include <cstring>

#include "hil/can/crc8.hpp"

namespace gyrostab::can {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the frame map is little-endian and the codec copies frame fields bytewise");

bool is_frame_signal(const SignalSpec& s) {
  return s.field_offset >= 0;
}

// Raw bits of a little-endian field of up to 64 bits at a byte-aligned position.
std::uint64_t raw_bits(const std::uint8_t* p, std::size_t bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}

void put_bits(std::uint8_t* p, std::uint64_t v, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// The integer value of raw bits of a signal of an integer kind.
double integer_value(const SignalSpec& s, std::uint64_t raw) {
  if (s.kind == SignalKind::kUnsigned) return static_cast<double>(raw);
  const unsigned shift = static_cast<unsigned>(64 - s.bit_length);
  return static_cast<double>(static_cast<std::int64_t>(raw << shift) >> shift);
}

// The physical value of a frame signal (for the range statistics only; the frame gets the raw bits).
double physical(const SignalSpec& s, const std::uint8_t* p, bool& finite) {
  const std::uint64_t raw = raw_bits(p, s.bit_length / 8u);
  finite = true;
  double v = 0.0;
  if (s.kind == SignalKind::kDouble) {
    v = std::bit_cast<double>(raw);
    finite = std::isfinite(v);
  } else {
    v = integer_value(s, raw);
  }
  return v * s.factor + s.offset;
}

double frame_double(const std::uint8_t* frame, const SignalSpec& s) {
  double v;
  std::memcpy(&v, frame + s.field_offset, sizeof v);
  return v;
}

// A frame field onto the wire: its bytes, or the integer its double holds (checked by carriable()).
void write_signal(const SignalSpec& s, const std::uint8_t* frame, std::uint8_t* payload) {
  std::uint8_t* at = payload + s.start_bit / 8u;
  if (!s.integer) {
    std::memcpy(at, frame + s.field_offset, s.bit_length / 8u);
    return;
  }
  std::uint64_t raw = 0;
  integer_raw(s, frame_double(frame, s), raw);
  put_bits(at, raw, s.bit_length / 8u);
}

// The wire onto a frame field: its bytes, or the double of the integer.
void read_signal(const SignalSpec& s, const std::uint8_t* payload, std::uint8_t* frame) {
  const std::uint8_t* at = payload + s.start_bit / 8u;
  if (!s.integer) {
    std::memcpy(frame + s.field_offset, at, s.bit_length / 8u);
    return;
  }
  const double v = integer_value(s, raw_bits(at, s.bit_length / 8u));
  std::memcpy(frame + s.field_offset, &v, sizeof v);
}

}  // namespace

bool integer_raw(const SignalSpec& s, double v, std::uint64_t& raw) {
  if (!s.integer || s.bit_length == 0 || s.bit_length > 32 || s.kind == SignalKind::kDouble) return false;
  const unsigned bits = s.bit_length;
  const double lo = s.kind == SignalKind::kSigned ? -std::ldexp(1.0, static_cast<int>(bits) - 1) : 0.0;
  const double hi = s.kind == SignalKind::kSigned ? std::ldexp(1.0, static_cast<int>(bits) - 1) - 1.0
                                                  : std::ldexp(1.0, static_cast<int>(bits)) - 1.0;
  // NaN fails every comparison; -0.0 would come back as +0.0.
  if (!(v >= lo && v <= hi) || std::trunc(v) != v || (v == 0.0 && std::signbit(v))) return false;
  const auto i = static_cast<std::int64_t>(v);
  raw = static_cast<std::uint64_t>(i) & (bits == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1u);
  return true;
}

std::string_view frame_error_name(FrameError e) {
  switch (e) {
    case FrameError::kNone: return "none";
    case FrameError::kErrorFrame: return "error frame";
    case FrameError::kRemote: return "remote frame";
    case FrameError::kExtendedId: return "29-bit identifier";
    case FrameError::kUnknownId: return "unknown identifier";
    case FrameError::kWrongDirection: return "frame of the other direction";
    case FrameError::kNotFd: return "classic frame on a CAN FD identifier";
    case FrameError::kWrongLength: return "wrong length";
    case FrameError::kBadCrc: return "bad CRC";
    case FrameError::kReservedBits: return "reserved bits or padding not zero";
    case FrameError::kCounterRepeated: return "alive counter repeated (stale frame)";
    case FrameError::kCounterSkipped: return "alive counter skipped (frames lost)";
    case FrameError::kTickMismatch: return "header tick disagrees with its tick tag";
    case FrameError::kLate: return "late (tick already stepped)";
    case FrameError::kCount: break;
  }
  return "?";
}

std::uint8_t frame_crc(std::uint32_t id, const std::uint8_t* data, std::size_t len) {
  const std::uint8_t id_bytes[2] = {static_cast<std::uint8_t>(id & 0xFFu), static_cast<std::uint8_t>((id >> 8) & 0xFFu)};
  std::uint8_t reg = crc8_update(kCrc8Init, id_bytes, 2);
  if (len > 1) reg = crc8_update(reg, data + 1, len - 1);
  return crc8_finish(reg);
}

std::size_t used_bytes(const MessageSpec& m) {
  std::size_t end = kEnvelopeBytes;
  for (const SignalSpec& s : m.signals) {
    const std::size_t e = (static_cast<std::size_t>(s.start_bit) + s.bit_length + 7u) / 8u;
    if (e > end) end = e;
  }
  return end;
}

// --- FrameEncoder ------------------------------------------------------------------------------------------

FrameEncoder::FrameEncoder(const DeviceBus& bus, Direction direction)
    : bus_(bus), direction_(direction), count_(bus.frames(direction)) {}

std::size_t FrameEncoder::encode(const msg::AnySensorFrame& f, std::span<CanFrame> out, FieldViolation* violation) {
  if (direction_ != Direction::kSensor) return 0;
  return encode_bytes(reinterpret_cast<const std::uint8_t*>(&f), out, violation);
}

std::size_t FrameEncoder::encode(const msg::AnyActuatorFrame& f, std::span<CanFrame> out, FieldViolation* violation) {
  if (direction_ != Direction::kActuator) return 0;
  return encode_bytes(reinterpret_cast<const std::uint8_t*>(&f), out, violation);
}

bool FrameEncoder::carriable(const std::uint8_t* frame, FieldViolation* violation) const {
  const auto refuse = [&](FieldViolation::Cause cause, const MessageSpec& m, const SignalSpec& s) {
    // Every value of a device's table is a double in the frame (the header's fields are never refused).
    const bool value = s.field_offset >= static_cast<int>(msg::kFrameHeaderBytes);
    if (violation != nullptr) *violation = FieldViolation{cause, m.name, s.name, value ? frame_double(frame, s) : 0.0, &s};
    return false;
  };
  const std::span<const MessageSpec> messages = bus_.messages();
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const MessageSpec& m = messages[i];
    if (m.direction != direction_) continue;
    for (const SignalSpec& s : m.signals) {
      if (!is_frame_signal(s)) continue;
      if (s.integer) {
        std::uint64_t raw = 0;
        if (!integer_raw(s, frame_double(frame, s), raw)) return refuse(FieldViolation::Cause::kNotInteger, m, s);
      }
    }
  }
  return true;
}

std::size_t FrameEncoder::encode_bytes(const std::uint8_t* frame, std::span<CanFrame> out,
                                       FieldViolation* violation) {
  if (out.size() < count_) return 0;
  // Refuse before encoding anything (the alive counters stay as they are).
  if (!carriable(frame, violation)) return 0;
  // Both generic frames begin with the 64-bit tick.
  const std::uint64_t tick = raw_bits(frame, 8);
  const std::span<const MessageSpec> messages = bus_.messages();
  std::size_t n = 0;
  for (std::size_t idx = 0; idx < messages.size(); ++idx) {
    const MessageSpec& m = messages[idx];
    if (m.direction != direction_) continue;
    CanFrame& c = out[n++];
    c = CanFrame{};
    c.id = m.id;
    c.len = m.length;
    c.flags = kFlagFd | kFlagBrs;
    for (const SignalSpec& s : m.signals)
      if (is_frame_signal(s)) write_signal(s, frame, c.data);
    c.data[kAliveByte] = static_cast<std::uint8_t>(alive_[idx] & kAliveMask);
    alive_[idx] = static_cast<std::uint8_t>((alive_[idx] + 1u) & kAliveMask);
    c.data[kTickTagByte] = static_cast<std::uint8_t>(tick & 0xFFu);
    c.data[kTickTagByte + 1] = static_cast<std::uint8_t>((tick >> 8) & 0xFFu);
    c.data[kCrcByte] = frame_crc(c.id, c.data, c.len);
  }
  return n;
}

// --- SetAssembler ------------------------------------------------------------------------------------------

SetAssembler::SetAssembler(const DeviceBus& bus, Direction direction)
    : bus_(bus), direction_(direction), mask_(bus.mask(direction)), frame_size_(bus.frame_bytes(direction)) {}

FrameError SetAssembler::reject(FrameError e, std::uint32_t id) {
  ++counters_.rejected[static_cast<std::size_t>(e)];
  counters_.last_error = e;
  counters_.last_error_id = id;
  return e;
}

FrameError SetAssembler::check(const CanFrame& f, int& index) {
  if ((f.flags & kFlagError) != 0) return FrameError::kErrorFrame;
  if ((f.flags & kFlagRemote) != 0) return FrameError::kRemote;
  if ((f.flags & kFlagExtended) != 0) return FrameError::kExtendedId;
  index = bus_.index_of(f.id);
  if (index < 0) return FrameError::kUnknownId;
  const MessageSpec& m = bus_.messages()[static_cast<std::size_t>(index)];
  if (m.direction != direction_) return FrameError::kWrongDirection;
  if (!f.fd()) return FrameError::kNotFd;
  if (f.len != m.length) return FrameError::kWrongLength;
  if (frame_crc(f.id, f.data, f.len) != f.data[kCrcByte]) return FrameError::kBadCrc;
  if ((f.data[kAliveByte] & ~kAliveMask) != 0) return FrameError::kReservedBits;
  for (std::size_t i = used_bytes(m); i < f.len; ++i)
    if (f.data[i] != 0) return FrameError::kReservedBits;
  return FrameError::kNone;
}

void SetAssembler::abandon() {
  if (building_) ++counters_.sets_abandoned;
  building_ = false;
  have_ = 0;
}

void SetAssembler::count_values(const MessageSpec& m, const CanFrame& f) {
  for (const SignalSpec& s : m.signals) {
    if (!is_frame_signal(s)) continue;
    bool finite = true;
    const double v = physical(s, f.data + s.start_bit / 8u, finite);
    if (!finite) {
      ++counters_.non_finite_values;
    } else if (v < s.min || v > s.max) {
      ++counters_.out_of_range_values;
    }
  }
}

FrameError SetAssembler::accept(const CanFrame& f) {
  ++counters_.frames;
  int index = -1;
  const FrameError e = check(f, index);
  if (e != FrameError::kNone) return reject(e, f.id);
  const auto idx = static_cast<std::size_t>(index);
  const MessageSpec& m = bus_.messages()[idx];

  // Alive counter: +1 mod 16 per frame on this identifier. The first frame synchronises.
  const std::uint8_t alive = f.data[kAliveByte] & kAliveMask;
  if (alive_seen_[idx]) {
    const std::uint8_t want = static_cast<std::uint8_t>((last_alive_[idx] + 1u) & kAliveMask);
    if (alive == last_alive_[idx]) return reject(FrameError::kCounterRepeated, f.id);
    if (alive != want) {
      last_alive_[idx] = alive;  // resynchronise: the next frame in sequence is accepted again
      return reject(FrameError::kCounterSkipped, f.id);
    }
  }
  alive_seen_[idx] = true;
  last_alive_[idx] = alive;

  const auto tag = static_cast<std::uint16_t>(f.data[kTickTagByte] | (f.data[kTickTagByte + 1] << 8));
  std::uint64_t header_tick = 0;
  if (m.header) {
    for (const SignalSpec& s : m.signals) {
      if (s.field_offset == 0 && !s.integer) header_tick = raw_bits(f.data + s.start_bit / 8u, 8);
    }
    if (static_cast<std::uint16_t>(header_tick & 0xFFFFu) != tag) return reject(FrameError::kTickMismatch, f.id);
    // The last tick taken may come again (a lockstep resend): it is delivered, the caller's order check
    // classifies it as a repeat. Anything older is late.
    if (header_tick + 1 < expected_) {
      if (building_ && building_tag_ == tag) {  // the rest of this late set is dropped with it
        building_ = false;
        have_ = 0;
      }
      return reject(FrameError::kLate, f.id);
    }
  } else {
    // Without its header the frame's tick is known modulo 2^16: late when it lies in the half-window behind
    // the expected tick, except the last tick taken (see above).
    const auto behind = static_cast<std::int16_t>(static_cast<std::uint16_t>(tag - static_cast<std::uint16_t>(expected_)));
    if (behind < -1) return reject(FrameError::kLate, f.id);
  }

  if (building_ && (building_tag_ != tag || (have_ & (1u << idx)) != 0)) abandon();
  if (!building_) {
    building_ = true;
    building_tag_ = tag;
    have_ = 0;
    building_bytes_.fill(0);
  }
  for (const SignalSpec& s : m.signals)
    if (is_frame_signal(s)) read_signal(s, f.data, building_bytes_.data());
  if (m.header) building_tick_ = header_tick;
  building_frames_[idx] = f;
  have_ |= 1u << idx;
  ++counters_.accepted;
  count_values(m, f);

  if (have_ == mask_) {
    ready_ = true;
    ready_tick_ = building_tick_;
    ready_bytes_ = building_bytes_;
    ready_frames_ = building_frames_;
    ++counters_.sets_completed;
    building_ = false;
    have_ = 0;
  }
  return FrameError::kNone;
}

bool SetAssembler::take_bytes(std::uint8_t* out, std::size_t size, Direction d) {
  if (!ready_ || d != direction_ || size < frame_size_) return false;
  std::memcpy(out, ready_bytes_.data(), frame_size_);
  std::memset(out + frame_size_, 0, size - frame_size_);
  ready_ = false;
  if (ready_tick_ + 1 > expected_) expected_ = ready_tick_ + 1;
  return true;
}

std::size_t SetAssembler::ready_frames(std::span<CanFrame> out) const {
  if (!ready_) return 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < bus_.messages().size() && n < out.size(); ++i)
    if ((mask_ & (1u << i)) != 0) out[n++] = ready_frames_[i];
  return n;
}

bool SetAssembler::take(msg::AnySensorFrame& out) {
  return take_bytes(reinterpret_cast<std::uint8_t*>(&out), sizeof(out), Direction::kSensor);
}

bool SetAssembler::take(msg::AnyActuatorFrame& out) {
  return take_bytes(reinterpret_cast<std::uint8_t*>(&out), sizeof(out), Direction::kActuator);
}

void SetAssembler::skip_through(std::uint64_t tick) {
  if (tick + 1 > expected_) expected_ = tick + 1;
  if (ready_ && ready_tick_ < expected_) ready_ = false;
}

}  // namespace gyrostab::can
