#include "hil/can/frame_codec.hpp"

#include <bit>
#include <cmath>
#include <cstring>

#include "hil/can/crc8.hpp"

namespace gyrostab::can {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the frame map is little-endian and the codec copies contract fields bytewise");

std::size_t contract_size(Direction d) {
  return d == Direction::kSensor ? sizeof(msg::SensorFrame) : sizeof(msg::ActuatorFrame);
}

bool is_contract_signal(const SignalSpec& s) {
  return s.field_offset >= 0;
}

// Raw bits of a little-endian field of up to 64 bits at a byte-aligned position.
std::uint64_t raw_bits(const std::uint8_t* p, std::size_t bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}

// The physical value of a contract signal (for the range statistics only; the contract gets the raw bits).
double physical(const SignalSpec& s, const std::uint8_t* p, bool& finite) {
  const std::size_t bytes = s.bit_length / 8u;
  const std::uint64_t raw = raw_bits(p, bytes);
  double v = 0.0;
  finite = true;
  switch (s.kind) {
    case SignalKind::kDouble: v = std::bit_cast<double>(raw); finite = std::isfinite(v); break;
    case SignalKind::kUnsigned: v = static_cast<double>(raw); break;
    case SignalKind::kSigned: {
      const unsigned shift = static_cast<unsigned>(64 - s.bit_length);
      v = static_cast<double>(static_cast<std::int64_t>(raw << shift) >> shift);
      break;
    }
  }
  return v * s.factor + s.offset;
}

}  // namespace

std::string_view frame_error_name(FrameError e) {
  switch (e) {
    case FrameError::kNone: return "none";
    case FrameError::kErrorFrame: return "error frame";
    case FrameError::kRemote: return "remote frame";
    case FrameError::kExtendedId: return "29-bit identifier";
    case FrameError::kUnknownId: return "unknown identifier";
    case FrameError::kWrongDirection: return "frame of the other direction";
    case FrameError::kAbsentNode: return "frame of a node the device does not have";
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

FrameEncoder::FrameEncoder(Direction direction, NodeSet nodes) : direction_(direction), nodes_(nodes) {
  for (const MessageSpec& m : kMessages)
    if (m.direction == direction && message_present(m, nodes)) ++count_;
}

std::size_t FrameEncoder::encode(const msg::AnySensorFrame& f, std::span<CanFrame> out, FieldViolation* violation) {
  if (direction_ != Direction::kSensor) return 0;
  return encode_bytes(reinterpret_cast<const std::uint8_t*>(&f), out, violation);
}

std::size_t FrameEncoder::encode(const msg::AnyActuatorFrame& f, std::span<CanFrame> out, FieldViolation* violation) {
  if (direction_ != Direction::kActuator) return 0;
  return encode_bytes(reinterpret_cast<const std::uint8_t*>(&f), out, violation);
}

std::size_t FrameEncoder::encode_bytes(const std::uint8_t* contract, std::span<CanFrame> out,
                                       FieldViolation* violation) {
  if (out.size() < count_) return 0;
  // Both contract structs begin with the 64-bit tick.
  const std::uint64_t tick = raw_bits(contract, 8);
  // Refuse before sending anything: a value in a field no node of this device carries.
  for (const MessageSpec& m : kMessages) {
    if (m.direction != direction_ || message_present(m, nodes_)) continue;
    for (const SignalSpec& s : m.signals) {
      if (!is_contract_signal(s)) continue;
      const std::uint8_t* p = contract + s.field_offset;
      for (std::size_t i = 0; i < s.bit_length / 8u; ++i) {
        if (p[i] != 0) {
          if (violation != nullptr) *violation = FieldViolation{m.name, s.name};
          return 0;
        }
      }
    }
  }
  std::size_t n = 0;
  for (std::size_t idx = 0; idx < kMessageCount; ++idx) {
    const MessageSpec& m = kMessages[idx];
    if (m.direction != direction_ || !message_present(m, nodes_)) continue;
    CanFrame& c = out[n++];
    c = CanFrame{};
    c.id = m.id;
    c.len = m.length;
    c.flags = kFlagFd | kFlagBrs;
    for (const SignalSpec& s : m.signals) {
      if (!is_contract_signal(s)) continue;
      std::memcpy(c.data + s.start_bit / 8u, contract + s.field_offset, s.bit_length / 8u);
    }
    c.data[kAliveByte] = static_cast<std::uint8_t>(alive_[idx] & kAliveMask);
    alive_[idx] = static_cast<std::uint8_t>((alive_[idx] + 1u) & kAliveMask);
    c.data[kTickTagByte] = static_cast<std::uint8_t>(tick & 0xFFu);
    c.data[kTickTagByte + 1] = static_cast<std::uint8_t>((tick >> 8) & 0xFFu);
    c.data[kCrcByte] = frame_crc(c.id, c.data, c.len);
  }
  return n;
}

// --- SetAssembler ------------------------------------------------------------------------------------------

SetAssembler::SetAssembler(Direction direction, NodeSet nodes)
    : direction_(direction), nodes_(nodes), mask_(can::message_mask(direction, nodes)),
      contract_size_(contract_size(direction)) {}

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
  index = message_index(f.id);
  if (index < 0) return FrameError::kUnknownId;
  const MessageSpec& m = kMessages[static_cast<std::size_t>(index)];
  if (m.direction != direction_) return FrameError::kWrongDirection;
  if (!message_present(m, nodes_)) return FrameError::kAbsentNode;
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
    if (!is_contract_signal(s)) continue;
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
  const MessageSpec& m = kMessages[idx];

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
      if (s.field_offset == 0) header_tick = raw_bits(f.data + s.start_bit / 8u, 8);
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
  for (const SignalSpec& s : m.signals) {
    if (!is_contract_signal(s)) continue;
    std::memcpy(building_bytes_.data() + s.field_offset, f.data + s.start_bit / 8u, s.bit_length / 8u);
  }
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
  if (!ready_ || d != direction_ || size < contract_size_) return false;
  std::memcpy(out, ready_bytes_.data(), contract_size_);
  std::memset(out + contract_size_, 0, size - contract_size_);
  ready_ = false;
  if (ready_tick_ + 1 > expected_) expected_ = ready_tick_ + 1;
  return true;
}

std::size_t SetAssembler::ready_frames(std::span<CanFrame> out) const {
  if (!ready_) return 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < kMessageCount && n < out.size(); ++i)
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
