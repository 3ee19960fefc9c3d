// The link envelope of a CAN FD set (frame_map.hpp: link_sender, link_session, link_freshness, link_mac in the
// header frame, which is sent last): seal() writes it, open() judges it, for the session binding and
// authentication that every plant ⇄ controller link has (hil/link/link_guard.hpp, docs/transport.md).
//
// The MAC covers, for each frame of the set in map order, its identifier (2 bytes, low first) and its data
// bytes 2 … len−1 (tick tag, signals, padding); of the header frame only up to the session id (the freshness
// value and the MAC are inputs of the MAC computation itself, and the CRC and alive counter change whenever the
// set is resent), followed by the sender's scene hash (8 bytes, low first: the frames have no room for it, so
// it is covered rather than carried — a set of another scene fails the MAC, keyed or not). So it binds every
// body frame to its header:
//   - with a key (`--key-file`) it is SecOC's keyed SipHash-2-4 (firmware/link/secoc.hpp) with a 32-bit
//     freshness value on the wire: a forger cannot make a set the receiver accepts;
//   - without a key the set carries an unkeyed SipHash-2-4 (key of zeros) over the same bytes and open()
//     checks it after the session and sender: integrity, not authenticity (anyone can compute it), so that the
//     frames of two pairs on one bus are never mixed into one set unnoticed — such a set is refused as
//     foreign.
// No heap; O(bytes of the set) per call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "hil/can/frame_codec.hpp"
#include "hil/link/link_guard.hpp"

namespace gyrostab::can {

inline constexpr std::size_t kMaxMacPayload = kMaxMessagesPerDirection * (2 + kFdMaxData) + 8;

// A guard configuration made fit for CAN: the freshness value travels as 32 bits.
hil::GuardConfig can_guard_config(hil::GuardConfig c);

// The bytes the MAC covers (see above); `set` in map order with the header last, `scene` the sealing end's
// scene hash. Returns their number.
std::size_t set_mac_payload(std::span<const CanFrame> set, std::uint64_t scene,
                            std::span<std::uint8_t, kMaxMacPayload> out);

// The envelope in a header frame, and writing one into it (the CRC recomputed).
hil::LinkEnvelope read_link_envelope(const CanFrame& header);
void write_link_envelope(CanFrame& header, const hil::LinkEnvelope& e);

// Seals an encoded set (its last frame is the header): sender and session, then freshness and MAC.
void seal(std::span<CanFrame> set, hil::LinkGuard& guard);

// Judges a completed set; refusals are counted by the guard. kOk: the set may be acted on, `env` is its
// envelope (for the handshake's binding).
hil::GuardVerdict open(std::span<const CanFrame> set, hil::LinkGuard& guard, hil::LinkEnvelope& env);

}  // namespace gyrostab::can
