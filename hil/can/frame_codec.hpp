// Encoder and decoder between a device's frames (msg::AnySensorFrame, msg::AnyActuatorFrame with its
// msg::DeviceSignals) and the CAN FD frames of its map (frame_map.hpp DeviceBus: the map generated from its
// signal table, gyrostab_signals/<device>_can.hpp). Nothing here knows a device.
//
// FrameEncoder: one generic frame → the frames of its direction on the device's bus, header last, each with
// its envelope (CRC-8, alive counter, tick tag). Refuses (returns 0, nothing encoded, no counter advanced) a
// frame with a value the bus cannot carry exactly: a value that rides as an integer (the table's
// can = "int32") but is not one of that type (a fraction, out of range, NaN, -0.0). Such a value would be lost or changed on the bus, and
// lockstep over CAN would silently stop being bit-identical to in-process.
//
// SetAssembler: received frames → complete generic frames, one per tick. Each frame is checked in this order
// and rejected with the first failing check (FrameError), counted per cause in RxCounters:
//   error frame, remote frame, 29-bit id, unknown id, other direction, classic instead of FD,
//   wrong length, CRC, reserved bits / padding not zero, alive counter repeated (stale) or skipped (frames lost:
//   the counter then resynchronises on this frame, so one loss rejects one frame), header tick ≠ tick tag,
//   late (a tick the receiver has already stepped past).
// A tick's set completes when every frame of the direction's message mask has arrived with the same tick tag;
// frames of a newer tick abandon an incomplete set (counted). What the receiver does with a tick that has no
// complete set — step the firmware with no sensor frame (fault monitor: hold, then safe state), or hold the
// last command at a drive — is the loop's business (docs/can.md).
// Accepted values are passed on bit for bit (an integer signal as the double of that integer); non-finite
// doubles and values outside the map's range are only counted here, because the firmware's fault monitor must
// make the same decision as it does in-process.
//
// Resources: fixed-size members, no heap, no exceptions, no I/O (firmware-grade; also the fuzz target's
// surface, tests/fuzz/can_decoder_fuzz.cpp). accept() is O(frame length + signals of the message).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "firmware/msg/any_frame.hpp"
#include "hil/can/can_frame.hpp"
#include "hil/can/frame_map.hpp"

namespace gyrostab::can {

enum class FrameError : std::uint8_t {
  kNone,
  kErrorFrame,       // an error frame reported by the CAN controller
  kRemote,           // a remote (RTR) frame: this bus never uses them
  kExtendedId,       // a 29-bit identifier: this bus uses 11-bit ones
  kUnknownId,        // an identifier not in the device's map
  kWrongDirection,   // a frame of the map this receiver does not take (e.g. a command at the controller)
  kNotFd,            // a classic frame on an identifier of the map (all are CAN FD)
  kWrongLength,      // a length other than the map's
  kBadCrc,           // the CRC-8 does not match
  kReservedBits,     // upper nibble of the alive byte or a padding byte not zero
  kCounterRepeated,  // the alive counter did not advance: a stale (repeated) frame
  kCounterSkipped,   // the alive counter jumped: frames were lost
  kTickMismatch,     // the header's full tick disagrees with its tick tag
  kLate,             // the frame's tick is before the one the receiver expects (already stepped)
  kCount
};
inline constexpr std::size_t kFrameErrorCount = static_cast<std::size_t>(FrameError::kCount);
std::string_view frame_error_name(FrameError e);

struct RxCounters {
  std::uint64_t frames{0};                                // frames offered to accept() [-]
  std::uint64_t accepted{0};                              // frames that passed every check [-]
  std::array<std::uint64_t, kFrameErrorCount> rejected{};  // rejected frames by cause (index = FrameError) [-]
  std::uint64_t sets_completed{0};                        // ticks whose set completed [-]
  std::uint64_t sets_abandoned{0};                        // incomplete sets dropped for a newer tick or a late header [-]
  std::uint64_t non_finite_values{0};                     // accepted doubles that are NaN or ±Inf (passed on) [-]
  std::uint64_t out_of_range_values{0};                   // accepted values outside the map's range (passed on) [-]
  FrameError last_error{FrameError::kNone};               // the latest rejection's cause
  std::uint32_t last_error_id{0};                         // and its identifier

  std::uint64_t rejected_total() const {
    std::uint64_t n = 0;
    for (std::uint64_t r : rejected) n += r;
    return n;
  }
  std::uint64_t count(FrameError e) const { return rejected[static_cast<std::size_t>(e)]; }
};

// A value of a frame the bus cannot carry exactly (FrameEncoder::encode refused the frame).
struct FieldViolation {
  enum class Cause : std::uint8_t {
    kNotInteger,  // a value that rides as an integer but is not an integer of its type (or is -0.0)
  };
  Cause cause{Cause::kNotInteger};
  std::string_view message;  // the frame that carries it
  std::string_view signal;   // the signal
  double value{0.0};
  const SignalSpec* spec{nullptr};
};

class FrameEncoder {
 public:
  FrameEncoder(const DeviceBus& bus, Direction direction);

