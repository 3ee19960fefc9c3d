// The firmware's own cos, sin, exp, expm1 and log: one implementation compiled on the host (x86-64, SSE2)
// and on the target (Cortex-M7, double-precision FPU) so that every command that goes through them is
// bit-identical on both. The C libraries differ (glibc on the host, newlib on the target), and newlib's
// kernels use fused multiply-add where the FPU has one, so the same call gives different last bits. Here
// only IEEE-754 +, −, ×, / in double (round to nearest), comparisons and bit casts are used, in a fixed
// order; no libm call, no FMA. Build with -ffp-contract=off (the project does) so that the compiler does not
// fuse a × b + c on its own; the functions are constexpr, and GCC folds them to the same bits.
//
// Methods (all polynomials are truncated Taylor series with correctly rounded coefficients, by Horner):
//   cos, sin  x = k·π/2 + r, |r| ≲ π/4, r carried as a double-double hi + lo. For |x| < 2^19·π/2
//             Cody–Waite with π/2 in three parts (33 + 33 + 53 bits, so k·part is exact for k < 2^20 and the
//             first subtraction is exact). Beyond that Payne–Hanek: x·(2/π) mod 4 from a 1280-bit table of
//             2/π in 32-bit integer arithmetic (224-bit window × 53-bit mantissa), the fraction (128 bits)
//             times π/2 in double-double. Quadrant k mod 4 picks ±sin/±cos of r; kernels of degree 17 (sin)
//             and 18 (cos) on [−π/4, π/4], with the lo part entering to first order.
//   exp       x = k·ln2 + r with ln2 = hi (32 bits, k·hi exact) + lo, |r| ≤ ln2/2; e^r = (1 + r) + tail
//             with 1 + r held exactly as a two-sum and the rounding of r fed back, degree-13 tail; then ×2^k
//             built from the exponent bits, in two steps below 2^-1021 (the first exact, so the subnormal
//             result is rounded once).
//   expm1     |x| ≤ ln2/2: x + x²·q(x), degree 14, no cancellation. Otherwise the exp reduction and
//             2^k·(1 + r + tail) − 1 evaluated as a two-sum of 2^k·(1 + r)_hi and −1 plus the exact low parts,
//             so the cancellation at k = 1, −1 is exact. x < −38 → −1 (e^x below half an ulp of 1).
//   log       x = 2^e·m, m ∈ [√2/2, √2) (subnormals pre-scaled by 2^54), f = m − 1 exact, s = f/(2 + f),
//             log m = f − (f²/2 − s·(f²/2 + R(s²))), R of degree 20 in s (atanh series), then
//             e·ln2_hi + (e·ln2_lo + log m) with e·ln2_hi exact.
//
// Measured accuracy against glibc 2.36 (tests/unit/deterministic_math_test.cpp, 10^6 seeded samples per
// range; glibc is correctly rounded for nearly all of these, so 1 ulp here means "off by the last bit"):
//   cos, sin  ≤ 1 ulp on [−10, 10], [−1e5, 1e5], [5e5, 2e6] (both reductions), |x| < 1e-8 (0 ulp), and
//             2^20 ≤ |x| ≤ DBL_MAX (Payne–Hanek); also ≤ 1 ulp at the doubles nearest k·π/2, k < 2^21, and
//             0 ulp at 6381956970095103·2^797, a known worst case of the reduction (|r| ≈ 2^-61).
//   exp       ≤ 1 ulp on [−745, 710], subnormal results included
//   expm1     ≤ 1 ulp on [−40, 710], [−3, 3], around ±ln2/2; 0 ulp for |x| < 1e-5
//   log       ≤ 1 ulp over all positive doubles (subnormals included) and near 1
// Cost on x86-64 (-O2): about glibc's for cos, sin, exp, expm1 (7–14 ns); log ≈ 8 ns (glibc 3 ns, table
// driven); sin/cos for |x| > 8e5 ≈ 32 ns.
// Domain (C99 Annex F): NaN → NaN; cos, sin(±inf) = NaN, sin(±0) = ±0; exp(+inf) = +inf, exp(−inf) = +0,
// exp(x > 709.78…) = +inf; expm1(±0) = ±0, expm1(−inf) = −1; log(±0) = −inf, log(x < 0) = NaN,
// log(+inf) = +inf, log(1) = +0. No errno, no floating-point exceptions are relied on.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace gyrostab::firmware::math {

