// The outside controller's cosine (tests/interop/outside_cos.h, written from docs/models/README.md#firmware-cosine)
// against the firmware's own (firmware/math/deterministic_math.hpp): the same bits on every argument tried, so the
// documentation says all an outside implementation needs. Arguments: 2·10⁶ uniform in [−π/2, π/2] (the
// precession angles a law sees) and in [−10, 10], 2·10⁵ up to the documented limit 823549, the doubles next to
// k·π/4 for k < 4096 (the reduction's and the quadrants' edges), and 0, ±2⁻²⁷, NaN, ±inf. Exit 0 when all
// agree, 1 with the first few that do not. Label interop; under 1 s.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "firmware/math/deterministic_math.hpp"

extern "C" {
#include "outside_cos.h"
}

namespace {

std::uint64_t bits(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

long tried = 0;
long differ = 0;

void compare(double x) {
  ++tried;
  const double a = outside_cos(x);
  const double b = gyrostab::firmware::math::cos(x);
  const bool same = bits(a) == bits(b) || (std::isnan(a) && std::isnan(b));
  if (!same && differ++ < 5) std::printf("cos(%a): outside %a, firmware %a\n", x, a, b);
}

}  // namespace

int main() {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> angle(-1.5707963267948966, 1.5707963267948966);
  std::uniform_real_distribution<double> wide(-10.0, 10.0);
  std::uniform_real_distribution<double> large(-823548.0, 823548.0);
  for (int i = 0; i < 2000000; ++i) compare(angle(rng));
  for (int i = 0; i < 2000000; ++i) compare(wide(rng));
  for (int i = 0; i < 200000; ++i) compare(large(rng));
  for (int k = 0; k < 4096; ++k) {
    const double x = k * 0.78539816339744830962;
    for (double y : {std::nextafter(x, 0.0), x, std::nextafter(x, 1e9)}) {
      compare(y);
      compare(-y);
    }
  }
  for (double x : {0.0, -0.0, 0x1p-27, -0x1p-27, 0x1.fffffffffffffp-28, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    compare(x);
  }
  std::printf("%ld arguments, %ld differ\n", tried, differ);
  return differ == 0 ? 0 : 1;
}
