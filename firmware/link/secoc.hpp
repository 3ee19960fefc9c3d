// Frame authentication on the plant-controller link (LCM, CAN FD, UART), in the manner of AUTOSAR SecOC
// ("Specification of Secure Onboard Communication", AUTOSAR Classic Platform): every frame carries the
// session id, the low bytes of a freshness value and a truncated MAC; the receiver rebuilds the full
// freshness value, checks it against the latest accepted one and verifies the MAC over
//   data id (u32 LE) | session id (u64 LE) | freshness value (u64 LE) | payload
// with SipHash-2-4 (firmware/link/siphash24.hpp; Aumasson & Bernstein 2012) under a 128-bit key.
// The data id is never sent: it is what the receiver expects on that channel (CAN identifier, LCM channel),
// so a genuine frame moved to another channel fails its MAC.
//
// Freshness (SecOC's freshness value counter, one per direction): the sender counts 1, 2, 3, ... per frame
// and transmits the low freshness_bytes bytes. The receiver takes the upper bits of its latest accepted
// value, puts the received low bits under them and adds one wrap of the truncated counter when the received
// bits are not greater than the latest's (SecOC's construction of the freshness verify value). It accepts
// only a value that is newer than the latest and at most acceptance_window ahead of it, and only after the
// MAC verifies; the state advances on nothing else. Hence:
//   - a forger without the key changes nothing: a frame that fails its MAC is counted and leaves the state
//     exactly as it was, however far ahead it claims to be, so the genuine peer is never locked out;
//   - a genuine frame after N lost frames, N < acceptance_window, is accepted (it is N + 1 ahead);
//   - the window bounds the damage of the one forgery in 2^(8 mac_bytes) that verifies by chance: it can
//     move the latest value at most acceptance_window ahead, so the genuine peer is refused for at most that
//     many frames instead of for ever;
//   - after acceptance_window or more consecutive lost frames the receiver cannot catch up by itself; the
//     host re-binds it (new session id, or a freshness value learnt out of band: SecOC's freshness value
//     manager, which is host code).
// The session id, drawn by the plant at start-up, is compared before anything else, so frames of an earlier
// run (and their replays) are refused as wrong_session without a MAC computation.
//
// The truncated MAC is the first mac_bytes bytes of the SipHash output as the reference implementation
// prints it (least significant first), i.e. the low 8·mac_bytes bits of the 64-bit tag; SecOC likewise
// keeps the leading bits of the MAC. The comparison is constant-time (one xor and a mask, no early exit).
// A random forgery that reaches the comparison passes with probability 2^-(8·mac_bytes).
//
// Time complexity: O(n) for an n-byte payload per protect() or verify() (one SipHash over 20 + n bytes);
// every other step is O(1). Memory: a SecOcSender is 56 bytes and a SecOcReceiver 96 (key, counters and
// state included; the same on the host and the Cortex-M7), constant stack (one 48-byte SipHash state and a
// 20-byte header), no heap, no exceptions. Everything is constexpr.
//
// Tested by tests/unit/secoc_test.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "firmware/control/config_check.hpp"
#include "firmware/link/siphash24.hpp"

namespace gyrostab::firmware::link {

inline constexpr std::size_t kMaxMacBytes = 8;
inline constexpr std::size_t kMaxFreshnessBytes = 8;

// The 128-bit link key. Parsing a key file is host code; the target only receives the 16 bytes.
struct Key128 {
  std::array<std::uint8_t, SipHash24::kKeyBytes> bytes{};