namespace detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr std::uint64_t kFracMask = 0x000fffffffffffffULL;

// ln2 with hi of 32 significant bits: k·hi is exact for |k| < 2^21, covering every exponent.
inline constexpr double kLn2Hi = 0x1.62e42feep-1;
inline constexpr double kLn2Lo = 0x1.a39ef35793c76p-33;
inline constexpr double kInvLn2 = 0x1.71547652b82fep+0;
inline constexpr double kHalfLn2 = 0x1.62e42fefa39efp-2;
// ln(DBL_MAX) rounded: the largest x with a finite e^x.
inline constexpr double kExpOverflow = 0x1.62e42fefa39efp+9;

// π/2 in three parts for Cody–Waite (33, 33 and 53 bits; residual ≈ 6e-38 relative).
inline constexpr double kPio2P1 = 0x1.921fb544p+0;
inline constexpr double kPio2P2 = 0x1.0b4611a6p-34;
inline constexpr double kPio2P3 = 0x1.3198a2e037073p-69;
// π/2 as a double-double for the Payne–Hanek fraction.
inline constexpr double kPio2Hi = 0x1.921fb54442d18p+0;
inline constexpr double kPio2Lo = 0x1.1a62633145c07p-54;
inline constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
inline constexpr double kPio4 = 0x1.921fb54442d18p-1;
// Above this the Cody–Waite k exceeds 2^19 and k·P1, k·P2 would stop being exact.
inline constexpr double kCodyWaiteLimit = 823549.0;

// 2/π = 0.a2f9836e 4e441529 … (hex), 1280 bits, enough for x up to DBL_MAX.
inline constexpr std::uint32_t kTwoOverPiBits[40] = {
    0xa2f9836eu, 0x4e441529u, 0xfc2757d1u, 0xf534ddc0u, 0xdb629599u, 0x3c439041u, 0xfe5163abu, 0xdebbc561u,
    0xb7246e3au, 0x424dd2e0u, 0x06492eeau, 0x09d1921cu, 0xfe1deb1cu, 0xb129a73eu, 0xe88235f5u, 0x2ebb4484u,
    0xe99c7026u, 0xb45f7e41u, 0x3991d639u, 0x835339f4u, 0x9c845f8bu, 0xbdf9283bu, 0x1ff897ffu, 0xde05980fu,
    0xef2f118bu, 0x5a0a6d1fu, 0x6d367ecfu, 0x27cb09b7u, 0x4f463f66u, 0x9e5fea2du, 0x7527bac7u, 0xebe5f17bu,
    0x3d0739f7u, 0x8a5292eau, 0x6bfb5fb1u, 0x1f8d5d08u, 0x56033046u, 0xfc7b6babu, 0xf0cfbc20u, 0x9af4361du};

struct DoubleDouble {
  double hi;
  double lo;
};

constexpr std::uint64_t bits_of(double x) { return std::bit_cast<std::uint64_t>(x); }
constexpr double from_bits(std::uint64_t b) { return std::bit_cast<double>(b); }
constexpr double abs(double x) { return from_bits(bits_of(x) & ~(1ULL << 63)); }

// Round to the nearest integer (ties to even) for |x| < 2^51: adding 1.5·2^52 leaves no fraction bits.
constexpr double round_to_int(double x) { return (x + 0x1.8p52) - 0x1.8p52; }

