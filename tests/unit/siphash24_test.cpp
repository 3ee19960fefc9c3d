// SipHash-2-4 (firmware/link/siphash24.hpp) against the published vectors and an independent implementation.
//
// 1. The 64 vectors of the SipHash reference implementation (github.com/veorq/SipHash, vectors.h,
//    vectors_sip64): key 00 01 .. 0f, message 00 01 .. n-1 for n = 0..63. The reference stores each tag as
//    8 bytes least significant first; they are written here as those bytes read little-endian, which is the
//    64-bit word siphash24() returns. n = 15 is the worked example of Aumasson & Bernstein 2012, appendix A.
// 2. 10 000 random keys and messages of 0..300 bytes (fixed seed) against libsodium's
//    crypto_shorthash_siphash24, which was written apart from this one.
// 3. update() over random splits of a message (empty pieces included) equals the one-shot tag.
// Exact 64-bit equality everywhere: one wrong rotation or constant changes every tag.
#include "firmware/link/siphash24.hpp"

#include <gtest/gtest.h>
#include <sodium.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sim/random/seeded_rng.hpp"

namespace gyrostab::firmware::link {
namespace siphash24_test {

constexpr std::array<std::uint64_t, 64> kReferenceVectors = {
    0x726fdb47dd0e0e31ULL, 0x74f839c593dc67fdULL, 0x0d6c8009d9a94f5aULL, 0x85676696d7fb7e2dULL,  // n = 0..3
    0xcf2794e0277187b7ULL, 0x18765564cd99a68dULL, 0xcbc9466e58fee3ceULL, 0xab0200f58b01d137ULL,  // n = 4..7
    0x93f5f5799a932462ULL, 0x9e0082df0ba9e4b0ULL, 0x7a5dbbc594ddb9f3ULL, 0xf4b32f46226bada7ULL,  // n = 8..11
    0x751e8fbc860ee5fbULL, 0x14ea5627c0843d90ULL, 0xf723ca908e7af2eeULL, 0xa129ca6149be45e5ULL,  // n = 12..15
    0x3f2acc7f57c29bdbULL, 0x699ae9f52cbe4794ULL, 0x4bc1b3f0968dd39cULL, 0xbb6dc91da77961bdULL,  // n = 16..19
    0xbed65cf21aa2ee98ULL, 0xd0f2cbb02e3b67c7ULL, 0x93536795e3a33e88ULL, 0xa80c038ccd5ccec8ULL,  // n = 20..23
    0xb8ad50c6f649af94ULL, 0xbce192de8a85b8eaULL, 0x17d835b85bbb15f3ULL, 0x2f2e6163076bcfadULL,  // n = 24..27
    0xde4daaaca71dc9a5ULL, 0xa6a2506687956571ULL, 0xad87a3535c49ef28ULL, 0x32d892fad841c342ULL,  // n = 28..31
    0x7127512f72f27cceULL, 0xa7f32346f95978e3ULL, 0x12e0b01abb051238ULL, 0x15e034d40fa197aeULL,  // n = 32..35
    0x314dffbe0815a3b4ULL, 0x027990f029623981ULL, 0xcadcd4e59ef40c4dULL, 0x9abfd8766a33735cULL,  // n = 36..39
    0x0e3ea96b5304a7d0ULL, 0xad0c42d6fc585992ULL, 0x187306c89bc215a9ULL, 0xd4a60abcf3792b95ULL,  // n = 40..43
    0xf935451de4f21df2ULL, 0xa9538f0419755787ULL, 0xdb9acddff56ca510ULL, 0xd06c98cd5c0975ebULL,  // n = 44..47
    0xe612a3cb9ecba951ULL, 0xc766e62cfcadaf96ULL, 0xee64435a9752fe72ULL, 0xa192d576b245165aULL,  // n = 48..51
    0x0a8787bf8ecb74b2ULL, 0x81b3e73d20b49b6fULL, 0x7fa8220ba3b2eceaULL, 0x245731c13ca42499ULL,  // n = 52..55
    0xb78dbfaf3a8d83bdULL, 0xea1ad565322a1a0bULL, 0x60e61c23a3795013ULL, 0x6606d7e446282b93ULL,  // n = 56..59
    0x6ca4ecb15c5f91e1ULL, 0x9f626da15c9625f3ULL, 0xe51b38608ef25f57ULL, 0x958a324ceb064572ULL,  // n = 60..63
};

constexpr std::array<std::uint8_t, 16> reference_key() {
  std::array<std::uint8_t, 16> k{};
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<std::uint8_t>(i);
  return k;
}

constexpr std::array<std::uint8_t, 64> reference_message() {
  std::array<std::uint8_t, 64> m{};
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = static_cast<std::uint8_t>(i);
  return m;
}

std::uint64_t sodium_siphash24(std::span<const std::uint8_t, 16> key, std::span<const std::uint8_t> msg) {
  std::array<unsigned char, crypto_shorthash_siphash24_BYTES> out{};
  crypto_shorthash_siphash24(out.data(), msg.data(), msg.size(), key.data());
  std::uint64_t w = 0;
  for (std::size_t i = out.size(); i-- > 0;) w = (w << 8) | out[i];
  return w;
}

// The header promises constexpr: the first and last reference vectors, evaluated by the compiler.
constexpr std::array<std::uint8_t, 16> kKey = reference_key();
constexpr std::array<std::uint8_t, 64> kMessage = reference_message();
static_assert(siphash24(kKey, std::span(kMessage).first(0)) == kReferenceVectors[0]);
static_assert(siphash24(kKey, std::span(kMessage).first(63)) == kReferenceVectors[63]);

TEST(SipHash24, ReferenceVectors) {
  for (std::size_t n = 0; n < kReferenceVectors.size(); ++n)
    EXPECT_EQ(siphash24(kKey, std::span(kMessage).first(n)), kReferenceVectors[n]) << "n = " << n;
}

TEST(SipHash24, PaperAppendixExample) {
  EXPECT_EQ(siphash24(kKey, std::span(kMessage).first(15)), 0xa129ca6149be45e5ULL);
}

// The table itself against libsodium, so a transcription error in it could not pass unnoticed.
TEST(SipHash24, ReferenceVectorsAgreeWithLibsodium) {
  ASSERT_GE(sodium_init(), 0);
  EXPECT_EQ(sodium_siphash24(kKey, std::span(kMessage).first(0)), kReferenceVectors[0]);
  EXPECT_EQ(sodium_siphash24(kKey, std::span(kMessage).first(63)), kReferenceVectors[63]);
  for (std::size_t n = 0; n < kReferenceVectors.size(); ++n)
    EXPECT_EQ(sodium_siphash24(kKey, std::span(kMessage).first(n)), kReferenceVectors[n]) << "n = " << n;
}

struct RandomCase {
  std::array<std::uint8_t, 16> key{};
  std::vector<std::uint8_t> message;
};

RandomCase random_case(random::SeededRng& rng, std::size_t max_length) {
  RandomCase c;
  for (auto& b : c.key) b = static_cast<std::uint8_t>(rng.next());
  c.message.resize(static_cast<std::size_t>(rng.next() % (max_length + 1)));
  for (auto& b : c.message) b = static_cast<std::uint8_t>(rng.next() >> 56);
  return c;
}

TEST(SipHash24, RandomKeysAndMessagesAgreeWithLibsodium) {
  ASSERT_GE(sodium_init(), 0);
  random::SeededRng rng(20120924);
  for (int i = 0; i < 10000; ++i) {
    const RandomCase c = random_case(rng, 300);
    ASSERT_EQ(siphash24(c.key, c.message), sodium_siphash24(c.key, c.message))
        << "case " << i << ", " << c.message.size() << " bytes";
  }
}

// Every length 0..300 at least once, since the random lengths above need not hit each tail length.
TEST(SipHash24, EveryLengthUpTo300AgreesWithLibsodium) {
  ASSERT_GE(sodium_init(), 0);
  random::SeededRng rng(300);
  std::array<std::uint8_t, 16> key{};
  for (auto& b : key) b = static_cast<std::uint8_t>(rng.next());
  std::vector<std::uint8_t> msg(300);
  for (auto& b : msg) b = static_cast<std::uint8_t>(rng.next());
  for (std::size_t n = 0; n <= msg.size(); ++n)
    ASSERT_EQ(siphash24(key, std::span(msg).first(n)), sodium_siphash24(key, std::span(msg).first(n)))
        << n << " bytes";
}

TEST(SipHash24, IncrementalOverRandomSplitsEqualsOneShot) {
  random::SeededRng rng(4242);
  for (int i = 0; i < 2000; ++i) {
    const RandomCase c = random_case(rng, 300);
    const std::uint64_t one_shot = siphash24(c.key, c.message);
    SipHash24 h(c.key);
    std::size_t at = 0;
    while (at < c.message.size()) {
      // Pieces of 0..17 bytes: empty updates, sub-word pieces and pieces across word boundaries.
      const std::size_t piece = std::min<std::size_t>(rng.next() % 18, c.message.size() - at);
      h.update(std::span(c.message).subspan(at, piece));
      at += piece;
    }
    h.update({});
    ASSERT_EQ(h.finish(), one_shot) << "case " << i << ", " << c.message.size() << " bytes";
  }
}

TEST(SipHash24, ByteAtATimeMatchesReferenceVectors) {
  for (std::size_t n = 0; n < kReferenceVectors.size(); ++n) {
    SipHash24 h(kKey);
    for (std::size_t i = 0; i < n; ++i) h.update(std::span(kMessage).subspan(i, 1));
    EXPECT_EQ(h.finish(), kReferenceVectors[n]) << "n = " << n;
  }
}

// finish() leaves the state alone: tagging a prefix and continuing gives the tag of the whole message.
TEST(SipHash24, FinishDoesNotDisturbTheState) {
  SipHash24 h(kKey);
  h.update(std::span(kMessage).first(13));
  EXPECT_EQ(h.finish(), kReferenceVectors[13]);
  h.update(std::span(kMessage).subspan(13, 50));
  EXPECT_EQ(h.finish(), kReferenceVectors[63]);
}

}  // namespace siphash24_test
}  // namespace gyrostab::firmware::link
