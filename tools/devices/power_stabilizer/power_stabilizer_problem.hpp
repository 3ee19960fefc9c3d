// The power-stabilizer scene as a study problem: the rigid two-axis gyro stabilizer (Magnus §14.3,
// sim/models/power_stabilizer.hpp, the full nonlinear gimbal gyro (10.4) on the scene's rolling base),
// open loop, with the disturbance steps and motor torques its closed-loop run held over every tick.
// State x = [α, β (rad), α', β' (rad/s), H (N m s)].
//
// Error quantities (each the largest over every tick boundary of the window, against the reference):
//   attitude_rad             max(|Δα|, |Δβ|): where the gimbals (the stabilized platform) point;
//   nutation_amplitude_rad_s |Δν| with ν = sqrt(I(β) α'²/B + β'²): for a free nutation of the small-angle
//                            gyro (14.20) I α'² + B β'² is constant (the gyroscopic coupling does no work), so
//                            ν is the amplitude of β' in the nutation — an integrator that damps or excites
//                            the nutation moves ν even where the phase is right.
// Oracle: none (a forced, controlled trajectory); the study uses a converged reference.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "tools/accuracy/study_problem.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_study.hpp"

namespace gyrostab::tools::accuracy {

class PowerStabilizerProblem {
 public:
  using Model = models::PowerStabilizer<models::HarmonicBaseRotation>;
  static constexpr int kStateSize = Model::kStateSize;
  using State = Model::State;
  static constexpr int kQuantities = 2;
  static constexpr int kA = Model::kAlpha, kB = Model::kBeta, kAr = Model::kAlphaRate, kBr = Model::kBetaRate;

  explicit PowerStabilizerProblem(const PowerStabilizerStudySetup& s)
      : setup_(s), model_(s.plant_gyro, {}, {}, s.base) {}

  Model& model() { return model_; }
  void set_tick(std::int64_t k) { model_.inputs = setup_.inputs[static_cast<std::size_t>(k)]; }
  State initial_state() const { return Model::make_state(0.0, 0.0, 0.0, 0.0, setup_.H); }
  std::int64_t ticks() const { return static_cast<std::int64_t>(setup_.inputs.size()); }
  std::int64_t tick_ns() const { return setup_.loop.tick_ns; }

  std::array<Quantity, kQuantities> quantities() const {
    return {{{"attitude_rad", "rad", "max over ticks of max(|d alpha|, |d beta|)"},
             {"nutation_amplitude_rad_s", "rad/s",
              "max over ticks of |d nu|, nu = sqrt(I(beta) alpha'^2/B + beta'^2) (beta' amplitude of the nutation)"}}};
  }

  void errors(const Trajectory<State>& run, const Trajectory<State>& ref, double* out) const {
    double attitude = 0.0, nutation = 0.0;
    for (std::size_t k = 0; k < run.size(); ++k) {
      const State& a = run[k];
      const State& b = ref[k];
      if (!a.allFinite()) {
        attitude = nutation = INFINITY;
        break;
      }
      attitude = std::max({attitude, std::abs(a[kA] - b[kA]), std::abs(a[kB] - b[kB])});
      nutation = std::max(nutation, std::abs(nutation_amplitude(a) - nutation_amplitude(b)));
    }
    out[0] = attitude;
    out[1] = nutation;
  }

  void scales(const Trajectory<State>& ref, double* out) const {
    out[0] = out[1] = 0.0;
    for (const State& x : ref) {
      out[0] = std::max({out[0], std::abs(x[kA]), std::abs(x[kB])});
      out[1] = std::max(out[1], nutation_amplitude(x));
    }
  }

  double nutation_amplitude(const State& x) const {
    const models::GimbalGyroParams& p = model_.gyro().params();
    return std::sqrt(p.outer_axis_inertia(x[kB]) * x[kAr] * x[kAr] / p.B() + x[kBr] * x[kBr]);
  }

 private:
  const PowerStabilizerStudySetup& setup_;
  Model model_;
};

}  // namespace gyrostab::tools::accuracy
