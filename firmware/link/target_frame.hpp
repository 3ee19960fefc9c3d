// The frames of the target link: the plant (host) ⇄ the controller image on the processor (emulated or real),
// over the board's UART or any byte stream (docs/pil.md). Target code: no heap, no exceptions, no I/O; the
// host's end (hil/target/) uses the same encoder and decoder, so both ends agree by construction.
//
// On the wire each frame is COBS-encoded (firmware/link/cobs.hpp) and ends with one 0x00 byte. Decoded:
//   byte  0      kind (TargetFrameKind)
//   byte  1      bits 0-3: alive counter, +1 (mod 16) per frame of this kind sent in this direction;
//                bits 4-7: zero (as the CAN frame map's alive byte, hil/can/frame_map.hpp)
//   bytes 2-5    sender id (u32 LE): the sending end's id, never 0
//   bytes 6-9    session id (u32 LE): the plant's session, drawn at start-up (the link guard's rules,
//                docs/transport.md); the controller binds to it with the configuration frame; 0 only in
//                the image's Hello, which precedes every session
//   bytes 10-13  freshness (u32 LE): the sender's frame counter in this direction, 1, 2, 3, ...
//   bytes 14..   payload: the kind's struct as its bytes (both ends little-endian with the same layout); a
//                sensor or actuator frame is the device's typed frame (its 32-byte header, then its signals as
//                doubles, gyrostab_signals/<device>_frames.hpp), so its length is the device's; the
//                configuration is checked by its size
//   last 4       CRC-32 (firmware/link/crc32.hpp) of every byte before it, LE
// A receiver checks, in this order, and refuses with the first failure (counted per cause in
// TargetRxCounters): framing (COBS), length (header + CRC at least, the largest frame at most), CRC, reserved
// bits, kind (known, and sent in this direction), payload length of the kind, session and sender (once
// bound), and the alive counter: repeated ⇒ a stale copy; skipped ⇒ frames were lost or reordered (the counter
// resynchronises on this frame, so one loss refuses one frame) — the rules of CAN's alive counter.
// What a refused or missing sensor frame does to the controller (it steps the tick without a frame: the fault
// monitor holds, then latches the safe state) is the session's business (firmware/target/pil_session.hpp).
// Tested by tests/unit/target_frame_test.cpp; fuzzed by tests/fuzz/target_frame_fuzz.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "firmware/link/cobs.hpp"
#include "firmware/link/crc32.hpp"
#include "firmware/msg/any_frame.hpp"
#include "firmware/scheduler/perf_counter.hpp"

namespace gyrostab::firmware::link {

enum class TargetFrameKind : std::uint8_t {
  kHello = 1,           // target → host at boot: which image, what it expects
  kConfig = 2,          // host → target: the controller's configuration; binds the session
  kConfigVerdict = 3,   // target → host: the controller's start-up check
  kSensor = 4,          // host → target: the device's sensor frame
  kActuator = 5,        // target → host: the device's actuator frame
  kProfileRequest = 6,  // host → target: send the execution profile now
  kProfile = 7,         // target → host: TargetProfile
  kStop = 8,            // host → target: the run is over (the image answers with its profile, then exits)
};
inline constexpr std::size_t kTargetFrameKinds = 9;  // index = kind value; 0 unused

// Which end sends a kind.
constexpr bool sent_by_host(TargetFrameKind k) {
  return k == TargetFrameKind::kConfig || k == TargetFrameKind::kSensor ||
         k == TargetFrameKind::kProfileRequest || k == TargetFrameKind::kStop;
}

inline constexpr std::size_t kTargetHeaderBytes = 14;
inline constexpr std::size_t kTargetCrcBytes = 4;
inline constexpr std::size_t kMaxConfigBytes = 1024;  // the largest device Config is 856 bytes (the CMG cluster's)

// Hello: the image names itself and what it will accept.
// This file's layout (3: each device's own frames, their sizes in the Hello; 2: one frame shared by every
// device).
inline constexpr std::uint32_t kTargetFrameVersion = 3;
struct TargetHello {
  char image[24]{};                  // the device name, NUL-padded ("ship_roll_damper")
  std::uint32_t config_bytes{0};     // sizeof(Controller::Config) in this image
  std::uint32_t frame_version{kTargetFrameVersion};
  std::uint32_t clock_ns_per_count{0};  // resolution of the profile clock [virtual ns]
  std::uint16_t sensor_signals{0};      // values in the device's sensor frame (its signal table)
  std::uint16_t command_signals{0};     // values in its actuator frame
};
static_assert(sizeof(TargetHello) == 40);

// The controller's start-up check as the image ran it (firmware/control/config_check.hpp).
struct TargetConfigVerdict {
  std::uint32_t accepted{0};  // 1: armed; 0: refused (every command is the safe one, kConfigRefused)
  std::uint32_t reserved{0};
  double value{0.0};
  double lower{0.0};
  double upper{0.0};
  char reason[160]{};  // the check's text, NUL-terminated (truncated if longer)
};
static_assert(sizeof(TargetConfigVerdict) == 8 + 24 + 160);

// Frames refused by one receiver, per cause.
struct TargetRxCounters {
  std::uint64_t accepted{0};
  std::uint64_t framing{0};       // not valid COBS, or longer than the largest frame
  std::uint64_t length{0};        // shorter than header + CRC, or the kind's payload length is wrong
  std::uint64_t crc{0};
  std::uint64_t reserved_bits{0};
  std::uint64_t kind{0};          // unknown kind, or one the other end does not send
  std::uint64_t foreign{0};       // another session or another sender once bound
  std::uint64_t repeated{0};      // alive counter did not advance: a stale copy
  std::uint64_t skipped{0};       // alive counter jumped: frames lost or out of order
  std::uint64_t overflow{0};      // bytes dropped because a frame overran the receive buffer

