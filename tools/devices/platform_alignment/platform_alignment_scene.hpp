// A platform alignment scene (Magnus §16.5, (16.52)), as read and checked: the loop, the plant (the platform
// with its gyros' drifts and accelerometers' biases on a base at rest on the rotating Earth, with optional
// small base motion: sim/plants/platform_alignment_plant.hpp), the firmware controller's configuration
// (firmware/app/platform_alignment_controller.hpp: levelling, then gyrocompassing), and what the scene
// requires of the alignment (its maximum time and tolerances: the latitude limit follows from them). The
// member initializers are the scene's defaults; the keys: platform_alignment_schema.cpp, docs/scenes.md.
#pragma once

#include <memory>

#include "firmware/app/platform_alignment_controller.hpp"
#include "sim/plants/platform_alignment_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/devices/platform_alignment/platform_alignment_closed_forms.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

// The base motion as the scene gives it (built into plant.base).
struct AlignmentBaseKeys {
  double roll_amplitude{0.0}, roll_period_s{2.0};    // [rad], [s]
  double pitch_amplitude{0.0}, pitch_period_s{3.0};  // [rad], [s]
  double lever_z_m{0.0};                             // platform above the rocking axes [m]
  double sway_amplitude_m{0.0}, sway_frequency_hz{0.5};
  double heave_amplitude_m{0.0}, heave_frequency_hz{0.5};
};

struct PlatformAlignmentScene {
  LoopConfig loop;
  plants::PlatformAlignmentPlantParams plant;
  AlignmentBaseKeys base;
  firmware::PlatformAlignmentConfig controller;
  double max_time_s{900.0};           // [alignment] the alignment must be done by then [s]
  double heading_tolerance{1e-3};     // [alignment] aligned: |ψ| ≤ this [rad]
  double tilt_tolerance{1e-4};        // [alignment] ... and |θ_E|, |θ_N| ≤ this [rad]
  double latitude_limit{0.0};         // derived: the largest |φ| that aligns by max_time_s [rad]
  double predicted_switch_s{0.0};     // derived: start of the azimuth phase the check assumes [s]
};

// Reads and checks the scene (the problems in the reader; nullptr when refused).
std::unique_ptr<DeviceScene> read_platform_alignment(SceneReader& r);
SceneDoc platform_alignment_doc();

// The alignment-time model (tools/devices/platform_alignment/platform_alignment_closed_forms.hpp) of the scene's loop, platform,
// initial heading error, tolerance and azimuth-phase start.
oracles::AlignmentTimeInputs alignment_time_inputs(const PlatformAlignmentScene& s);

// The run's plant and controller (platform_alignment_run.cpp).
std::unique_ptr<DeviceScene> make_platform_alignment_scene(std::unique_ptr<PlatformAlignmentScene> s);

}  // namespace gyrostab::tools
