// The firmware's deterministic cos, sin, exp, expm1, log (firmware/math/deterministic_math.hpp): the
// special values of C99 Annex F bit for bit, and the error against glibc (≤ 1 ulp nearly everywhere,
// correctly rounded in most cases) over ≥ 10^6 seeded samples per range, bounded by 2 ulp.
#include "firmware/math/deterministic_math.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <random>

namespace gyrostab {
namespace deterministic_math_test {

namespace dm = firmware::math;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kSamples = 1'000'000;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Distance in representable doubles (−0 and +0 coincide); NaN against NaN is 0, NaN against a number huge.
double ulp_distance(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0.0 : 1e300;
  const std::uint64_t ma = bits(a) & 0x7fffffffffffffffULL;
  const std::uint64_t mb = bits(b) & 0x7fffffffffffffffULL;
  if (std::signbit(a) != std::signbit(b)) return static_cast<double>(ma) + static_cast<double>(mb);
  return static_cast<double>(ma > mb ? ma - mb : mb - ma);
}

struct Worst {
  double ulp{0.0};
  double x{0.0};
};

// Samples x = draw(rng) kSamples times and returns the largest ulp distance of f(x) from ref(x).
template <class F, class Ref, class Draw>
Worst max_ulp(const char* label, F f, Ref ref, Draw draw, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Worst w;
  for (int i = 0; i < kSamples; ++i) {
    const double x = draw(rng);
    const double u = ulp_distance(f(x), ref(x));
    if (u > w.ulp) w = {u, x};
  }
  std::printf("  %-34s max %.0f ulp (at x = %.17g)\n", label, w.ulp, w.x);
  return w;
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// |x| log-uniform in [2^lo, 2^hi], random sign.
double log_uniform(std::mt19937_64& rng, double lo, double hi) {
  const double x = std::exp2(uniform(rng, lo, hi));
  return (rng() & 1) ? -x : x;
}

double cos_ref(double x) { return std::cos(x); }
double sin_ref(double x) { return std::sin(x); }
double exp_ref(double x) { return std::exp(x); }
double expm1_ref(double x) { return std::expm1(x); }
double log_ref(double x) { return std::log(x); }
double cos_dm(double x) { return dm::cos(x); }
double sin_dm(double x) { return dm::sin(x); }
double exp_dm(double x) { return dm::exp(x); }
double expm1_dm(double x) { return dm::expm1(x); }
double log_dm(double x) { return dm::log(x); }

constexpr double kMaxUlp = 2.0;

TEST(DeterministicMath, SinCosSpecialValues) {
  EXPECT_TRUE(std::isnan(dm::sin(kNaN)));
  EXPECT_TRUE(std::isnan(dm::cos(kNaN)));
  EXPECT_TRUE(std::isnan(dm::sin(kInf)));
  EXPECT_TRUE(std::isnan(dm::sin(-kInf)));
  EXPECT_TRUE(std::isnan(dm::cos(kInf)));
  EXPECT_TRUE(std::isnan(dm::cos(-kInf)));
  EXPECT_EQ(bits(dm::sin(0.0)), bits(0.0));
  EXPECT_EQ(bits(dm::sin(-0.0)), bits(-0.0));
  EXPECT_EQ(dm::cos(0.0), 1.0);
  EXPECT_EQ(dm::cos(-0.0), 1.0);
  const double denorm = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(bits(dm::sin(-denorm)), bits(-denorm));
  EXPECT_EQ(dm::cos(denorm), 1.0);
  // Values of the same bits as glibc (correctly rounded here) at a few quadrant boundaries.
  for (const double x : {1.0, -1.0, 3.0, 1e22, -1e300, std::numeric_limits<double>::max()}) {
    EXPECT_LE(ulp_distance(dm::sin(x), std::sin(x)), 1.0) << x;
    EXPECT_LE(ulp_distance(dm::cos(x), std::cos(x)), 1.0) << x;
  }
}

TEST(DeterministicMath, ExpSpecialValues) {
  EXPECT_TRUE(std::isnan(dm::exp(kNaN)));
  EXPECT_EQ(dm::exp(kInf), kInf);
  EXPECT_EQ(bits(dm::exp(-kInf)), bits(0.0));
  EXPECT_EQ(dm::exp(0.0), 1.0);
  EXPECT_EQ(dm::exp(-0.0), 1.0);
  EXPECT_EQ(dm::exp(710.0), kInf);
  EXPECT_EQ(dm::exp(0x1.62e42fefa39efp+9), std::exp(0x1.62e42fefa39efp+9));  // largest finite result
  EXPECT_EQ(dm::exp(std::nextafter(0x1.62e42fefa39efp+9, kInf)), kInf);
  EXPECT_EQ(bits(dm::exp(-746.0)), bits(0.0));
  EXPECT_EQ(bits(dm::exp(-1e300)), bits(0.0));
  // Around the smallest subnormal, e^x = 2^-1074 and 2^-1075 (rounds to 0, ties to even).
  for (const double x : {-745.0, -745.1332191019411, -745.13321910194122, -744.44007192138122, -708.5, -709.0,
                         -730.0})
    EXPECT_EQ(bits(dm::exp(x)), bits(std::exp(x))) << x;
}

TEST(DeterministicMath, Expm1SpecialValues) {
  EXPECT_TRUE(std::isnan(dm::expm1(kNaN)));
  EXPECT_EQ(dm::expm1(kInf), kInf);
  EXPECT_EQ(dm::expm1(-kInf), -1.0);
  EXPECT_EQ(bits(dm::expm1(0.0)), bits(0.0));
  EXPECT_EQ(bits(dm::expm1(-0.0)), bits(-0.0));
  EXPECT_EQ(dm::expm1(1e-300), 1e-300);
  EXPECT_EQ(dm::expm1(-1e-300), -1e-300);
  const double denorm = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(dm::expm1(denorm), denorm);
  EXPECT_EQ(dm::expm1(-50.0), -1.0);
  EXPECT_EQ(dm::expm1(710.0), kInf);
  EXPECT_EQ(dm::expm1(0x1.62e42fefa39efp+9), std::expm1(0x1.62e42fefa39efp+9));
}

TEST(DeterministicMath, LogSpecialValues) {
  EXPECT_TRUE(std::isnan(dm::log(kNaN)));
  EXPECT_TRUE(std::isnan(dm::log(-1.0)));
  EXPECT_TRUE(std::isnan(dm::log(-kInf)));
  EXPECT_TRUE(std::isnan(dm::log(-std::numeric_limits<double>::denorm_min())));
  EXPECT_EQ(dm::log(0.0), -kInf);
  EXPECT_EQ(dm::log(-0.0), -kInf);
  EXPECT_EQ(dm::log(kInf), kInf);
  EXPECT_EQ(bits(dm::log(1.0)), bits(0.0));
  for (const double x : {std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::min(),
                         std::numeric_limits<double>::max(), 2.0, 0.5, 10.0, std::nextafter(1.0, 0.0),
                         std::nextafter(1.0, 2.0)})
    EXPECT_LE(ulp_distance(dm::log(x), std::log(x)), 1.0) << x;
}

TEST(DeterministicMath, SinCosMatchGlibcWithinTwoUlp) {
  const auto small = [](std::mt19937_64& r) { return uniform(r, -10.0, 10.0); };
  const auto medium = [](std::mt19937_64& r) { return uniform(r, -1e5, 1e5); };
  const auto tiny = [](std::mt19937_64& r) { return uniform(r, -1e-8, 1e-8); };
  const auto near_limit = [](std::mt19937_64& r) { return uniform(r, 5e5, 2e6); };  // both reductions
  const auto large = [](std::mt19937_64& r) { return log_uniform(r, 20.0, 1023.9); };  // Payne–Hanek
  EXPECT_LE(max_ulp("cos [-10, 10]", cos_dm, cos_ref, small, 1).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("sin [-10, 10]", sin_dm, sin_ref, small, 2).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("cos [-1e5, 1e5]", cos_dm, cos_ref, medium, 3).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("sin [-1e5, 1e5]", sin_dm, sin_ref, medium, 4).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("cos |x| < 1e-8", cos_dm, cos_ref, tiny, 5).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("sin |x| < 1e-8", sin_dm, sin_ref, tiny, 6).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("cos [5e5, 2e6]", cos_dm, cos_ref, near_limit, 7).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("sin [5e5, 2e6]", sin_dm, sin_ref, near_limit, 8).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("cos 2^20 < |x| < 2^1023.9", cos_dm, cos_ref, large, 9).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("sin 2^20 < |x| < 2^1023.9", sin_dm, sin_ref, large, 10).ulp, kMaxUlp);
}

// Where the reduction cancels most: the doubles nearest k·π/2 (and their neighbours) for k < 2^20, and the
// double closest to a multiple of π/2 (6381956970095103·2^797, r ≈ 2^-60.9).
TEST(DeterministicMath, SinCosNearMultiplesOfHalfPi) {
  const long double half_pi = 1.5707963267948966192313216916397514L;
  double worst = 0.0;
  for (long k = 1; k < (1L << 20); ++k) {
    const double x0 = static_cast<double>(static_cast<long double>(k) * half_pi);
    for (const double x : {x0, std::nextafter(x0, 0.0), std::nextafter(x0, kInf)}) {
      worst = std::max(worst, ulp_distance(dm::sin(x), std::sin(x)));
      worst = std::max(worst, ulp_distance(dm::cos(x), std::cos(x)));
    }
  }
  std::printf("  %-34s max %.0f ulp\n", "sin/cos near k·π/2, k < 2^20", worst);
  EXPECT_LE(worst, kMaxUlp);
  // Against the correctly rounded values (mpmath at 2000 bits), not std::cos: GCC folds std::cos of this
  // constant with MPFR (correctly rounded), clang calls glibc at run time, whose cos is 8 ulp off here
  // (-0x1.14ae72e6ba227p-61, glibc 2.36).
  const double hard = std::ldexp(6381956970095103.0, 797);
  EXPECT_EQ(dm::sin(hard), 1.0);
  EXPECT_LE(ulp_distance(dm::cos(hard), -0x1.14ae72e6ba22fp-61), 1.0);
}

TEST(DeterministicMath, ExpMatchesGlibcWithinTwoUlp) {
  const auto full = [](std::mt19937_64& r) { return uniform(r, -745.0, 710.0); };
  const auto unit = [](std::mt19937_64& r) { return uniform(r, -2.0, 2.0); };
  const auto subnormal = [](std::mt19937_64& r) { return uniform(r, -745.2, -708.0); };
  EXPECT_LE(max_ulp("exp [-745, 710]", exp_dm, exp_ref, full, 11).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("exp [-2, 2]", exp_dm, exp_ref, unit, 12).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("exp [-745.2, -708] (subnormal)", exp_dm, exp_ref, subnormal, 13).ulp, kMaxUlp);
}

TEST(DeterministicMath, Expm1MatchesGlibcWithinTwoUlp) {
  const double half_ln2 = 0x1.62e42fefa39efp-2;
  const auto full = [](std::mt19937_64& r) { return uniform(r, -40.0, 710.0); };
  const auto unit = [](std::mt19937_64& r) { return uniform(r, -3.0, 3.0); };
  const auto tiny = [](std::mt19937_64& r) { return log_uniform(r, -1074.0, std::log2(1e-5)); };
  const auto edge = [half_ln2](std::mt19937_64& r) {
    const double x = half_ln2 + uniform(r, -1e-3, 1e-3);
    return (r() & 1) ? -x : x;
  };
  EXPECT_LE(max_ulp("expm1 [-40, 710]", expm1_dm, expm1_ref, full, 14).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("expm1 [-3, 3]", expm1_dm, expm1_ref, unit, 15).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("expm1 |x| < 1e-5 (log-uniform)", expm1_dm, expm1_ref, tiny, 16).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("expm1 ±ln2/2 ± 1e-3", expm1_dm, expm1_ref, edge, 17).ulp, kMaxUlp);
}

TEST(DeterministicMath, LogMatchesGlibcWithinTwoUlp) {
  // Uniform over the bit patterns of positive finite doubles: every exponent, subnormals included.
  const auto all = [](std::mt19937_64& r) {
    return std::bit_cast<double>(r() % 0x7ff0000000000000ULL);
  };
  const auto subnormal = [](std::mt19937_64& r) {
    return std::bit_cast<double>(1 + r() % 0x000fffffffffffffULL);
  };
  const auto near_one = [](std::mt19937_64& r) { return 1.0 + uniform(r, -1e-3, 1e-3); };
  const auto octave = [](std::mt19937_64& r) { return uniform(r, 0.5, 2.0); };
  EXPECT_LE(max_ulp("log all positive doubles", log_dm, log_ref, all, 18).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("log subnormals", log_dm, log_ref, subnormal, 19).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("log 1 ± 1e-3", log_dm, log_ref, near_one, 20).ulp, kMaxUlp);
  EXPECT_LE(max_ulp("log [0.5, 2]", log_dm, log_ref, octave, 21).ulp, kMaxUlp);
}

// Constant evaluation gives the same bits as the run-time code (the compiler folds in IEEE double).
TEST(DeterministicMath, ConstexprEvaluationMatchesRunTime) {
  constexpr double c = dm::cos(2.5);
  constexpr double s = dm::sin(1e300);
  constexpr double e = dm::exp(-744.0);
  constexpr double m = dm::expm1(0.3);
  constexpr double l = dm::log(1e-310);
  volatile double in[5] = {2.5, 1e300, -744.0, 0.3, 1e-310};
  EXPECT_EQ(bits(c), bits(dm::cos(in[0])));
  EXPECT_EQ(bits(s), bits(dm::sin(in[1])));
  EXPECT_EQ(bits(e), bits(dm::exp(in[2])));
  EXPECT_EQ(bits(m), bits(dm::expm1(in[3])));
  EXPECT_EQ(bits(l), bits(dm::log(in[4])));
}

}  // namespace deterministic_math_test
}  // namespace gyrostab