  constexpr std::uint64_t refused() const {
    return framing + length + crc + reserved_bits + kind + foreign + repeated + skipped;
  }
};

// The image's execution profile, measured with its profile clock (firmware/target/instruction_clock.hpp):
// under QEMU's -icount shift=0 one virtual nanosecond is one instruction, so every *_ns here counts
// instructions (with the clock's resolution, clock_ns_per_count).
struct TargetProfile {
  std::uint64_t ticks{0};        // controller ticks stepped
  std::uint64_t missing{0};      // ticks stepped without a sensor frame (refused, withheld or lost)
  std::uint64_t republished{0};  // actuator frames sent again for a repeated sensor frame
  std::uint64_t late{0};         // valid sensor frames for a tick already stepped past (not answered)
  std::uint32_t clock_ns_per_count{0};
  std::uint32_t monitor_status{0};  // the fault monitor's status bits at the end
  PerfCounter step{};             // the whole controller.step(): monitor, scheduler, header
  PerfCounter control{};          // the scheduler's control task
  PerfCounter drive{};            // the scheduler's drive task (runs = 0 without one)
  PerfCounter link{};             // decoding the sensor frame and encoding the actuator frame
  TargetRxCounters rx{};          // what the image refused
};

// The sizes of a device's two frames on the link (header + 8 bytes per signal).
struct TargetFrameSizes {
  std::size_t sensor{0};
  std::size_t actuator{0};
};
constexpr TargetFrameSizes target_frame_sizes(std::size_t sensor_signals, std::size_t command_signals) {
  return {msg::kFrameHeaderBytes + 8 * sensor_signals, msg::kFrameHeaderBytes + 8 * command_signals};
}

// Payload length of a kind (kConfig: at most kMaxConfigBytes, checked by the session against its Config; the
// frames: the device's sizes).
constexpr long target_payload_bytes(TargetFrameKind k, TargetFrameSizes frames) {
  switch (k) {
    case TargetFrameKind::kHello: return sizeof(TargetHello);
    case TargetFrameKind::kConfig: return -1;
    case TargetFrameKind::kConfigVerdict: return sizeof(TargetConfigVerdict);
    case TargetFrameKind::kSensor: return static_cast<long>(frames.sensor);
    case TargetFrameKind::kActuator: return static_cast<long>(frames.actuator);
    case TargetFrameKind::kProfileRequest: return 0;
    case TargetFrameKind::kProfile: return sizeof(TargetProfile);
    case TargetFrameKind::kStop: return 0;
  }
  return -2;
}

inline constexpr std::size_t kMaxTargetPayload = sizeof(TargetProfile) > kMaxConfigBytes ? sizeof(TargetProfile)
                                                                                            : kMaxConfigBytes;
static_assert(sizeof(msg::AnySensorFrame) <= kMaxTargetPayload);
inline constexpr std::size_t kMaxTargetFrame = kTargetHeaderBytes + kMaxTargetPayload + kTargetCrcBytes;
inline constexpr std::size_t kMaxTargetWire = cobs_max_encoded(kMaxTargetFrame) + 1;  // + the closing zero

constexpr void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
constexpr std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// One end's sending side: alive counters per kind, the freshness counter, and a wire buffer.
class TargetFrameEncoder {
 public:
  TargetFrameEncoder(std::uint32_t sender, std::uint32_t session) : sender_(sender), session_(session) {}
  void set_session(std::uint32_t s) { session_ = s; }
  std::uint32_t session() const { return session_; }
  std::uint32_t sender() const { return sender_; }