  static constexpr Key128 from_bytes(std::span<const std::uint8_t, SipHash24::kKeyBytes> b) noexcept {
    Key128 k;
    for (std::size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = b[i];
    return k;
  }
};

// How one direction of the link is secured; both ends must agree.
struct SecOcProfile {
  std::uint8_t mac_bytes{8};        // transmitted MAC length, 1..8 [bytes]
  std::uint8_t freshness_bytes{8};  // transmitted freshness length, 0..8 [bytes]
  // How far ahead of the latest accepted value a frame may be [frames]: acceptance_window - 1 consecutive
  // lost frames are tolerated, and a chance forgery locks the genuine peer out for at most this many.
  std::uint64_t acceptance_window{1024};
};

// Mask of the low n bytes of a 64-bit word (n ≥ 8: every bit).
constexpr std::uint64_t low_bytes_mask(std::size_t n) noexcept {
  return n >= 8 ? std::numeric_limits<std::uint64_t>::max() : (std::uint64_t{1} << (8u * n)) - 1u;
}

// A window wider than the truncated counter's period would let one received value stand for two
// candidates; with freshness_bytes = 0 only the next value (window 1) can be rebuilt.
constexpr std::uint64_t max_acceptance_window(std::size_t freshness_bytes) noexcept {
  return freshness_bytes >= 8 ? std::numeric_limits<std::uint64_t>::max()
                              : low_bytes_mask(freshness_bytes) + 1u;
}

constexpr ConfigCheck check(const SecOcProfile& p) noexcept {
  if (p.mac_bytes < 1 || p.mac_bytes > kMaxMacBytes)
    return ConfigCheck::refused("SecOC: mac_bytes must lie in 1..8", p.mac_bytes, 1, kMaxMacBytes);
  if (p.freshness_bytes > kMaxFreshnessBytes)
    return ConfigCheck::refused("SecOC: freshness_bytes must lie in 0..8", p.freshness_bytes, 0,
                                kMaxFreshnessBytes);
  const std::uint64_t max_window = max_acceptance_window(p.freshness_bytes);
  if (p.acceptance_window < 1 || p.acceptance_window > max_window)
    return ConfigCheck::refused("SecOC: acceptance_window must lie in 1..2^(8 freshness_bytes)",
                                static_cast<double>(p.acceptance_window), 1, static_cast<double>(max_window));
  return ConfigCheck::accepted();
}

// The profile moved into range, so that a profile that skipped check() still has defined behaviour.
constexpr SecOcProfile clamped(SecOcProfile p) noexcept {
  if (p.mac_bytes < 1) p.mac_bytes = 1;
  if (p.mac_bytes > kMaxMacBytes) p.mac_bytes = kMaxMacBytes;
  if (p.freshness_bytes > kMaxFreshnessBytes) p.freshness_bytes = kMaxFreshnessBytes;
  const std::uint64_t max_window = max_acceptance_window(p.freshness_bytes);
  if (p.acceptance_window < 1) p.acceptance_window = 1;
  if (p.acceptance_window > max_window) p.acceptance_window = max_window;
  return p;
}

// Little-endian wire form of the truncated fields: the first out.size() (≤ 8) bytes of v.
constexpr void store_le(std::uint64_t v, std::span<std::uint8_t> out) noexcept {
  for (std::size_t i = 0; i < out.size() && i < 8; ++i) out[i] = static_cast<std::uint8_t>(v >> (8u * i));
}
constexpr std::uint64_t load_le(std::span<const std::uint8_t> in) noexcept {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < in.size() && i < 8; ++i) v |= std::uint64_t{in[i]} << (8u * i);
  return v;
}

// The full 64-bit MAC of one frame (SecOC's authenticator before truncation).
[[nodiscard]] constexpr std::uint64_t authenticator(const Key128& key, std::uint32_t data_id,
                                                    std::uint64_t session_id, std::uint64_t freshness,
                                                    std::span<const std::uint8_t> payload) noexcept {
  // Fixed-length header first: the payload is the rest, so no two (header, payload) pairs encode alike.
  std::array<std::uint8_t, 4 + 8 + 8> header{};
  store_le(data_id, std::span(header).subspan(0, 4));
  store_le(session_id, std::span(header).subspan(4, 8));
  store_le(freshness, std::span(header).subspan(12, 8));
  SipHash24 h(key.bytes);
  h.update(header);
  h.update(payload);
  return h.finish();
}

constexpr std::uint64_t truncate_mac(std::uint64_t mac, std::size_t mac_bytes) noexcept {
  return mac & low_bytes_mask(mac_bytes);
}

// Equality of the low mac_bytes bytes, without a branch or an early exit that would tell a forger how many
// leading bytes of a guess were right.
constexpr bool mac_equal(std::uint64_t a, std::uint64_t b, std::size_t mac_bytes) noexcept {
  const std::uint64_t diff = (a ^ b) & low_bytes_mask(mac_bytes);
  return ((diff | (~diff + 1u)) >> 63) == 0;  // top bit of diff | -diff is set iff diff != 0
}

struct ReconstructedFreshness {
  std::uint64_t value{0};    // the full freshness value the frame claims
  bool representable{true};  // false when that value would pass 2^64 - 1 (the counter is exhausted)
};

// SecOC's freshness verify value: the upper bits of the latest accepted value over the received low bits,
// plus one period of the truncated counter when the received bits are not greater than the latest's.
constexpr ReconstructedFreshness reconstruct_freshness(std::uint64_t latest, std::uint64_t received,
                                                       std::size_t freshness_bytes) noexcept {
  if (freshness_bytes >= kMaxFreshnessBytes) return {received, true};
  const std::uint64_t mask = low_bytes_mask(freshness_bytes);
  const std::uint64_t low = received & mask;
  const std::uint64_t base = latest & ~mask;
  if (low > (latest & mask)) return {base | low, true};
  const std::uint64_t period = mask + 1u;
  if (base > std::numeric_limits<std::uint64_t>::max() - period) return {0, false};
  return {base + period + low, true};
}

// What the sender puts in a frame beside the payload (the transport packs them with store_le).
struct SecuredFields {
  std::uint64_t session_id{0};
  std::uint64_t freshness{0};  // low freshness_bytes bytes of the freshness value
  std::uint64_t mac{0};        // low mac_bytes bytes of the authenticator
};

enum class Verdict : std::uint8_t {
  kOk,           // verified and newer: the state advanced
  kBadMac,       // right session, freshness in the window, MAC wrong (forgery, corruption, wrong key/data id)
  kStale,        // not newer than the latest accepted value: a replay or a late duplicate
  kTooFarAhead,  // more than acceptance_window ahead (or past 2^64 - 1)
  kWrongSession,  // another session id: a frame of another run, or a forgery
};

struct SecOcCounters {
  std::uint64_t ok{0};
  std::uint64_t bad_mac{0};
  std::uint64_t stale{0};  // stale or replayed
  std::uint64_t too_far_ahead{0};
  std::uint64_t wrong_session{0};

