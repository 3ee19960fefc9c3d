// The plant's generator (sim/random/seeded_rng.hpp): reference vectors, streams, and the moments of its
// uniform and Gaussian draws (5-sigma bounds over 1e6 draws, fixed seeds).
#include "sim/random/seeded_rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace gyrostab {
namespace seeded_rng_test {

using random::SeededRng;

TEST(SeededRng, SplitMix64MatchesTheReferenceOutputsForSeed1234567) {
  // Published first outputs of Vigna's splitmix64.c for seed 1234567 (also Rosetta Code's reference).
  std::uint64_t x = 1234567;
  for (const std::uint64_t want : {6457827717110365317ULL, 3203168211198807973ULL, 9817491932198370423ULL,
                                   4593380528125082431ULL, 16408922859458223821ULL})
    EXPECT_EQ(random::splitmix64_next(x), want);
}

TEST(SeededRng, Xoshiro256StarStarSeedingNextJumpAndLongJumpMatchPhpsReference) {
  // php-src ext/random/tests/02_engine/xoshiro256starstar_value.phpt: Xoshiro256StarStar(1234) seeds the
  // state with four SplitMix64 outputs (as here), draws 10000, jump(), jumpLong(), then generate() == bytes
  // 1f197e9ca7969123 little-endian.
  SeededRng r(1234);
  for (int i = 0; i < 10000; ++i) r.next();
  r.jump();
  r.long_jump();
  EXPECT_EQ(r.next(), 0x239196a79c7e191fULL);
}

TEST(SeededRng, StreamKIsTheSeedJumpedKTimes) {
  SeededRng a(99);
  a.jump();
  a.jump();
  const SeededRng b(99, 2);
  EXPECT_EQ(a.state(), b.state());
  SeededRng c(99, 1), d(99, 2);
  int equal = 0;
  for (int i = 0; i < 1000; ++i) equal += c.next() == d.next();
  EXPECT_EQ(equal, 0);
}

TEST(SeededRng, UniformIsOnTheHalfOpenUnitIntervalWithMeanAndVarianceOfU01) {
  SeededRng r(7);
  const int n = 1000000;
  double s1 = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_EQ(std::ldexp(u, 53), std::floor(std::ldexp(u, 53)));  // a multiple of 2^-53
    s1 += u;
    s2 += u * u;
  }
  // mean: sd 1/√(12n) = 2.9e-4; E u² = 1/3 with sd √(4/45 /n) = 3.0e-4.
  EXPECT_NEAR(s1 / n, 0.5, 5 / std::sqrt(12.0 * n));
  EXPECT_NEAR(s2 / n, 1.0 / 3, 5 * std::sqrt(4.0 / 45 / n));
}

TEST(SeededRng, GaussianHasTheMomentsAndTailOfAStandardNormal) {
  SeededRng r(11);
  const int n = 1000000;
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  int beyond3 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.gaussian();
    s1 += x;
    s2 += x * x;
    s3 += x * x * x;
    s4 += x * x * x * x;
    beyond3 += std::abs(x) > 3.0;
  }
  const double sn = std::sqrt(static_cast<double>(n));
  // Standard errors: mean 1, E x² √2, E x³ √15, E x⁴ √96 (= √(E x⁸ − (E x⁴)²)), all over √n.
  EXPECT_NEAR(s1 / n, 0.0, 5 / sn);
  EXPECT_NEAR(s2 / n, 1.0, 5 * std::sqrt(2.0) / sn);
  EXPECT_NEAR(s3 / n, 0.0, 5 * std::sqrt(15.0) / sn);
  EXPECT_NEAR(s4 / n, 3.0, 5 * std::sqrt(96.0) / sn);
  // P(|x| > 3) = 2.6998e-3, binomial sd √(p(1 − p)/n) = 5.2e-5.
  const double p = 2.6997960632601866e-3;
  EXPECT_NEAR(static_cast<double>(beyond3) / n, p, 5 * std::sqrt(p * (1 - p) / n));
}

}  // namespace seeded_rng_test
}  // namespace gyrostab