  // Encodes one frame, closing zero included. Returns the bytes to send (empty if the payload is too long).
  std::span<const std::uint8_t> encode(TargetFrameKind kind, const void* payload, std::size_t n) {
    if (n > kMaxTargetPayload) return {};
    const auto k = static_cast<std::size_t>(kind);
    raw_[0] = static_cast<std::uint8_t>(kind);
    raw_[1] = static_cast<std::uint8_t>(alive_[k % kTargetFrameKinds] & 0x0Fu);
    alive_[k % kTargetFrameKinds] = static_cast<std::uint8_t>((alive_[k % kTargetFrameKinds] + 1u) & 0x0Fu);
    put_u32(&raw_[2], sender_);
    put_u32(&raw_[6], session_);
    put_u32(&raw_[10], ++freshness_);
    if (n > 0) std::memcpy(&raw_[kTargetHeaderBytes], payload, n);
    const std::size_t body = kTargetHeaderBytes + n;
    put_u32(&raw_[body], crc32(std::span<const std::uint8_t>(raw_.data(), body)));
    const std::size_t w = cobs_encode(std::span<const std::uint8_t>(raw_.data(), body + kTargetCrcBytes),
                                      std::span<std::uint8_t>(wire_.data(), wire_.size() - 1));
    wire_[w] = 0;
    return {wire_.data(), w + 1};
  }
  template <class T>
  std::span<const std::uint8_t> encode(TargetFrameKind kind, const T& payload) {
    return encode(kind, &payload, sizeof(T));
  }

 private:
  std::uint32_t sender_;
  std::uint32_t session_;
  std::uint32_t freshness_{0};
  std::array<std::uint8_t, kTargetFrameKinds> alive_{};
  std::array<std::uint8_t, kMaxTargetFrame> raw_{};
  std::array<std::uint8_t, kMaxTargetWire> wire_{};
};

enum class TargetRxVerdict : std::uint8_t {
  kOk,
  kFraming,
  kLength,
  kCrc,
  kReservedBits,
  kKind,
  kForeign,
  kRepeated,
  kSkipped,
};

constexpr const char* describe(TargetRxVerdict v) {
  switch (v) {
    case TargetRxVerdict::kOk: return "ok";
    case TargetRxVerdict::kFraming: return "framing (not COBS, or too long)";
    case TargetRxVerdict::kLength: return "wrong length";
    case TargetRxVerdict::kCrc: return "CRC";
    case TargetRxVerdict::kReservedBits: return "reserved bits not zero";
    case TargetRxVerdict::kKind: return "unknown kind or wrong direction";
    case TargetRxVerdict::kForeign: return "another session or sender";
    case TargetRxVerdict::kRepeated: return "alive counter repeated (stale copy)";
    case TargetRxVerdict::kSkipped: return "alive counter skipped (frames lost or out of order)";
  }
  return "?";
}

struct TargetFrameView {
  TargetFrameKind kind{};
  std::uint32_t sender{0};
  std::uint32_t session{0};
  std::uint32_t freshness{0};
  std::span<const std::uint8_t> payload{};
};

// One end's receiving side. `from_host`: the kinds it accepts are the host's (the target's decoder) or the
// target's (the host's). feed() takes the stream byte by byte or in chunks; each complete frame is judged and,
// when accepted, handed to the callback.
class TargetFrameDecoder {
 public:
  // `frames`: the device's frame sizes (the image knows its own; the host sets them from the scene's device
  // before the session, set_frame_sizes()). A frame of another length is refused (kLength).
  TargetFrameDecoder(bool from_host, TargetFrameSizes frames) : from_host_(from_host), frames_(frames) {}
  void set_frame_sizes(TargetFrameSizes frames) { frames_ = frames; }
  TargetFrameSizes frame_sizes() const { return frames_; }

  // Accept from now on only this session and sender (0: any).
  void bind(std::uint32_t session, std::uint32_t sender) {
    session_ = session;
    sender_ = sender;
  }
  bool bound() const { return session_ != 0; }

  // Judges one COBS frame (closing zero excluded). kOk: `out` is the frame (its payload points into this
  // decoder and stays valid until the next call).
  TargetRxVerdict judge(std::span<const std::uint8_t> wire, TargetFrameView& out) {
    const TargetRxVerdict v = judge_uncounted(wire, out);
    count(v);
    return v;
  }

