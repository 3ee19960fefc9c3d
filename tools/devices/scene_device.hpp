// The scene runner's entry points for one device: `check` validates a scene (the parameters and the
// controller's start-up checks) without running; `run` validates, builds the plant and the firmware
// controller, runs the in-process closed loop and writes the run's outputs. Both print every problem.
#pragma once

#include "tools/run/run_output.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

// Returns the process exit code: 0 ok, 2 scene refused, 3 run failed (diverged, output not written).
using SceneEntry = int (*)(SceneReader& reader, const RunRequest& request);

struct DeviceEntry {
  const char* name;  // [scene] device
  SceneEntry run;
};

int run_ship_roll_damper(SceneReader& reader, const RunRequest& request);
int run_power_stabilizer(SceneReader& reader, const RunRequest& request);
int run_monorail(SceneReader& reader, const RunRequest& request);
int run_servo_gyro(SceneReader& reader, const RunRequest& request);
int run_gyro_vertical(SceneReader& reader, const RunRequest& request);     // issue 6: Magnus 12.3
int run_gyrocompass(SceneReader& reader, const RunRequest& request);       // issue 6: Magnus 13
int run_inertial_platform(SceneReader& reader, const RunRequest& request);  // issue 6: Magnus 16
int run_gyro_pendulum(SceneReader& reader, const RunRequest& request);     // issue 6: Magnus 12.3.3, Chelnokov

}  // namespace gyrostab::tools
