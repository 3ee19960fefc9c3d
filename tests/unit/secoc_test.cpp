// SecOC-like frame authentication (firmware/link/secoc.hpp): what a forger without the key can and cannot do
// to the link, and that loss and wrap of the truncated freshness value do not break the genuine peer.
// Payloads are ActuatorFrame bytes, so "rejected" means "the plant does not apply this command".
// Deterministic: every random key, payload and forgery comes from a fixed seed.
#include "firmware/link/secoc.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

#include "firmware/link/siphash24.hpp"
#include "tests/support/union_frames.hpp"
#include "sim/random/seeded_rng.hpp"

namespace gyrostab::firmware::link {
namespace secoc_test {

constexpr std::uint32_t kDataId = 0x1A0;
constexpr std::uint64_t kSession = 0x5E55'1D00'C0FF'EE01ULL;
constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();

constexpr SecOcProfile kFull{8, 8, 1024};  // whole MAC, whole freshness value
constexpr SecOcProfile kFour{4, 4, 1024};  // 4-byte MAC, 4-byte freshness
constexpr SecOcProfile kCan{4, 1, 16};     // a short trailer: 4-byte MAC, 1-byte freshness
constexpr SecOcProfile kWide{8, 8, kMax};  // no window at all: only the MAC protects

Key128 random_key(random::SeededRng& rng) {
  std::array<std::uint8_t, 16> b{};
  for (auto& x : b) x = static_cast<std::uint8_t>(rng.next());
  return Key128::from_bytes(b);
}

using Payload = std::array<std::uint8_t, sizeof(msg::ActuatorFrame)>;

Payload command(std::uint64_t tick, double torque_Nm) {
  msg::ActuatorFrame f;
  f.tick = tick;
  f.sequence = static_cast<std::uint32_t>(tick);
  f.gimbal_torque_Nm[msg::kAxis2] = torque_Nm;
  f.precession_brake = 0.25;
  Payload p{};
  std::memcpy(p.data(), &f, sizeof f);
  return p;
}

Payload random_payload(random::SeededRng& rng) {
  Payload p{};
  for (auto& b : p) b = static_cast<std::uint8_t>(rng.next());
  return p;
}

struct Frame {
  Payload payload{};
  SecuredFields fields{};
};

struct Link {
  Key128 key;
  SecOcSender tx;
  SecOcReceiver rx;

  Link(const SecOcProfile& p, std::uint64_t seed)
      : key(make_key(seed)), tx(key, kDataId, kSession, p), rx(key, kDataId, kSession, p) {}

  static Key128 make_key(std::uint64_t seed) {
    random::SeededRng rng(seed);
    return random_key(rng);
  }

