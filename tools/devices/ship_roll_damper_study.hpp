// What the accuracy study (tools/accuracy/, `gyrostab accuracy`) takes from a ship-roll-damper scene: the
// stabilized ship exactly as the scene binding builds it, the recipe of its sea moment E(t) (the same
// generator, seed stream and grid, so the study's E(t) is the run's bit for bit), and the inputs its
// closed-loop run held over every tick (precession torque command and brake, zero-order hold).
// Implemented in ship_roll_damper_scene.cpp (it needs the scene reading there).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/models/ship_roll_damper.hpp"
#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/regular_wave_moment.hpp"
#include "sim/motion/wave_spectrum.hpp"
#include "tools/scene/loop_config.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

struct ShipRollDamperStudySetup {
  LoopConfig loop;            // the scene's, with duration_s = the ticks run
  double scene_duration_s{0.0};  // [scene] duration_s
  models::ShipRollDamperParams ship;
  // Sea moment: regular E0 cos(ωt + phase), or IrregularSea<256>(WaveSpectrum(spectrum), irregular,
  // SeededRng(loop.seed, sea_stream), WaveRollMomentTransfer{ship.c, kappa}) evaluated with operator()(t).
  bool regular_sea{false};
  motion::RegularWaveMoment wave{};
  motion::WaveSpectrumParams spectrum{};
  motion::IrregularSeaParams irregular{};  // grid_period as the scene uses it
  double kappa{1.0};
  std::uint64_t sea_stream{1};
  struct TickInputs {
    double command_Nm{0.0};  // precession torque held over the tick [N m]
    double brake_Nms{0.0};   // viscous brake held over the tick [N m s/rad]
  };
  std::vector<TickInputs> inputs;              // held over tick k
  std::vector<Eigen::Matrix<double, 4, 1>> states;  // closed-loop state after tick k
  double closed_loop_wall_s{0.0};
};

// Reads the scene, runs its closed loop for `ticks` ticks (< 0: the scene's duration) and records the
// stabilized ship's inputs and states. Returns 0 ok, 2 scene refused (problems in the reader), 3 diverged.
int ship_roll_damper_study_setup(SceneReader& reader, std::int64_t ticks, ShipRollDamperStudySetup& out);

}  // namespace gyrostab::tools
