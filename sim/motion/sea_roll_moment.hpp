// The roll moment E(t) [N m] of a beam sea on a ship: Magnus's regular wave moment E0 cos ωt (14.9), or an
// irregular sea (Pierson-Moskowitz or JONSWAP spectrum, seeded phases: irregular_sea.hpp) through the
// effective-wave-slope transfer E = c κ α_w (wave_transfer.hpp). One definition for the ship scene's plant,
// the accuracy study and the benchmarks, so all three integrate the same E(t) bit for bit.
// E is a pure function of t; the last few values are kept, because a stabilized ship and its locked
// reference evaluate E at the same integrator stage times (a hit returns the same bits).
// Docs: docs/models/suspension-motion.md. Tests: tests/oracle/wave_spectrum_test.cpp,
// tests/unit/base_motion_generators_test.cpp.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/regular_wave_moment.hpp"
#include "sim/motion/wave_spectrum.hpp"
#include "sim/motion/wave_transfer.hpp"
#include "sim/random/seeded_rng.hpp"

namespace gyrostab::motion {

enum class SeaKind : std::uint8_t { kRegular, kPiersonMoskowitz, kJonswap };

struct SeaRollMomentParams {
  SeaKind kind{SeaKind::kJonswap};
  RegularWaveMoment wave{};      // kRegular
  WaveSpectrumParams spectrum{};  // irregular (its kind follows `kind`: spectrum_kind())
  IrregularSeaParams irregular{};
  double kappa{1.0};  // effective wave-slope coefficient [-]

  bool regular() const { return kind == SeaKind::kRegular; }
  WaveSpectrumParams::Kind spectrum_kind() const {
    return kind == SeaKind::kJonswap ? WaveSpectrumParams::Kind::kJonswap : WaveSpectrumParams::Kind::kPiersonMoskowitz;
  }
};

class SeaRollMoment {
 public:
  static constexpr int kMaxComponents = 256;
  using Sea = IrregularSea<kMaxComponents>;

  // `grid_period` [s]: the plant's step; `rng`: the sea's own stream of the scene seed; `roll_stiffness`:
  // c = m g GM [N m/rad].
  SeaRollMoment(const SeaRollMomentParams& p, double grid_period, random::SeededRng rng, double roll_stiffness)
      : regular_(p.regular()), wave_(p.wave) {
    if (!regular_) {
      IrregularSeaParams ip = p.irregular;
      ip.grid_period = grid_period;
      WaveSpectrumParams sp = p.spectrum;
      sp.kind = p.spectrum_kind();
      sea_ = std::make_unique<Sea>(WaveSpectrum(sp), ip, rng, WaveRollMomentTransfer{roll_stiffness, p.kappa});
    }
  }

  double operator()(double t) const {
    for (const Memo& m : memo_) {
      if (m.t == t) return m.value;
    }
    const double value = this->value(t);
    memo_[next_memo_] = {t, value};
    next_memo_ = (next_memo_ + 1) % memo_.size();
    return value;
  }
  // E(t) without the memo (a study that compares integrators gives each the same cost per evaluation).
  double value(double t) const { return regular_ ? wave_(t) : (*sea_)(t); }
  // RMS of E [N m].
  double rms() const { return regular_ ? wave_.E0 / std::sqrt(2.0) : std::sqrt(sea_->output_variance()); }

 private:
  struct Memo {
    double t{std::numeric_limits<double>::quiet_NaN()};  // NaN: never equal, an empty slot
    double value{0.0};
  };
  bool regular_;
  RegularWaveMoment wave_;
  std::unique_ptr<Sea> sea_;
  mutable std::array<Memo, 4> memo_{};
  mutable std::size_t next_memo_{0};
};

}  // namespace gyrostab::motion