  // Collects stream bytes; returns true with `frame` = the bytes of one complete COBS frame when a zero
  // closes it. Empty frames (two zeros in a row: a receiver's resynchronisation) are skipped. A frame longer
  // than the buffer is dropped up to its zero (counted: overflow, then framing).
  bool collect(std::uint8_t b, std::span<const std::uint8_t>& frame) {
    if (b != 0) {
      if (fill_ < collect_.size()) {
        collect_[fill_++] = b;
      } else {
        overflowed_ = true;
        ++counters_.overflow;
      }
      return false;
    }
    const std::size_t n = fill_;
    const bool over = overflowed_;
    fill_ = 0;
    overflowed_ = false;
    if (n == 0) return false;
    if (over) {
      ++counters_.framing;
      return false;
    }
    frame = std::span<const std::uint8_t>(collect_.data(), n);
    return true;
  }

  const TargetRxCounters& counters() const { return counters_; }
  TargetRxCounters& counters() { return counters_; }

 private:
  TargetRxVerdict judge_uncounted(std::span<const std::uint8_t> wire, TargetFrameView& out) {
    const long n = cobs_decode(wire, std::span<std::uint8_t>(raw_.data(), raw_.size()));
    if (n < 0) return TargetRxVerdict::kFraming;
    const auto len = static_cast<std::size_t>(n);
    if (len < kTargetHeaderBytes + kTargetCrcBytes) return TargetRxVerdict::kLength;
    const std::size_t body = len - kTargetCrcBytes;
    if (crc32(std::span<const std::uint8_t>(raw_.data(), body)) != get_u32(&raw_[body])) {
      return TargetRxVerdict::kCrc;
    }
    if ((raw_[1] & 0xF0u) != 0) return TargetRxVerdict::kReservedBits;
    const std::uint8_t k = raw_[0];
    if (k == 0 || k >= kTargetFrameKinds) return TargetRxVerdict::kKind;
    const auto kind = static_cast<TargetFrameKind>(k);
    if (sent_by_host(kind) != from_host_) return TargetRxVerdict::kKind;
    const std::size_t payload = body - kTargetHeaderBytes;
    const long want = target_payload_bytes(kind, frames_);
    if (want >= 0 ? payload != static_cast<std::size_t>(want) : payload > kMaxConfigBytes) {
      return TargetRxVerdict::kLength;
    }
    const std::uint32_t sender = get_u32(&raw_[2]);
    const std::uint32_t session = get_u32(&raw_[6]);
    // The image's Hello precedes every session (session 0); anything else names one.
    if (sender == 0 || (session == 0 && kind != TargetFrameKind::kHello)) return TargetRxVerdict::kForeign;
    if (session_ != 0 && (session != session_ || (sender_ != 0 && sender != sender_))) {
      return TargetRxVerdict::kForeign;
    }
    const std::uint8_t alive = raw_[1];
    if (alive_seen_[k]) {
      const auto want_alive = static_cast<std::uint8_t>((last_alive_[k] + 1u) & 0x0Fu);
      if (alive == last_alive_[k]) return TargetRxVerdict::kRepeated;
      if (alive != want_alive) {
        last_alive_[k] = alive;  // resynchronise: the next frame in sequence is accepted again
        return TargetRxVerdict::kSkipped;
      }
    }
    alive_seen_[k] = true;
    last_alive_[k] = alive;
    out.kind = kind;
    out.sender = sender;
    out.session = session;
    out.freshness = get_u32(&raw_[10]);
    out.payload = std::span<const std::uint8_t>(&raw_[kTargetHeaderBytes], payload);
    return TargetRxVerdict::kOk;
  }

  void count(TargetRxVerdict v) {
    switch (v) {
      case TargetRxVerdict::kOk: ++counters_.accepted; break;
      case TargetRxVerdict::kFraming: ++counters_.framing; break;
      case TargetRxVerdict::kLength: ++counters_.length; break;
      case TargetRxVerdict::kCrc: ++counters_.crc; break;
      case TargetRxVerdict::kReservedBits: ++counters_.reserved_bits; break;
      case TargetRxVerdict::kKind: ++counters_.kind; break;
      case TargetRxVerdict::kForeign: ++counters_.foreign; break;
      case TargetRxVerdict::kRepeated: ++counters_.repeated; break;
      case TargetRxVerdict::kSkipped: ++counters_.skipped; break;
    }
  }

  bool from_host_;
  TargetFrameSizes frames_;
  std::uint32_t session_{0};
  std::uint32_t sender_{0};
  std::array<std::uint8_t, kTargetFrameKinds> last_alive_{};
  std::array<bool, kTargetFrameKinds> alive_seen_{};
  std::array<std::uint8_t, kMaxTargetFrame> raw_{};
  std::array<std::uint8_t, kMaxTargetWire> collect_{};
  std::size_t fill_{0};
  bool overflowed_{false};
  TargetRxCounters counters_{};
};

}  // namespace gyrostab::firmware::link