  constexpr std::uint64_t rejected() const noexcept {
    return bad_mac + stale + too_far_ahead + wrong_session;
  }
};

class SecOcSender {
 public:
  // next_freshness = 1 pairs with a receiver whose latest accepted value is 0 (a fresh session).
  constexpr SecOcSender(const Key128& key, std::uint32_t data_id, std::uint64_t session_id,
                        const SecOcProfile& profile, std::uint64_t next_freshness = 1) noexcept
      : key_(key),
        data_id_(data_id),
        session_id_(session_id),
        profile_(clamped(profile)),
        next_(next_freshness) {}

  // Secures one frame and consumes one freshness value. The counter stops at 2^64 - 1 rather than wrap to 0:
  // frames after it repeat that value and are refused as stale, instead of reusing freshness values under
  // the same key and session (2^64 frames are out of reach at any frame rate anyway).
  [[nodiscard]] constexpr SecuredFields protect(std::span<const std::uint8_t> payload) noexcept {
    const std::uint64_t fv = next_;
    if (next_ != std::numeric_limits<std::uint64_t>::max()) ++next_;
    return {session_id_, fv & low_bytes_mask(profile_.freshness_bytes),
            truncate_mac(authenticator(key_, data_id_, session_id_, fv, payload), profile_.mac_bytes)};
  }