  Frame send(double torque_Nm = 1.5) {
    Frame f;
    f.payload = command(tx.next_freshness(), torque_Nm);
    f.fields = tx.protect(f.payload);
    return f;
  }
  Verdict deliver(const Frame& f) { return rx.verify(f.payload, f.fields); }
};

// The header promises constexpr: a round trip evaluated by the compiler.
constexpr bool constexpr_round_trip() {
  const std::array<std::uint8_t, 16> kb{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
  const Key128 key = Key128::from_bytes(kb);
  SecOcSender tx(key, kDataId, kSession, kCan);
  SecOcReceiver rx(key, kDataId, kSession, kCan);
  const std::array<std::uint8_t, 3> payload{7, 8, 9};
  bool ok = true;
  for (int i = 0; i < 300; ++i) ok = ok && rx.verify(payload, tx.protect(payload)) == Verdict::kOk;
  return ok && rx.latest_accepted() == 300;
}
static_assert(constexpr_round_trip());

TEST(SecOc, ProfilesAreChecked) {
  EXPECT_TRUE(check(kFull).ok);
  EXPECT_TRUE(check(kFour).ok);
  EXPECT_TRUE(check(kCan).ok);
  EXPECT_TRUE(check(kWide).ok);
  EXPECT_TRUE(check(SecOcProfile{1, 0, 1}).ok);
  EXPECT_TRUE(check(SecOcProfile{4, 1, 256}).ok);
  EXPECT_FALSE(check(SecOcProfile{0, 8, 16}).ok);
  EXPECT_FALSE(check(SecOcProfile{9, 8, 16}).ok);
  EXPECT_FALSE(check(SecOcProfile{8, 9, 16}).ok);
  EXPECT_FALSE(check(SecOcProfile{8, 8, 0}).ok);
  EXPECT_FALSE(check(SecOcProfile{4, 1, 257}).ok);  // one byte rebuilds at most 256 values ahead
  EXPECT_FALSE(check(SecOcProfile{4, 0, 2}).ok);    // no freshness bytes: only the next value
  const SecOcProfile c = clamped(SecOcProfile{0, 12, 0});
  EXPECT_EQ(c.mac_bytes, 1);
  EXPECT_EQ(c.freshness_bytes, 8);
  EXPECT_EQ(c.acceptance_window, 1u);
  EXPECT_EQ(clamped(SecOcProfile{4, 1, 1000}).acceptance_window, 256u);
}

// The canonical encoding, byte by byte, so that a host-side implementation has one definition to match.
TEST(SecOc, AuthenticatorIsSipHashOverTheCanonicalEncoding) {
  random::SeededRng rng(1);
  const Key128 key = random_key(rng);
  const Payload p = random_payload(rng);
  std::vector<std::uint8_t> m = {0xA0, 0x01, 0x00, 0x00,                           // data id 0x1A0
                                 0x01, 0xEE, 0xFF, 0xC0, 0x00, 0x1D, 0x55, 0x5E,   // session id
                                 0x2A, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00};  // freshness 42
  m.insert(m.end(), p.begin(), p.end());
  EXPECT_EQ(authenticator(key, kDataId, kSession, 42, p), siphash24(key.bytes, m));
}

// The transmitted MAC is the leading mac_bytes bytes of SipHash's output string (least significant first).
TEST(SecOc, TruncatedFieldsTravelLittleEndian) {
  const std::uint64_t mac = 0x0123456789ABCDEFULL;
  std::array<std::uint8_t, 4> wire{};
  store_le(truncate_mac(mac, 4), wire);
  EXPECT_EQ(wire, (std::array<std::uint8_t, 4>{0xEF, 0xCD, 0xAB, 0x89}));
  EXPECT_EQ(load_le(wire), 0x89ABCDEFULL);
  std::array<std::uint8_t, 8> all{};
  store_le(mac, all);
  EXPECT_EQ(load_le(all), mac);
}

TEST(SecOc, MacEqualComparesOnlyTheTransmittedBytes) {
  EXPECT_TRUE(mac_equal(0x1122334455667788ULL, 0x1122334455667788ULL, 8));
  EXPECT_TRUE(mac_equal(0xFFFFFFFF55667788ULL, 0x55667788ULL, 4));
  EXPECT_TRUE(mac_equal(0, 0, 1));
  for (std::size_t n = 1; n <= 8; ++n)
    for (unsigned bit = 0; bit < 8 * n; ++bit)
      EXPECT_FALSE(mac_equal(0x0123456789ABCDEFULL, 0x0123456789ABCDEFULL ^ (std::uint64_t{1} << bit), n))
          << n << " bytes, bit " << bit;
}

TEST(SecOc, ReconstructionFollowsTheSecOcRule) {
  // Received low bits greater than the latest's: same upper bits.
  EXPECT_EQ(reconstruct_freshness(0x1205, 0x07, 1).value, 0x1207u);
  // Not greater: one wrap of the truncated counter.
  EXPECT_EQ(reconstruct_freshness(0x12FE, 0x01, 1).value, 0x1301u);
  EXPECT_EQ(reconstruct_freshness(0x1205, 0x05, 1).value, 0x1305u);
  // Only the transmitted bytes count.
  EXPECT_EQ(reconstruct_freshness(0x1205, 0xAB07, 1).value, 0x1207u);
  EXPECT_EQ(reconstruct_freshness(0x0001'FFFF'FFF0ULL, 0x10, 4).value, 0x0002'0000'0010ULL);
  // No freshness bytes: always the next value.
  EXPECT_EQ(reconstruct_freshness(41, 0, 0).value, 42u);
  // Whole value sent: taken as it is.
  EXPECT_EQ(reconstruct_freshness(41, 7, 8).value, 7u);
  // Past 2^64 - 1: not representable.
  EXPECT_FALSE(reconstruct_freshness(kMax - 3, 0x01, 1).representable);
  EXPECT_TRUE(reconstruct_freshness(kMax - 3, 0xFF, 1).representable);
}

TEST(SecOc, RoundTrip) {
  for (const SecOcProfile& p : {kFull, kFour, kCan, kWide, SecOcProfile{1, 0, 1}}) {
    Link link(p, 2);
    for (int i = 1; i <= 50; ++i) ASSERT_EQ(link.deliver(link.send()), Verdict::kOk) << "frame " << i;
    EXPECT_EQ(link.rx.latest_accepted(), 50u);
    EXPECT_EQ(link.rx.counters().ok, 50u);
    EXPECT_EQ(link.rx.counters().rejected(), 0u);
  }
}

// Every single-bit change of what the MAC covers or of what the frame carries is refused and leaves the
// receiver's state as it was. Profiles with at least 4 MAC bytes: with a 1-byte MAC each flip would pass
// with probability 2^-8, which is the truncation's documented strength, not a defect.
class SecOcBitFlip : public ::testing::TestWithParam<SecOcProfile> {};

TEST_P(SecOcBitFlip, EverySingleBitFlipIsRejected) {
  const SecOcProfile p = GetParam();
  Link link(p, 3);
  for (int i = 0; i < 41; ++i) ASSERT_EQ(link.deliver(link.send()), Verdict::kOk);
  const Frame good = link.send(-2.0);
  const std::uint64_t latest = link.rx.latest_accepted();

  auto refused = [&](SecOcReceiver rx, const Payload& payload, const SecuredFields& f) {
    const Verdict v = rx.verify(payload, f);
    return v != Verdict::kOk && rx.latest_accepted() == latest;
  };

  for (std::size_t bit = 0; bit < 8 * good.payload.size(); ++bit) {
    Payload bad = good.payload;
    bad[bit / 8] = static_cast<std::uint8_t>(bad[bit / 8] ^ (1u << (bit % 8)));
    EXPECT_TRUE(refused(link.rx, bad, good.fields)) << "payload bit " << bit;
  }
  for (unsigned bit = 0; bit < 32; ++bit) {
    // The data id is not sent: the frame arrives on a channel whose data id differs in one bit.
    SecOcReceiver other(link.key, kDataId ^ (1u << bit), kSession, p, latest);
    EXPECT_EQ(other.verify(good.payload, good.fields), Verdict::kBadMac) << "data id bit " << bit;
    EXPECT_EQ(other.latest_accepted(), latest);
  }
  for (unsigned bit = 0; bit < 64; ++bit) {
    SecuredFields f = good.fields;
    f.session_id ^= std::uint64_t{1} << bit;
    SecOcReceiver rx = link.rx;
    EXPECT_EQ(rx.verify(good.payload, f), Verdict::kWrongSession) << "session bit " << bit;
    EXPECT_EQ(rx.latest_accepted(), latest);
  }
  for (unsigned bit = 0; bit < 8u * p.freshness_bytes; ++bit) {
    SecuredFields f = good.fields;
    f.freshness ^= std::uint64_t{1} << bit;
    EXPECT_TRUE(refused(link.rx, good.payload, f)) << "freshness bit " << bit;
  }
  for (unsigned bit = 0; bit < 8u * p.mac_bytes; ++bit) {
    SecuredFields f = good.fields;
    f.mac ^= std::uint64_t{1} << bit;
    SecOcReceiver rx = link.rx;
    EXPECT_EQ(rx.verify(good.payload, f), Verdict::kBadMac) << "mac bit " << bit;
    EXPECT_EQ(rx.latest_accepted(), latest);
  }
  // None of it cost the genuine frame its place.
  EXPECT_EQ(link.deliver(good), Verdict::kOk);
}

INSTANTIATE_TEST_SUITE_P(Profiles, SecOcBitFlip, ::testing::Values(kFull, kFour, kCan, kWide));

TEST(SecOc, WrongKeyIsRejected) {
  Link link(kFour, 4);
  const Frame f = link.send();
  random::SeededRng rng(40);
  SecOcReceiver stranger(random_key(rng), kDataId, kSession, kFour);
  EXPECT_EQ(stranger.verify(f.payload, f.fields), Verdict::kBadMac);
  for (std::size_t bit = 0; bit < 128; ++bit) {
    Key128 near = link.key;
    near.bytes[bit / 8] = static_cast<std::uint8_t>(near.bytes[bit / 8] ^ (1u << (bit % 8)));
    SecOcReceiver rx(near, kDataId, kSession, kFour);
    EXPECT_EQ(rx.verify(f.payload, f.fields), Verdict::kBadMac) << "key bit " << bit;
  }
  EXPECT_EQ(link.deliver(f), Verdict::kOk);
}

TEST(SecOc, ReplayOfAnOldFrameIsRejected) {
  for (const SecOcProfile& p : {kFull, kFour, kCan}) {
    Link link(p, 5);
    std::vector<Frame> sent;
    for (int i = 0; i < 5; ++i) {
      sent.push_back(link.send());
      ASSERT_EQ(link.deliver(sent.back()), Verdict::kOk);
    }
    EXPECT_EQ(link.deliver(sent[2]), Verdict::kStale) << "replay of frame 3";
    EXPECT_EQ(link.deliver(sent[4]), Verdict::kStale) << "replay of the latest frame";
    EXPECT_EQ(link.rx.latest_accepted(), 5u);
    EXPECT_EQ(link.rx.counters().stale, 2u);
    EXPECT_EQ(link.deliver(link.send()), Verdict::kOk);
  }
}

// With a 1-byte freshness value, frames one period (256) old carry the same bits as new ones; they are still
// refused (the MAC covers the full value), whichever verdict names them.
TEST(SecOc, ReplayFromAnEarlierPeriodOfTheTruncatedCounterIsRejected) {
  Link link(kCan, 6);
  std::vector<Frame> sent;
  for (int i = 0; i < 300; ++i) {
    sent.push_back(link.send());
    ASSERT_EQ(link.deliver(sent.back()), Verdict::kOk);
  }
  for (std::size_t i = 0; i < sent.size(); ++i) {
    SecOcReceiver rx = link.rx;
    EXPECT_NE(rx.verify(sent[i].payload, sent[i].fields), Verdict::kOk) << "replay of frame " << i + 1;
    EXPECT_EQ(rx.latest_accepted(), 300u);
  }
  // Frame 44 = 300 - 256 carries the latest's very bits: read as one period old, hence stale.
  SecOcReceiver rx = link.rx;
  EXPECT_EQ(rx.verify(sent[43].payload, sent[43].fields), Verdict::kStale);
  EXPECT_EQ(link.deliver(link.send()), Verdict::kOk);
}

TEST(SecOc, OneByteFreshnessWrapsAcross300Frames) {
  Link link(kCan, 7);
  for (int i = 1; i <= 300; ++i) {
    const Frame f = link.send();
    ASSERT_LE(f.fields.freshness, 0xFFu);
    ASSERT_EQ(link.deliver(f), Verdict::kOk) << "frame " << i;
  }
  EXPECT_EQ(link.rx.latest_accepted(), 300u);
  EXPECT_EQ(link.rx.counters().ok, 300u);
}

// A genuine frame after N lost frames is N + 1 ahead: accepted for N < window, refused at N = window.
TEST(SecOc, LossOfFewerThanWindowFramesIsTolerated) {
  for (const SecOcProfile& p : {kFull, kFour, kCan, SecOcProfile{4, 1, 256}, SecOcProfile{2, 0, 1}}) {
    const std::uint64_t w = p.acceptance_window;
    Link link(p, 8);
    for (int i = 0; i < 250; ++i) ASSERT_EQ(link.deliver(link.send()), Verdict::kOk);
    for (std::uint64_t lost = 0; lost + 1 < w; ++lost) (void)link.send();
    ASSERT_EQ(link.deliver(link.send()), Verdict::kOk) << "after " << (w - 1) << " lost, window " << w;

    for (std::uint64_t lost = 0; lost < w; ++lost) (void)link.send();
    const std::uint64_t latest = link.rx.latest_accepted();
    const Frame f = link.send();
    EXPECT_NE(link.deliver(f), Verdict::kOk) << "after " << w << " lost, window " << w;
    EXPECT_EQ(link.rx.latest_accepted(), latest);
  }
}

TEST(SecOc, LossBeyondTheWindowIsNamedTooFarAheadNotStale) {
  // Latest 250 of a 1-byte counter, 20 frames lost: the bits wrapped, yet the frame is ahead, not a replay.
  Link link(kCan, 9);
  for (int i = 0; i < 250; ++i) ASSERT_EQ(link.deliver(link.send()), Verdict::kOk);
  for (int i = 0; i < 20; ++i) (void)link.send();
  EXPECT_EQ(link.deliver(link.send()), Verdict::kTooFarAhead);
  EXPECT_EQ(link.rx.latest_accepted(), 250u);
  // The host re-binds from a value learnt out of band; the link resumes.
  link.rx.rebind(kSession, link.tx.next_freshness() - 1);
  EXPECT_EQ(link.deliver(link.send()), Verdict::kOk);
}

// What plain sequence checks get wrong: one frame claiming a sequence 2^30 ahead must not move the receiver.
// It fails the MAC (it has no key), so the state does not move and the genuine next frame is accepted, with a
// window (refused as too far ahead) and without one (refused on its MAC).
TEST(SecOc, ForgedFrameFarAheadDoesNotLockOutTheGenuinePeer) {
  random::SeededRng rng(10);
  for (const SecOcProfile& p : {kFull, kFour, kWide}) {
    Link link(p, 11);
    for (int i = 0; i < 5; ++i) ASSERT_EQ(link.deliver(link.send()), Verdict::kOk);
    const std::uint64_t latest = link.rx.latest_accepted();
    SecuredFields forged{kSession, (latest + (std::uint64_t{1} << 30)) & low_bytes_mask(p.freshness_bytes),
                         rng.next() & low_bytes_mask(p.mac_bytes)};
    const Verdict v = link.rx.verify(command(latest + (1u << 30), 1e6), forged);
    EXPECT_NE(v, Verdict::kOk);
    EXPECT_EQ(v, p.acceptance_window == kMax ? Verdict::kBadMac : Verdict::kTooFarAhead);
    EXPECT_EQ(link.rx.latest_accepted(), latest);
    EXPECT_EQ(link.deliver(link.send()), Verdict::kOk) << "genuine next frame";
  }
}

// A forgery claiming exactly the next freshness value does not use that value up either.
TEST(SecOc, ForgedNextFrameDoesNotConsumeTheGenuineOne) {
  random::SeededRng rng(12);
  Link link(kCan, 13);
  for (int i = 0; i < 5; ++i) ASSERT_EQ(link.deliver(link.send()), Verdict::kOk);
  const SecuredFields forged{kSession, 6, rng.next() & 0xFFFF'FFFFu};
  EXPECT_EQ(link.rx.verify(command(6, 1e6), forged), Verdict::kBadMac);
  EXPECT_EQ(link.deliver(link.send()), Verdict::kOk);
  EXPECT_EQ(link.rx.latest_accepted(), 6u);
}

// Brute force of a 4-byte MAC: each forgery below reaches the MAC comparison (right session, freshness in
// the window) and passes with probability 2^-32, so 100 000 of them are expected to pass
// 100 000 · 2^-32 ≈ 2.3e-5 times, and the chance that any passes is about the same. The seed is fixed, so
// the outcome is fixed too: zero, and the genuine peer is unaffected.
TEST(SecOc, BruteForceOfAFourByteMacFails) {
  random::SeededRng rng(14);
  Link link(kCan, 15);
  for (int i = 0; i < 5; ++i) ASSERT_EQ(link.deliver(link.send()), Verdict::kOk);
  constexpr int kForgeries = 100000;
  int accepted = 0;
  for (int i = 0; i < kForgeries; ++i) {
    const std::uint64_t claim = 5 + 1 + rng.next() % kCan.acceptance_window;
    const SecuredFields forged{kSession, claim & 0xFFu, rng.next() & 0xFFFF'FFFFu};
    if (link.rx.verify(random_payload(rng), forged) == Verdict::kOk) ++accepted;
  }
  EXPECT_EQ(accepted, 0);
  EXPECT_EQ(link.rx.counters().bad_mac, static_cast<std::uint64_t>(kForgeries));
  EXPECT_EQ(link.rx.latest_accepted(), 5u);
  EXPECT_EQ(link.deliver(link.send()), Verdict::kOk);
}

// The session id is compared before the MAC: a genuine frame of another run (same key) is wrong_session;
// a frame with the right session id and a wrong MAC is bad_mac.
TEST(SecOc, FrameFromAnotherSessionIsWrongSession) {
  Link link(kFour, 16);
  SecOcSender earlier_run(link.key, kDataId, kSession ^ 0x77, kFour);
  const Payload p = command(1, 0.5);
  EXPECT_EQ(link.rx.verify(p, earlier_run.protect(p)), Verdict::kWrongSession);

  Frame f = link.send();
  f.fields.mac ^= 1u;
  EXPECT_EQ(link.deliver(f), Verdict::kBadMac);

  EXPECT_EQ(link.rx.counters().wrong_session, 1u);
  EXPECT_EQ(link.rx.counters().bad_mac, 1u);
  EXPECT_EQ(link.rx.counters().ok, 0u);
  EXPECT_EQ(link.rx.latest_accepted(), 0u);
}

TEST(SecOc, RebindToANewSessionKeepsTheCounters) {
  Link link(kFour, 17);
  ASSERT_EQ(link.deliver(link.send()), Verdict::kOk);
  const std::uint64_t next_session = kSession + 1;
  SecOcSender restarted(link.key, kDataId, next_session, kFour);
  const Payload p = command(1, 0.5);
  EXPECT_EQ(link.rx.verify(p, restarted.protect(p)), Verdict::kWrongSession);
  link.rx.rebind(next_session, 0);
  EXPECT_EQ(link.rx.verify(p, restarted.protect(p)), Verdict::kOk);
  EXPECT_EQ(link.rx.counters().ok, 2u);
  EXPECT_EQ(link.rx.counters().wrong_session, 1u);
}

TEST(SecOc, ExhaustedCounterNeverRepeatsAnAcceptedValue) {
  random::SeededRng rng(18);
  const Key128 key = random_key(rng);
  SecOcSender tx(key, kDataId, kSession, kFull, kMax);
  SecOcReceiver rx(key, kDataId, kSession, kFull, kMax - 1);
  const Payload p = command(1, 0.5);
  EXPECT_EQ(rx.verify(p, tx.protect(p)), Verdict::kOk);
  EXPECT_EQ(tx.next_freshness(), kMax);
  EXPECT_EQ(rx.verify(p, tx.protect(p)), Verdict::kStale);

  // Truncated: the value after 2^64 - 1 cannot be represented, so it is refused rather than wrapped to 0.
  SecOcReceiver rx1(key, kDataId, kSession, kCan, kMax);
  EXPECT_EQ(rx1.verify(p, SecuredFields{kSession, 0x00, 0}), Verdict::kTooFarAhead);
  EXPECT_EQ(rx1.latest_accepted(), kMax);
}

}  // namespace secoc_test
}  // namespace gyrostab::firmware::link