// 2^k for k in [−1022, 1023], straight from the exponent field.
constexpr double pow2(int k) { return from_bits(static_cast<std::uint64_t>(k + 1023) << 52); }

// y·2^k for y in [0.5, 2) and k in [−1080, 1024]. Below the normal range the first product is exact and
// only the second rounds, so a subnormal result is rounded once.
constexpr double scale(double y, int k) {
  if (k > 1023) return y * pow2(1023) * pow2(k - 1023);
  if (k < -1021) return y * pow2(k + 64) * 0x1p-64;
  return y * pow2(k);
}

// Knuth's two-sum: hi + lo == a + b exactly, in any order of magnitude.
constexpr DoubleDouble two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  const double err = (a - (s - bb)) + (b - bb);
  return {s, err};
}

// Requires |a| ≥ |b| (or a == 0).
constexpr DoubleDouble fast_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

// Dekker's exact product without FMA (Veltkamp split at 27 bits); |a|, |b| well inside the range.
constexpr DoubleDouble two_prod(double a, double b) {
  const double ca = 134217729.0 * a;
  const double ah = ca - (ca - a);
  const double al = a - ah;
  const double cb = 134217729.0 * b;
  const double bh = cb - (cb - b);
  const double bl = b - bh;
  const double p = a * b;
  const double err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
  return {p, err};
}

// x = k·ln2 + (hi − lo), |x| ≤ 746: returns k, r = fl(hi − lo) and tail with r + tail ≈ e^(hi − lo) − 1; the
// rounding of r is folded into tail so that it is not lost when 1 + r is formed exactly.
struct ExpReduced {
  int k;
  double r;
  double tail;
};

// c[0] + x·(c[1] + x·(c[2] + …)), evaluated innermost first: the same operations in the same order as the
// nested form written out, so the bits do not depend on how a polynomial is spelled.
template <std::size_t N>
constexpr double horner(double x, const double (&c)[N]) {
  double r = c[N - 1];
  for (std::size_t i = N - 1; i-- > 0;) r = c[i] + x * r;
  return r;
}

// (e^x − 1 − x) / x² = 1/2! + x/3! + … + x^12/14!, Horner; for |x| ≤ ln2/2 the next term is below 2^-61
// relative to x. One polynomial for exp's reduced argument and expm1's small arguments.
constexpr double expm1_taylor_q(double x) {
  constexpr double c[] = {0x1p-1,                0x1.5555555555555p-3,  0x1.5555555555555p-5, 0x1.1111111111111p-7,
                          0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-13, 0x1.a01a01a01a01ap-16, 0x1.71de3a556c734p-19,
                          0x1.27e4fb7789f5cp-22, 0x1.ae64567f544e4p-26, 0x1.1eed8eff8d898p-29, 0x1.6124613a86d09p-33,
                          0x1.93974a8c07c9dp-37};
  return horner(x, c);
}

constexpr ExpReduced exp_reduce(double x) {
  const double kd = round_to_int(x * kInvLn2);
  const double hi = x - kd * kLn2Hi;  // exact: kd·kLn2Hi is exact and close to x
  const double lo = kd * kLn2Lo;
  const double r = hi - lo;
  const double c = (hi - r) - lo;  // what the rounding of r lost
  // e^r − 1 − r = r²·q(r); |r| ≤ 0.347.
  const double q = expm1_taylor_q(r);
  // e^(r + c) − 1 ≈ (e^r − 1) + c·(1 + r): c is ≤ half an ulp of r, so first order suffices.
  const double tail = r * r * q + (c + c * r);
  return {static_cast<int>(kd), r, tail};
}

