// SipHash-2-4: the keyed pseudo-random function that authenticates frames on the plant-controller link
// (firmware/link/secoc.hpp). 128-bit key, 64-bit output, any message length.
//
// Standard: J.-P. Aumasson and D. J. Bernstein, "SipHash: a fast short-input PRF", INDOCRYPT 2012 — two
// SipRounds per 8-byte message word (c = 2), four in the finalization (d = 4). Its output is the 64-bit
// word v0^v1^v2^v3; the reference implementation prints that word as 8 bytes least significant first, so
// the published byte vectors read as little-endian words equal the values returned here.
// Why SipHash and not HMAC-SHA-256 or AES-CMAC: the target has no crypto unit; SipHash is a PRF (hence a
// MAC) designed for short inputs such as one frame: two rounds of add-rotate-xor per 8 bytes, no tables
// (nothing to leak through a cache), no key schedule, and a 64-bit tag that covers every truncation the
// link uses (1..8 bytes).
//
// Key and message words are loaded little-endian with explicit byte shifts (never a cast or memcpy of a
// word), so host and target compute the same value whatever their byte order or alignment rules.
//
// Time complexity: O(n) for n message bytes (one compression per 8 bytes, plus a constant finalization);
// update() costs the same whatever the split of the message into calls.
// Memory: sizeof(SipHash24) = 48 bytes of state (four words, the pending partial word and the length mod
// 256), constant stack, no heap, no recursion, no tables. Everything is constexpr.
//
// Tested by tests/unit/siphash24_test.cpp: the 64 published vectors (key 00..0f, message 00..n-1), 10 000
// random keys and messages against libsodium's crypto_shorthash_siphash24, and incremental == one-shot.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

namespace gyrostab::firmware::link {

namespace detail {

// Spelled out rather than looped: compilers recognise this pattern and merge it into word loads where the
// target allows unaligned little-endian access (Clang -O2 on x86-64: one mov; arm-none-eabi-gcc -Os for the
// Cortex-M7: two ldr), and keep byte loads elsewhere. A loop over the bytes ran about twice as slow (GCC
// -O2).
constexpr std::uint64_t sip_load_le64(const std::uint8_t* p) noexcept {
  return std::uint64_t{p[0]} | (std::uint64_t{p[1]} << 8) | (std::uint64_t{p[2]} << 16) |
         (std::uint64_t{p[3]} << 24) | (std::uint64_t{p[4]} << 32) | (std::uint64_t{p[5]} << 40) |
         (std::uint64_t{p[6]} << 48) | (std::uint64_t{p[7]} << 56);
}

struct SipState {
  std::uint64_t v0, v1, v2, v3;

  constexpr void round() noexcept {
    v0 += v1;
    v1 = std::rotl(v1, 13);
    v1 ^= v0;
    v0 = std::rotl(v0, 32);
    v2 += v3;
    v3 = std::rotl(v3, 16);
    v3 ^= v2;
    v0 += v3;
    v3 = std::rotl(v3, 21);
    v3 ^= v0;
    v2 += v1;
    v1 = std::rotl(v1, 17);
    v1 ^= v2;
    v2 = std::rotl(v2, 32);
  }

  constexpr void compress(std::uint64_t m) noexcept {
    v3 ^= m;
    round();
    round();
    v0 ^= m;
  }
};

}  // namespace detail

class SipHash24 {
 public:
  static constexpr std::size_t kKeyBytes = 16;

  // Initialization of the paper (§2): the key words xor the constants "somepseudorandomlygeneratedbytes".
  explicit constexpr SipHash24(std::span<const std::uint8_t, kKeyBytes> key) noexcept {
    const std::uint64_t k0 = detail::sip_load_le64(key.data());
    const std::uint64_t k1 = detail::sip_load_le64(key.data() + 8);
    s_ = {k0 ^ 0x736f6d6570736575ULL, k1 ^ 0x646f72616e646f6dULL, k0 ^ 0x6c7967656e657261ULL,
          k1 ^ 0x7465646279746573ULL};
  }

  // Appends bytes to the message. Whole words are compressed straight from the span; only a partial word
  // at either end goes through the pending word, so the cost does not depend on how the message is split.
  constexpr void update(std::span<const std::uint8_t> bytes) noexcept {
    std::size_t i = 0;
    const std::size_t n = bytes.size();
    while (pending_bytes() != 0 && i < n) push_byte(bytes[i++]);
    for (; i + 8 <= n; i += 8) {
      s_.compress(detail::sip_load_le64(bytes.data() + i));
      length_mod_256_ = static_cast<std::uint8_t>(length_mod_256_ + 8u);
    }
    while (i < n) push_byte(bytes[i++]);
  }

  // The 64-bit tag of everything passed to update() so far. const: the state is left as it was, so a
  // caller may tag a prefix and keep appending.
  [[nodiscard]] constexpr std::uint64_t finish() const noexcept {
    detail::SipState s = s_;
    // Last block: the 0..7 pending bytes, and the message length mod 256 in the top byte (paper §2).
    const std::uint64_t b = (std::uint64_t{length_mod_256_} << 56) | pending_;
    s.compress(b);
    s.v2 ^= 0xffu;
    for (int r = 0; r < 4; ++r) s.round();
    return s.v0 ^ s.v1 ^ s.v2 ^ s.v3;
  }

 private:
  // Only the length mod 256 enters the tag, and the number of pending bytes is that length mod 8.
  constexpr unsigned pending_bytes() const noexcept { return length_mod_256_ & 7u; }

  constexpr void push_byte(std::uint8_t byte) noexcept {
    pending_ |= std::uint64_t{byte} << (8u * pending_bytes());
    length_mod_256_ = static_cast<std::uint8_t>(length_mod_256_ + 1u);
    if (pending_bytes() == 0) {
      s_.compress(pending_);
      pending_ = 0;
    }
  }

  detail::SipState s_{};
  std::uint64_t pending_{0};  // bytes of the current partial word, least significant first
  std::uint8_t length_mod_256_{0};
};

// One-shot SipHash-2-4 of a message.
[[nodiscard]] constexpr std::uint64_t siphash24(std::span<const std::uint8_t, SipHash24::kKeyBytes> key,
                                                std::span<const std::uint8_t> message) noexcept {
  SipHash24 h(key);
  h.update(message);
  return h.finish();
}

}  // namespace gyrostab::firmware::link
