// The digital output stage of a sensor: saturation at ± full scale, then rounding to the least significant
// bit.
//
//   y = lsb · round(clamp(x, −full_scale, +full_scale) / lsb)      (round half away from zero, std::round)
//
// Parameters: lsb [unit] (0 ⇒ no quantization), full_scale [unit] (0 ⇒ no saturation). A NaN passes through
// unchanged so the controller's fault monitor sees it. Stateless, allocation-free.
// Test: tests/unit/sensors_test.cpp.
// Docs: docs/models/rate-gyros.md#measurement-chain
#pragma once

#include <cmath>

namespace gyrostab::sensors {

struct OutputQuantizer {
  double lsb{0.0};         // [unit]
  double full_scale{0.0};  // [unit]

  double operator()(double x) const {
    if (full_scale > 0.0) x = x > full_scale ? full_scale : (x < -full_scale ? -full_scale : x);
    if (lsb > 0.0) x = lsb * std::round(x / lsb);
    return x;
  }
};

}  // namespace gyrostab::sensors