// sin(hi + lo) for |hi| ≲ π/4, |lo| ≤ ulp(hi): Taylor to r^17 (next term < 2^-62 relative).
constexpr double sin_kernel(double hi, double lo) {
  const double z = hi * hi;
  constexpr double k[] = {-0x1.5555555555555p-3, 0x1.1111111111111p-7,  -0x1.a01a01a01a01ap-13, 0x1.71de3a556c734p-19,
                          -0x1.ae64567f544e4p-26, 0x1.6124613a86d09p-33, -0x1.ae7f3e733b81fp-41, 0x1.952c77030ad4ap-49};
  const double s = horner(z, k);
  // The hi·z·s correction is ≤ hi/6, so its own rounding stays far below the final one.
  return hi + ((hi * z) * s + lo * (1.0 - 0.5 * z));
}

// cos(hi + lo) for |hi| ≲ π/4: Taylor to r^18. 1 − z/2 is split so that its rounding error is kept.
constexpr double cos_kernel(double hi, double lo) {
  const double z = hi * hi;
  constexpr double k[] = {0x1.5555555555555p-5,  -0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-16, -0x1.27e4fb7789f5cp-22,
                          0x1.1eed8eff8d898p-29, -0x1.93974a8c07c9dp-37, 0x1.ae7f3e733b81fp-45,  -0x1.6827863b97d97p-53};
  const double c = horner(z, k);
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  return w + (((1.0 - w) - hz) + ((z * z) * c - hi * lo));
}

struct Reduced {
  int quadrant;  // k mod 4
  DoubleDouble r;
};

// |x| = k·π/2 + r for |x| < kCodyWaiteLimit. The first two subtractions are exact or two-summed.
constexpr Reduced reduce_cody_waite(double ax) {
  const double kd = round_to_int(ax * kTwoOverPi);
  const double t = ax - kd * kPio2P1;  // exact: k·P1 exact, t < 1 with ax's granularity
  const DoubleDouble a = two_sum(t, -(kd * kPio2P2));
  const DoubleDouble b = two_sum(a.hi, -(kd * kPio2P3));
  const DoubleDouble r = fast_two_sum(b.hi, b.lo + a.lo);
  return {static_cast<int>(kd) & 3, r};
}

// 32 bits of a little-endian 288-bit integer starting at bit pos (0 ≤ pos ≤ 256).
constexpr std::uint32_t bits_at(const std::uint32_t (&p)[9], int pos) {
  const int li = pos / 32;
  const int sh = pos % 32;
  std::uint64_t v = p[li];
  if (li + 1 < 9) v |= static_cast<std::uint64_t>(p[li + 1]) << 32;
  return static_cast<std::uint32_t>(v >> sh);
}

