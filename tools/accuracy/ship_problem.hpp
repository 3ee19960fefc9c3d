// The ship-roll-damper scenes as a study problem: the stabilized ship (Magnus §14.2, (14.8) with the
// large-angle terms and end stops of sim/models/ship_roll_damper.hpp) in the scene's sea, open loop, with
// the precession torque and brake its closed-loop run held over every tick. The sea moment E(t) is the
// scene's own generator (same spectrum, seed stream and grid), evaluated inside the right-hand side at
// every stage: a fixed function of t for every method.
// State x = [φ, β (rad), φ', β' (rad/s)].
//
// The right-hand side is the scene binding's ShipInSea, operation for operation (the study checks that the
// scene's integrator and step reproduce the closed-loop states bit for bit). It also offers the gyroscopic
// pair of (14.8) — roll/precession coupling H cosβ and the dampings d1, d2 + brake:
//   a = H cosβ/I(β), b = H cosβ/B, p = d1/I(β), q = (d2 + brake)/B
// so our gyro-exponential integrator applies (the scene binding itself runs rk4).
//
// Error quantities (against the reference):
//   roll_rad                  max over ticks of |Δφ|;
//   roll_amplitude_rad        |Δ rms φ| over the window (the scene's headline figure is the roll rms);
//   precession_rad            max over ticks of |Δβ|.
// Oracle: none (irregular sea, controlled); the study uses a converged reference.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "sim/dynamics/damped_gyroscopic_flow.hpp"
#include "sim/random/seeded_rng.hpp"
#include "tools/accuracy/study_problem.hpp"
#include "tools/devices/ship_in_sea.hpp"
#include "tools/devices/ship_roll_damper_study.hpp"

namespace gyrostab::tools::accuracy {

// E(t) of the scene (SeaMoment of ship_roll_damper_scene.cpp without its memo: a pure function of t).
class StudySea {
 public:
  explicit StudySea(const ShipRollDamperStudySetup& s) : regular_(s.regular_sea), wave_(s.wave) {
    if (!regular_) {
      random::SeededRng rng(s.loop.seed, s.sea_stream);
      sea_ = std::make_unique<motion::IrregularSea<256>>(motion::WaveSpectrum(s.spectrum), s.irregular, rng,
                                                         motion::WaveRollMomentTransfer{s.ship.c, s.kappa});
    }
  }
  double operator()(double t) const { return regular_ ? wave_(t) : (*sea_)(t); }

 private:
  bool regular_;
  motion::RegularWaveMoment wave_;
  std::unique_ptr<motion::IrregularSea<256>> sea_;
};

using ShipInStudySea = ShipInSeaOf<StudySea>;

class ShipProblem {
 public:
  using Model = ShipInStudySea;
  static constexpr int kStateSize = 4;
  using State = Model::State;
  static constexpr int kQuantities = 3;

  explicit ShipProblem(const ShipRollDamperStudySetup& s)
      : setup_(s), sea_(s), model_{models::ShipRollDamper(s.ship), &sea_, 0.0, 0.0} {}

  Model& model() { return model_; }
  void set_tick(std::int64_t k) {
    const ShipRollDamperStudySetup::TickInputs& in = setup_.inputs[static_cast<std::size_t>(k)];
    model_.command_Nm = in.command_Nm;
    model_.brake_Nms = in.brake_Nms;
  }
  State initial_state() const { return State::Zero(); }
  std::int64_t ticks() const { return static_cast<std::int64_t>(setup_.inputs.size()); }
  std::int64_t tick_ns() const { return setup_.loop.tick_ns; }

  std::array<Quantity, kQuantities> quantities() const {
    return {{{"roll_rad", "rad", "max over ticks of |d phi|"},
             {"roll_amplitude_rad", "rad", "|d rms(phi)| over the window"},
             {"precession_rad", "rad", "max over ticks of |d beta|"}}};
  }

  void errors(const Trajectory<State>& run, const Trajectory<State>& ref, double* out) const {
    double roll = 0.0, precession = 0.0, ss_run = 0.0, ss_ref = 0.0;
    for (std::size_t k = 0; k < run.size(); ++k) {
      const State& a = run[k];
      const State& b = ref[k];
      if (!a.allFinite()) {
        out[0] = out[1] = out[2] = INFINITY;
        return;
      }
      roll = std::max(roll, std::abs(a[0] - b[0]));
      precession = std::max(precession, std::abs(a[1] - b[1]));
      ss_run += a[0] * a[0];
      ss_ref += b[0] * b[0];
    }
    const double n = static_cast<double>(run.size());
    out[0] = roll;
    out[1] = std::abs(std::sqrt(ss_run / n) - std::sqrt(ss_ref / n));
    out[2] = precession;
  }

  void scales(const Trajectory<State>& ref, double* out) const {
    double roll = 0.0, precession = 0.0, ss = 0.0;
    for (const State& x : ref) {
      roll = std::max(roll, std::abs(x[0]));
      precession = std::max(precession, std::abs(x[1]));
      ss += x[0] * x[0];
    }
    out[0] = roll;
    out[1] = std::sqrt(ss / static_cast<double>(ref.size()));
    out[2] = precession;
  }

 private:
  const ShipRollDamperStudySetup& setup_;
  StudySea sea_;
  Model model_;
};

}  // namespace gyrostab::tools::accuracy