  constexpr std::uint64_t next_freshness() const noexcept { return next_; }
  constexpr const SecOcProfile& profile() const noexcept { return profile_; }

 private:
  Key128 key_;
  std::uint32_t data_id_;
  std::uint64_t session_id_;
  SecOcProfile profile_;
  std::uint64_t next_;
};

class SecOcReceiver {
 public:
  constexpr SecOcReceiver(const Key128& key, std::uint32_t data_id, std::uint64_t session_id,
                          const SecOcProfile& profile, std::uint64_t latest_accepted = 0) noexcept
      : key_(key),
        data_id_(data_id),
        session_id_(session_id),
        profile_(clamped(profile)),
        latest_(latest_accepted) {}

  // Judges one received frame, counts the verdict, and advances the latest accepted freshness value only on
  // kOk. Checks run in the order session, freshness, MAC; the first that fails names the verdict (so a
  // forgery far outside the window costs no MAC computation).
  constexpr Verdict verify(std::span<const std::uint8_t> payload, const SecuredFields& f) noexcept {
    const Verdict v = judge(payload, f);
    switch (v) {
      case Verdict::kOk:
        ++counters_.ok;
        break;
      case Verdict::kBadMac:
        ++counters_.bad_mac;
        break;
      case Verdict::kStale:
        ++counters_.stale;
        break;
      case Verdict::kTooFarAhead:
        ++counters_.too_far_ahead;
        break;
      case Verdict::kWrongSession:
        ++counters_.wrong_session;
        break;
    }
    return v;
  }

  // Host decision (new session, or a freshness value synchronised out of band); the counters are kept.
  constexpr void rebind(std::uint64_t session_id, std::uint64_t latest_accepted) noexcept {
    session_id_ = session_id;
    latest_ = latest_accepted;
  }

  constexpr std::uint64_t latest_accepted() const noexcept { return latest_; }
  constexpr std::uint64_t session() const noexcept { return session_id_; }
  constexpr const SecOcProfile& profile() const noexcept { return profile_; }
  constexpr const SecOcCounters& counters() const noexcept { return counters_; }

 private:
  constexpr Verdict judge(std::span<const std::uint8_t> payload, const SecuredFields& f) noexcept {
    if (f.session_id != session_id_) return Verdict::kWrongSession;
    const ReconstructedFreshness r = reconstruct_freshness(latest_, f.freshness, profile_.freshness_bytes);
    if (!r.representable) return Verdict::kTooFarAhead;
    if (r.value <= latest_) return Verdict::kStale;
    const std::uint64_t ahead = r.value - latest_;
    if (ahead > profile_.acceptance_window) {
      // Truncated bits that read as `ahead` frames ahead also read as (period - ahead) frames behind; the
      // verdict names the nearer reading (the frame is refused either way). The rebuilt value is at most one
      // period ahead, so period - ahead does not underflow.
      const bool truncated = profile_.freshness_bytes < kMaxFreshnessBytes;
      const std::uint64_t period = max_acceptance_window(profile_.freshness_bytes);
      return truncated && ahead > period - ahead ? Verdict::kStale : Verdict::kTooFarAhead;
    }
    const std::uint64_t expected =
        truncate_mac(authenticator(key_, data_id_, session_id_, r.value, payload), profile_.mac_bytes);
    if (!mac_equal(expected, f.mac, profile_.mac_bytes)) return Verdict::kBadMac;
    latest_ = r.value;
    return Verdict::kOk;
  }

  Key128 key_;
  std::uint32_t data_id_;
  std::uint64_t session_id_;
  SecOcProfile profile_;
  std::uint64_t latest_;
  SecOcCounters counters_{};
};

}  // namespace gyrostab::firmware::link
