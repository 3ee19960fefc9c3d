// The ship-roll-damper scenes as a study problem: the stabilized ship (Magnus §14.2, (14.8) with the
// large-angle terms and end stops of sim/models/ship_roll_damper.hpp) in the scene's sea, open loop, with
// the precession torque and brake its closed-loop run held over every tick. The sea moment E(t) is the
// scene's own generator (same spectrum, seed stream and grid), evaluated inside the right-hand side at
// every stage: a fixed function of t for every method.
// State x = [φ, β (rad), φ', β' (rad/s)].
//
// The right-hand side is the scene plant's ShipInSea, operation for operation (the study checks that the
// scene's integrator and step reproduce the closed-loop states bit for bit). It also offers the gyroscopic
// pair of (14.8) — roll/precession coupling H cosβ and the dampings d1, d2 + brake:
//   a = H cosβ/I(β), b = H cosβ/B, p = d1/I(β), q = (d2 + brake)/B
// so our gyro-exponential integrator applies (the scene's plant itself runs rk4).
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
#include "sim/motion/sea_roll_moment.hpp"
#include "sim/plants/ship_in_sea.hpp"
#include "tools/accuracy/study_problem.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_study.hpp"

namespace gyrostab::tools::accuracy {

// E(t) of the scene's sea without its memo (every method pays the same per evaluation).
class StudySea {
 public:
  explicit StudySea(const ShipRollDamperStudySetup& s)
      : sea_(s.scene.plant.sea, s.scene.loop.tick_s() / s.scene.loop.substeps,
             random::SeededRng(s.scene.loop.seed, plants::ShipRollDamperPlant::kSeaStream), s.scene.plant.ship.c) {}
  double operator()(double t) const { return sea_.value(t); }

 private:
  motion::SeaRollMoment sea_;
};

using ShipInStudySea = plants::ShipInSeaOf<StudySea>;

class ShipProblem {
 public:
  using Model = ShipInStudySea;
  static constexpr int kStateSize = 4;
  using State = Model::State;
  static constexpr int kQuantities = 3;
  static constexpr int kRoll = models::ShipRollDamper::kRoll, kPrecession = models::ShipRollDamper::kPrecession;

  explicit ShipProblem(const ShipRollDamperStudySetup& s)
      : setup_(s), sea_(s), model_{models::ShipRollDamper(s.scene.plant.ship), &sea_, 0.0, 0.0} {}

  Model& model() { return model_; }
  void set_tick(std::int64_t k) {
    const plants::ShipRollDamperPlant::HeldInputs& in = setup_.inputs[static_cast<std::size_t>(k)];
    model_.command_Nm = in.command_Nm;
    model_.brake_Nms = in.brake_Nms;
  }
  State initial_state() const { return State::Zero(); }
  std::int64_t ticks() const { return static_cast<std::int64_t>(setup_.inputs.size()); }
  std::int64_t tick_ns() const { return setup_.scene.loop.tick_ns; }

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
      roll = std::max(roll, std::abs(a[kRoll] - b[kRoll]));
      precession = std::max(precession, std::abs(a[kPrecession] - b[kPrecession]));
      ss_run += a[kRoll] * a[kRoll];
      ss_ref += b[kRoll] * b[kRoll];
    }
    const double n = static_cast<double>(run.size());
    out[0] = roll;
    out[1] = std::abs(std::sqrt(ss_run / n) - std::sqrt(ss_ref / n));
    out[2] = precession;
  }

  void scales(const Trajectory<State>& ref, double* out) const {
    double roll = 0.0, precession = 0.0, ss = 0.0;
    for (const State& x : ref) {
      roll = std::max(roll, std::abs(x[kRoll]));
      precession = std::max(precession, std::abs(x[kPrecession]));
      ss += x[kRoll] * x[kRoll];
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