// Payne–Hanek for finite ax ≥ kCodyWaiteLimit: ax = m·2^e, ax·(2/π) mod 4 from the table bits that matter.
constexpr Reduced reduce_payne_hanek(double ax) {
  const std::uint64_t b = bits_of(ax);
  const std::uint64_t m = (b & kFracMask) | (1ULL << 52);
  const int e = static_cast<int>(b >> 52) - 1075;  // ax = m·2^e, e ≥ −33 here
  // Table bits i ≤ e − 2 (bit i weighs 2^-i) only add multiples of 4 to m·2^e·(2/π): start at e − 1.
  const int first_bit = e - 1 > 1 ? e - 1 : 1;
  const int w0 = (first_bit - 1) / 32;
  std::uint32_t w[7];  // window of 224 bits, little-endian
  for (int j = 0; j < 7; ++j) w[j] = kTwoOverPiBits[w0 + 6 - j];
  const std::uint32_t mm[2] = {static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(m >> 32)};
  // p = m·w, schoolbook in 32-bit limbs: first the low half of m, then the high half shifted by one limb.
  std::uint32_t p[9];
  std::uint64_t carry = 0;
  for (int j = 0; j < 7; ++j) {
    const std::uint64_t t = static_cast<std::uint64_t>(mm[0]) * w[j] + carry;
    p[j] = static_cast<std::uint32_t>(t);
    carry = t >> 32;
  }
  p[7] = static_cast<std::uint32_t>(carry);
  carry = 0;
  for (int j = 0; j < 7; ++j) {
    const std::uint64_t t = static_cast<std::uint64_t>(mm[1]) * w[j] + p[j + 1] + carry;
    p[j + 1] = static_cast<std::uint32_t>(t);
    carry = t >> 32;
  }
  p[8] = static_cast<std::uint32_t>(carry);
  // p·2^(e − 32·w0 − 224) = ax·(2/π) up to multiples of 4 and a dropped tail below 2^-137.
  const int frac_bits = 32 * w0 + 224 - e;  // in [191, 257]
  int quadrant = static_cast<int>(bits_at(p, frac_bits) & 3u);
  std::uint32_t g[4];
  for (int j = 0; j < 4; ++j) g[j] = bits_at(p, frac_bits - 128 + 32 * j);
  // Fraction ≥ 1/2: round k up and take the fraction negative, so |r| ≤ π/4.
  const bool negative = (g[3] & 0x80000000u) != 0;
  if (negative) {
    quadrant += 1;
    carry = 1;  // two's complement: invert and add one
    for (int j = 0; j < 4; ++j) {
      const std::uint64_t t = static_cast<std::uint64_t>(~g[j]) + carry;
      g[j] = static_cast<std::uint32_t>(t);
      carry = t >> 32;
    }
  }
  // The fraction as a double-double: the limbs do not overlap, each converts exactly. Doubles never come
  // closer than ~2^-62 to a multiple of π/2, so g[3] or g[2] holds the leading bits.
  const DoubleDouble top = two_sum(static_cast<double>(g[3]) * 0x1p-32, static_cast<double>(g[2]) * 0x1p-64);
  const DoubleDouble f =
      fast_two_sum(top.hi, top.lo + (static_cast<double>(g[1]) * 0x1p-96 + static_cast<double>(g[0]) * 0x1p-128));
  const DoubleDouble prod = two_prod(f.hi, kPio2Hi);
  DoubleDouble r = fast_two_sum(prod.hi, prod.lo + (f.hi * kPio2Lo + f.lo * kPio2Hi));
  if (negative) r = {-r.hi, -r.lo};
  return {quadrant & 3, r};
}

constexpr Reduced reduce(double ax) {
  if (ax <= kPio4) return {0, {ax, 0.0}};
  if (ax < kCodyWaiteLimit) return reduce_cody_waite(ax);
  return reduce_payne_hanek(ax);
}

}  // namespace detail

constexpr double sin(double x) {
  if (x != x) return x;
  const double ax = detail::abs(x);
  if (ax == detail::kInf) return detail::kNaN;
  if (ax < 0x1p-26) return x;  // x³/6 is below half an ulp of x; keeps ±0 and subnormals exact
  const detail::Reduced red = detail::reduce(ax);
  double y = 0.0;
  switch (red.quadrant) {
    case 0: y = detail::sin_kernel(red.r.hi, red.r.lo); break;
    case 1: y = detail::cos_kernel(red.r.hi, red.r.lo); break;
    case 2: y = -detail::sin_kernel(red.r.hi, red.r.lo); break;
    default: y = -detail::cos_kernel(red.r.hi, red.r.lo); break;
  }
  return x < 0.0 ? -y : y;
}

constexpr double cos(double x) {
  if (x != x) return x;
  const double ax = detail::abs(x);
  if (ax == detail::kInf) return detail::kNaN;
  if (ax < 0x1p-27) return 1.0;  // x²/2 is below half an ulp of 1
  const detail::Reduced red = detail::reduce(ax);
  switch (red.quadrant) {
    case 0: return detail::cos_kernel(red.r.hi, red.r.lo);
    case 1: return -detail::sin_kernel(red.r.hi, red.r.lo);
    case 2: return -detail::cos_kernel(red.r.hi, red.r.lo);
    default: return detail::sin_kernel(red.r.hi, red.r.lo);
  }
}

