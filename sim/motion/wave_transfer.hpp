// Linear transfers from wave elevation to what a model consumes (the RAO hook of irregular_sea.hpp): each is
// a callable `std::complex<double> operator()(double ω) const` giving H(ω); a wave component η = a cos(ωt +
// φ) becomes |H(ω)| a cos(ωt + φ + arg H(ω)). Evaluated at construction only, once per sea component.
//
//   ElevationTransfer         H = 1                              output η [m]
//   WaveSlopeTransfer         H = −i k,  k = ω²/g (deep water)   output ∂η/∂x [rad] of η = a cos(ωt − kx + φ)
//   at x = 0 WaveRollMomentTransfer    H = c κ (−i k)                      output roll moment E [N m] on a
//   ship in beam seas:
//       the effective-wave-slope model — for a ship narrow against the wave length the hydrostatic righting
//       moment acts about the local wave normal, so E = c κ α_w with c = m g GM the roll stiffness of Magnus
//       (14.8) [N m/rad], α_w the wave slope, κ [-] the effective-slope (Froude-Krylov/Smith) reduction, ≈ 1
//       for a small ship, < 1 for a deep hull (from strip theory or a model test). For one regular wave of
//       amplitude a this is Magnus's E(t) = E0 cos ωt (14.9) with E0 = c κ (ω²/g) a
//       (regular_wave_moment.hpp). Sign: positive E for waves travelling along +x (the ship's +y, beam seas);
//       flip κ for the other side.
//   TabulatedRao<K>           |H| and arg H interpolated linearly in ω from ≤ K (ω, gain, phase) rows (e.g. a
//                             response amplitude operator from a seakeeping code), held constant outside.
//
// Units: g [m/s²] (standard gravity 9.80665 by default), ω [rad/s]. Test:
// tests/unit/base_motion_generators_test.cpp.
// Docs: docs/models/suspension-motion.md#waves
#pragma once

#include <array>
#include <complex>
#include <cstddef>

namespace gyrostab::motion {

inline constexpr double kStandardGravity = 9.80665;  // [m/s²]

struct ElevationTransfer {
  std::complex<double> operator()(double /*w*/) const { return {1.0, 0.0}; }
};

struct WaveSlopeTransfer {
  double g{kStandardGravity};  // [m/s²]
  std::complex<double> operator()(double w) const { return {0.0, -w * w / g}; }
};

struct WaveRollMomentTransfer {
  double c{1.0};      // roll stiffness m g GM [N m/rad]
  double kappa{1.0};  // effective wave slope coefficient [-]
  double g{kStandardGravity};
  std::complex<double> operator()(double w) const { return {0.0, -c * kappa * w * w / g}; }
};

template <std::size_t K>
struct TabulatedRao {
  struct Row {
    double omega{0.0};  // [rad/s], rows in increasing ω
    double gain{0.0};   // |H| [output unit / m]
    double phase{0.0};  // arg H [rad]
  };
  std::array<Row, K> rows{};
  std::size_t count{0};  // rows used, ≤ K

  std::complex<double> operator()(double w) const {
    if (count == 0) return {0.0, 0.0};
    if (w <= rows[0].omega) return std::polar(rows[0].gain, rows[0].phase);
    for (std::size_t i = 1; i < count; ++i) {
      if (w <= rows[i].omega) {
        const Row& a = rows[i - 1];
        const Row& b = rows[i];
        const double s = (w - a.omega) / (b.omega - a.omega);
        return std::polar(a.gain + s * (b.gain - a.gain), a.phase + s * (b.phase - a.phase));
      }
    }
    return std::polar(rows[count - 1].gain, rows[count - 1].phase);
  }
};

}  // namespace gyrostab::motion
