// Shaft angle encoder: the angle of a gimbal or motor shaft quantized to integer counts (the "encoder
// quantization" of the gimbal drive, docs/models/drives.md).
//
//   q = (θ − θ0) · CPR / 2π
//   count = ⌊q⌋ (kFloor: an edge counter reads the last edge passed; error θ − θ̂ ∈ [0, 1) LSB, mean ½ LSB)
//        or ⌊q + ½⌋ (kNearest: error in [−½, ½) LSB)
//   kIncremental: count unbounded (multi-turn, int64);  kAbsolute: count mod CPR ∈ [0, CPR) (single-turn)
//   θ̂ = count · 2π/CPR                              (kAbsolute: in [0, 2π))
//
// Parameters: CPR counts per revolution after decoding (e.g. 4 × lines for quadrature) [-] ≥ 1; θ0 offset
// (angle of count 0) [rad]; mode; rounding. A non-finite angle reads as count 0 (no undefined conversion);
// |q| is clamped to 2⁶² counts. Stateless, allocation-free.
// Test: tests/unit/sensors_test.cpp (exact counts at and around every edge of a sweep, wrap, offset).
// Docs: docs/models/rate-gyros.md#measurement-chain
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace gyrostab::sensors {

struct EncoderParams {
  enum class Mode { kIncremental, kAbsolute };
  enum class Rounding { kFloor, kNearest };
  std::int64_t counts_per_rev{4096};  // CPR [-]
  double offset{0.0};                 // θ0 [rad]
  Mode mode{Mode::kIncremental};
  Rounding rounding{Rounding::kFloor};
};

class Encoder {
 public:
  explicit Encoder(const EncoderParams& p = {})
      : p_(p),
        per_rad_(static_cast<double>(p.counts_per_rev) / (2.0 * std::numbers::pi)),
        lsb_(2.0 * std::numbers::pi / static_cast<double>(p.counts_per_rev)) {}

  std::int64_t counts(double angle) const {
    double q = (angle - p_.offset) * per_rad_;
    if (p_.rounding == EncoderParams::Rounding::kNearest) q += 0.5;
    if (!std::isfinite(q)) return 0;
    constexpr double kMax = 4611686018427387904.0;  // 2⁶²
    q = q > kMax ? kMax : (q < -kMax ? -kMax : q);
    std::int64_t c = static_cast<std::int64_t>(std::floor(q));
    if (p_.mode == EncoderParams::Mode::kAbsolute) {
      c %= p_.counts_per_rev;
      if (c < 0) c += p_.counts_per_rev;
    }
    return c;
  }

  // θ̂ [rad] from a count.
  double angle_of(std::int64_t count) const { return static_cast<double>(count) * lsb_; }
  // θ̂ [rad] of a true angle.
  double measure(double angle) const { return angle_of(counts(angle)); }

  double lsb() const { return lsb_; }  // 2π/CPR [rad]
  const EncoderParams& params() const { return p_; }

 private:
  EncoderParams p_;
  double per_rad_;
  double lsb_;
};

}  // namespace gyrostab::sensors