constexpr double exp(double x) {
  if (x != x) return x;
  if (x > detail::kExpOverflow) return detail::kInf;
  if (x < -746.0) return 0.0;  // e^x < 2^-1076: rounds to +0 (also −inf)
  if (detail::abs(x) < 0x1p-54) return 1.0 + x;
  const detail::ExpReduced red = detail::exp_reduce(x);
  // (1 + r) exactly as a two-sum, so the only rounding of e^r is the final one.
  const detail::DoubleDouble one_r = detail::two_sum(1.0, red.r);
  const double y = one_r.hi + (one_r.lo + red.tail);
  return detail::scale(y, red.k);
}

constexpr double expm1(double x) {
  if (x != x) return x;
  if (x > detail::kExpOverflow) return detail::kInf;
  if (x < -38.0) return -1.0;  // e^x < 2^-54: −1 + e^x rounds to −1 (also −inf)
  const double ax = detail::abs(x);
  if (ax < 0x1p-54) return x;  // x²/2 below half an ulp of x; keeps ±0
  if (ax <= detail::kHalfLn2) {
    const double q = detail::expm1_taylor_q(x);
    return x + (x * x) * q;
  }
  const detail::ExpReduced red = detail::exp_reduce(x);
  const detail::DoubleDouble one_r = detail::two_sum(1.0, red.r);
  const double lo = one_r.lo + red.tail;
  if (red.k > 1000) return detail::scale(one_r.hi + lo, red.k);  // the −1 is far below an ulp
  // 2^k·(hi + lo) − 1 with 2^k·hi − 1 as an exact two-sum: no loss when it cancels (k = 1, −1).
  const double p = detail::pow2(red.k);
  const detail::DoubleDouble s = detail::two_sum(p * one_r.hi, -1.0);
  return s.hi + (s.lo + p * lo);
}

constexpr double log(double x) {
  if (x != x) return x;
  if (x < 0.0) return detail::kNaN;
  if (x == 0.0) return -detail::kInf;
  if (x == detail::kInf) return x;
  std::uint64_t b = detail::bits_of(x);
  int e = 0;
  if (b < (1ULL << 52)) {  // subnormal: make it normal first
    b = detail::bits_of(x * 0x1p54);
    e = -54;
  }
  e += static_cast<int>(b >> 52) - 1023;
  const std::uint64_t frac = b & detail::kFracMask;
  // Mantissa above √2 (fraction bits of 0x1.6a09e667f3bcdp+0): use m/2 and e + 1, so m ∈ [√2/2, √2).
  double m = 0.0;
  if (frac > 0x6a09e667f3bcdULL) {
    m = detail::from_bits(frac | (1022ULL << 52));
    e += 1;
  } else {
    m = detail::from_bits(frac | (1023ULL << 52));
  }
  const double f = m - 1.0;  // exact (Sterbenz)
  const double s = f / (2.0 + f);
  const double z = s * s;
  // log(1 + f) = 2·atanh(s) = 2s + s·R, R = 2z/3 + 2z²/5 + … + 2z^10/21 (|s| ≤ 0.1716, next < 2^-60).
  constexpr double k[] = {0x1.5555555555555p-1, 0x1.999999999999ap-2, 0x1.2492492492492p-2, 0x1.c71c71c71c71cp-3,
                          0x1.745d1745d1746p-3, 0x1.3b13b13b13b14p-3, 0x1.1111111111111p-3, 0x1.e1e1e1e1e1e1ep-4,
                          0x1.af286bca1af28p-4, 0x1.8618618618618p-4};
  const double rr = z * detail::horner(z, k);
  // 2s = f − s·f and f²/2 − s·f = s·f²/2 turn it into f − (f²/2 − s·(f²/2 + R)): f is exact and carries
  // the bulk, only small terms round.
  const double hfsq = 0.5 * f * f;
  const double de = static_cast<double>(e);
  return de * detail::kLn2Hi - ((hfsq - (s * (hfsq + rr) + de * detail::kLn2Lo)) - f);
}

}  // namespace gyrostab::firmware::math
