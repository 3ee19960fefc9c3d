// What the accuracy study (`gyrostab accuracy`, docs/accuracy.md) takes from a ship-roll-damper scene: the
// stabilized ship exactly as the scene's plant builds it (sim/plants/ship_roll_damper_plant.hpp), its sea
// (the same generator, seed stream and grid, so the study's E(t) is the run's bit for bit), and the inputs its
// closed-loop run held over every tick (precession torque command and brake, zero-order hold).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/plants/ship_roll_damper_plant.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_scene.hpp"
#include "tools/scene/loop_config.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

struct AccuracyRequest;

struct ShipRollDamperStudySetup {
  ShipRollDamperScene scene;     // as read, with loop.duration_s = the ticks run
  double scene_duration_s{0.0};  // [scene] duration_s
  std::vector<plants::ShipRollDamperPlant::HeldInputs> inputs;  // held over tick k
  std::vector<Eigen::Matrix<double, 4, 1>> states;            // closed-loop state after tick k
  double closed_loop_wall_s{0.0};
  const LoopConfig& loop() const { return scene.loop; }
};

// Reads the scene, runs its closed loop for `ticks` ticks (< 0: the scene's duration) and records the
// stabilized ship's inputs and states. Returns 0 ok, 2 scene refused (problems in the reader), 3 diverged.
int ship_roll_damper_study_setup(SceneReader& reader, std::int64_t ticks, ShipRollDamperStudySetup& out);

// `gyrostab accuracy` on a ship-roll-damper scene (the registry's accuracy entry).
int ship_roll_damper_accuracy(SceneReader& reader, const AccuracyRequest& req);

}  // namespace gyrostab::tools
