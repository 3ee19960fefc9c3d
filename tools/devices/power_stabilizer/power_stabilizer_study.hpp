// What the accuracy study (tools/accuracy/, `gyrostab accuracy`) takes from a power-stabilizer scene: the
// plant exactly as the scene's plant builds it (sim/plants/power_stabilizer_plant.hpp), and the inputs its
// closed-loop run held over every tick (zero-order hold: disturbance steps and motor torques), so that the
// study can integrate the same plant open loop with any method.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/models/base_motion.hpp"
#include "sim/models/gimbal_gyro.hpp"
#include "sim/models/power_stabilizer.hpp"
#include "tools/scene/loop_config.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

struct PowerStabilizerStudySetup {
  LoopConfig loop;            // the scene's, with duration_s = the ticks run
  double scene_duration_s{0.0};  // [scene] duration_s
  models::GimbalGyroParams plant_gyro;  // as integrated
  models::HarmonicBaseRotation base;
  double H{0.0};                      // rotor spin momentum [N m s]
  std::vector<models::PowerStabilizerInputs> inputs;  // held over tick k
  std::vector<Eigen::Matrix<double, 5, 1>> states;    // closed-loop state after tick k
  double closed_loop_wall_s{0.0};
};

// Reads and validates the scene, runs its closed loop (the scene's integrator and step) for `ticks` ticks
// (< 0: the scene's duration) and records the plant's inputs and states. Returns 0 ok, 2 scene refused
// (problems in the reader), 3 the closed loop diverged, 4 a plant variant the study does not take (`why`).
int power_stabilizer_study_setup(SceneReader& reader, std::int64_t ticks, PowerStabilizerStudySetup& out,
                                 std::string& why);

struct AccuracyRequest;
// `gyrostab accuracy` on a power-stabilizer scene (the registry's accuracy entry).
int power_stabilizer_accuracy(SceneReader& reader, const AccuracyRequest& req);

}  // namespace gyrostab::tools
