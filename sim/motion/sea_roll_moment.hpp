// The roll moment E(t) [N m] of a long-crested sea on a ship: Magnus's regular wave moment E0 cos ωt (14.9),
// or an irregular sea (Pierson-Moskowitz or JONSWAP spectrum, seeded phases: irregular_sea.hpp) through the
// effective-wave-slope transfer E = c κ α_w (wave_transfer.hpp), seen from a ship on its course
// (ship_course.hpp): speed U, heading μ to the waves, turn rate Ω3.
//   straight course (Ω3 = 0): each component at its encounter frequency ω_e = ω − (ω²/g) U cos μ0, its
//     moment scaled by sin μ0 (the slope across the ship); regular: E = E0 sin μ0 cos(ω_e t + ψ), E0 the
//     beam-sea moment of the wave at rest. The irregular sea keeps its phasor recursion (O(N) multiplies).
//   turning (Ω3 ≠ 0): E = sin μ(t) Σ bᵢ cos(ωᵢ t − kᵢ x_w(t) + ψᵢ) with μ(t) and the track x_w(t) of the
//     circle; evaluated directly, N cosines per call (a turning scene is short; the sweep's straight courses
//     keep the fast path).
// One definition for the ship scene's plant, the accuracy study and the benchmarks, so all three integrate the
// same E(t) bit for bit. E is a pure function of t; the last few values are kept, because a stabilized ship
// and its locked reference evaluate E at the same integrator stage times (a hit returns the same bits).
// Docs: docs/models/suspension-motion.md, docs/models/ship-roll-damper.md#course. Tests:
// tests/oracle/wave_spectrum_test.cpp, tests/oracle/ship_course_response_test.cpp,
// tests/unit/base_motion_generators_test.cpp.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/regular_wave_moment.hpp"
#include "sim/motion/ship_course.hpp"
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
  ShipCourse course{};  // speed and heading; the turn rate is the ship model's (passed to the constructor)

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
  // c = m g GM [N m/rad]; `turn_rate`: Ω3 of the ship [rad/s].
  SeaRollMoment(const SeaRollMomentParams& p, double grid_period, random::SeededRng rng, double roll_stiffness,
                double turn_rate = 0.0)
      : regular_(p.regular()), course_(p.course) {
    course_.turn_rate = turn_rate;
    const double slope = std::sin(course_.heading);
    if (regular_) {
      wave_ = p.wave;
      wavenumber_[0] = p.wave.omega * p.wave.omega / kStandardGravity;
      if (!course_.turning()) {
        wave_.E0 = p.wave.E0 * slope;
        wave_.omega = course_.encounter_frequency(p.wave.omega);
      }
      return;
    }
    IrregularSeaParams ip = p.irregular;
    ip.grid_period = grid_period;
    WaveSpectrumParams sp = p.spectrum;
    sp.kind = p.spectrum_kind();
    if (course_.turning()) {  // beam-sea components at the waves' own frequencies; course applied per call
      sea_ = std::make_unique<Sea>(WaveSpectrum(sp), ip, rng, WaveRollMomentTransfer{roll_stiffness, p.kappa});
      for (int i = 0; i < sea_->size(); ++i) wavenumber_[i] = sea_->frequency(i) * sea_->frequency(i) / kStandardGravity;
    } else {
      ip.velocity_along_waves = course_.velocity_along_waves();
      sea_ = std::make_unique<Sea>(WaveSpectrum(sp), ip, rng,
                                   WaveRollMomentTransfer{roll_stiffness, p.kappa * slope});
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
  double value(double t) const {
    if (course_.turning()) return turning_value(t);
    return regular_ ? wave_(t) : (*sea_)(t);
  }
  // RMS of E [N m].
  // On a straight course; turning, the rms of the beam sea (sin μ sweeps through ±1).
  double rms() const { return regular_ ? wave_.E0 / std::sqrt(2.0) : std::sqrt(sea_->output_variance()); }
  // Encounter frequency of the regular wave on a straight course [rad/s].
  double encounter_frequency() const { return wave_.omega; }

 private:
  struct Memo {
    double t{std::numeric_limits<double>::quiet_NaN()};  // NaN: never equal, an empty slot
    double value{0.0};
  };
  double turning_value(double t) const {
    const double x = course_.track_along_waves(t);
    const double slope = std::sin(course_.heading_at(t));
    if (regular_) return slope * wave_.E0 * std::cos(wave_.omega * t - wavenumber_[0] * x + wave_.phase);
    double sum = 0.0;
    for (int i = 0; i < sea_->size(); ++i)
      sum += sea_->amplitude(i) * std::cos(sea_->frequency(i) * t - wavenumber_[i] * x + sea_->phase(i));
    return slope * sum;
  }

  bool regular_;
  ShipCourse course_;
  RegularWaveMoment wave_{};
  std::unique_ptr<Sea> sea_;
  std::array<double, kMaxComponents> wavenumber_{};  // kᵢ = ωᵢ²/g, turning only [1/m]
  mutable std::array<Memo, 4> memo_{};
  mutable std::size_t next_memo_{0};
};

}  // namespace gyrostab::motion
