// Seeded pseudo-random numbers for the plant: uniform doubles on [0, 1) and standard Gaussians, bit-identical
// for the same seed on every platform with IEEE doubles (and the same libm `log`, see below).
//
//   generator  xoshiro256** 1.0 (Blackman & Vigna, "Scrambled linear pseudorandom number generators", 2018;
//              reference C at prng.di.unimi.it): 256-bit state, period 2^256 − 1, output rotl(s1·5, 7)·9.
//   seeding    the four state words are four successive SplitMix64 outputs from the 64-bit seed (Steele, Lea
//   &
//              Flood 2014) — the authors' recommended seeding, and PHP's
//              Random\Engine\Xoshiro256StarStar(int).
//   streams    SeededRng(seed, k) is the seed's generator advanced by k jumps of 2^128 draws (the authors'
//              jump polynomial): streams never overlap. Give each consumer (each sensor, the sea) its own
//              stream of the scene seed. Cost ~256·k draws at construction, so k is a small index.
//   uniform    (x >> 11)·2^-53: the 53 high bits, every value a multiple of 2^-53 in [0, 1).
//   gaussian   Marsaglia's polar method (Marsaglia & Bray 1964): u, v uniform on (−1, 1), s = u² + v² ∈ (0,
//   1),
//              accepted with probability π/4; returns u·√(−2 ln s / s) and keeps v·√(−2 ln s / s) for the
//              next call. Uses only `sqrt` (IEEE-exact) and `log`: results are bit-identical wherever
//              `std::log` is (same libm); std::normal_distribution is not used because its algorithm is
//              implementation-defined.
//
// Hot-path safe: no allocation, no exceptions, O(1) per draw (the polar method averages 1.27 pairs per two
// Gaussians). The scene owns the generators; models take a `SeededRng&` and document their draw order.
// Tests: tests/unit/seeded_rng_test.cpp (reference vectors for SplitMix64, xoshiro256** and its jumps;
// moments).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace gyrostab::random {

// One SplitMix64 step: advances `x` by the golden-ratio increment and returns the mixed value.
constexpr std::uint64_t splitmix64_next(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class SeededRng {
 public:
  using State = std::array<std::uint64_t, 4>;

  explicit SeededRng(std::uint64_t seed, std::uint64_t stream = 0) {
    std::uint64_t x = seed;
    for (auto& w : s_) w = splitmix64_next(x);
    for (std::uint64_t k = 0; k < stream; ++k) jump();
  }

  // Raw 64-bit output of xoshiro256**.
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform on [0, 1), resolution 2^-53.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform on [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }

  // Standard normal N(0, 1) by the polar method; every second call returns the cached partner.
  double gaussian() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u = 0.0, v = 0.0, s = 0.0;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }
  double gaussian(double mean, double sd) { return mean + sd * gaussian(); }

  // Advance by 2^128 draws (xoshiro256 jump polynomial) / by 2^192 draws (long jump). Drops a cached
  // Gaussian.
  void jump() {
    apply_jump({0x180ec6d33cfd0abaULL, 0xd5a61266f0c9392cULL, 0xa9582618e03fc9aaULL, 0x39abdc4529b1661cULL});
  }
  void long_jump() {
    apply_jump({0x76e15d3efefdcbbfULL, 0xc5004e441c522fb3ULL, 0x77710069854ee241ULL, 0x39109bb02acbe635ULL});
  }

  const State& state() const { return s_; }
  friend bool operator==(const SeededRng&, const SeededRng&) = default;

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

  void apply_jump(const State& poly) {
    State acc{0, 0, 0, 0};
    for (const std::uint64_t word : poly) {
      for (int b = 0; b < 64; ++b) {
        if (word & (std::uint64_t{1} << b)) {
          for (int i = 0; i < 4; ++i) acc[i] ^= s_[i];
        }
        next();
      }
    }
    s_ = acc;
    has_spare_ = false;
  }

  State s_{};
  double spare_{0.0};
  bool has_spare_{false};
};

}  // namespace gyrostab::random