  // The frames of one sensor (kSensor) or actuator (kActuator) frame into out (capacity ≥ frames_per_set()),
  // header last. Returns the number written, or 0 (and *violation) when a value cannot travel exactly.
  std::size_t encode(const msg::AnySensorFrame& f, std::span<CanFrame> out, FieldViolation* violation = nullptr);
  std::size_t encode(const msg::AnyActuatorFrame& f, std::span<CanFrame> out, FieldViolation* violation = nullptr);
  // A device's typed frame (its bytes are the generic frame's first ones).
  template <msg::TypedFrame Frame>
  std::size_t encode(const Frame& f, std::span<CanFrame> out, FieldViolation* violation = nullptr) {
    return encode(msg::any_of(f), out, violation);
  }

  std::size_t frames_per_set() const { return count_; }
  Direction direction() const { return direction_; }

 private:
  std::size_t encode_bytes(const std::uint8_t* frame, std::span<CanFrame> out, FieldViolation* violation);
  bool carriable(const std::uint8_t* frame, FieldViolation* violation) const;

  DeviceBus bus_;
  Direction direction_;
  std::size_t count_{0};
  std::array<std::uint8_t, kMaxMessages> alive_{};
};

class SetAssembler {
 public:
  SetAssembler(const DeviceBus& bus, Direction direction);

  // Check one received frame and add it to its tick's set. kNone: accepted (ready() may now be true).
  FrameError accept(const CanFrame& f);

  // A completed set waits here until taken; a later completion replaces it (the loop takes each at once).
  bool ready() const { return ready_; }
  std::uint64_t ready_tick() const { return ready_tick_; }
  // Copy the completed set out and clear ready(); the receiver then expects ready_tick() + 1. The overload
  // must match the direction (sensor sets for kSensor); false when nothing is ready or it does not.
  bool take(msg::AnySensorFrame& out);
  bool take(msg::AnyActuatorFrame& out);
  template <msg::TypedFrame Frame>
  bool take(Frame& out) {
    decltype(msg::any_of(out)) any{};
    if (!take(any)) return false;
    msg::from_any(any, out);
    return true;
  }
  // The frames of the completed set as received, in map order (the header last): what the link envelope's MAC
  // covers (link_seal.hpp). Returns their number (0 when nothing is ready).
  std::size_t ready_frames(std::span<CanFrame> out) const;
  // Clears ready() without taking the set (the link refused it): the receiver still expects the same tick.
  void drop_ready() { ready_ = false; }

  // The loop stepped tick `tick` without a set (timeout): frames of ticks before `tick + 1` are late from now.
  void skip_through(std::uint64_t tick);
  std::uint64_t expected_tick() const { return expected_; }

  const RxCounters& counters() const { return counters_; }
  std::uint32_t message_mask() const { return mask_; }
  Direction direction() const { return direction_; }

 private:
  FrameError check(const CanFrame& f, int& index);
  FrameError reject(FrameError e, std::uint32_t id);
  void abandon();
  void count_values(const MessageSpec& m, const CanFrame& f);
  bool take_bytes(std::uint8_t* out, std::size_t size, Direction d);

  DeviceBus bus_;
  Direction direction_;
  std::uint32_t mask_;
  std::size_t frame_size_;  // bytes of the generic frame the device's values fill
  std::uint64_t expected_{0};
  std::array<std::uint8_t, kMaxMessages> last_alive_{};
  std::array<bool, kMaxMessages> alive_seen_{};
  // Set under construction.
  bool building_{false};
  std::uint16_t building_tag_{0};
  std::uint32_t have_{0};
  std::uint64_t building_tick_{0};  // valid once the header is in (have_ has the header's bit)
  alignas(8) std::array<std::uint8_t, sizeof(msg::AnySensorFrame)> building_bytes_{};
  // Completed set.
  bool ready_{false};
  std::uint64_t ready_tick_{0};
  alignas(8) std::array<std::uint8_t, sizeof(msg::AnySensorFrame)> ready_bytes_{};
  std::array<CanFrame, kMaxMessages> building_frames_{};  // by message index
  std::array<CanFrame, kMaxMessages> ready_frames_{};
  RxCounters counters_{};
};

// CRC-8 of a frame as the envelope defines it (identifier low byte, high byte, then data[1..len-1]).
std::uint8_t frame_crc(std::uint32_t id, const std::uint8_t* data, std::size_t len);

// The number of payload bytes a message's signals use (the rest up to its length is zero padding).
std::size_t used_bytes(const MessageSpec& m);

// The raw bits of an integer signal (SignalSpec::integer) for the double it carries; false when the value is
// not an integer of the signal's type (a fraction, out of its range, not finite, -0.0): it cannot travel exactly.
bool integer_raw(const SignalSpec& s, double v, std::uint64_t& raw);

static_assert(sizeof(msg::AnySensorFrame) >= sizeof(msg::AnyActuatorFrame));

}  // namespace gyrostab::can
