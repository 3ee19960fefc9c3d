// The platform alignment's azimuth loop as the closed loop runs it (docs/sampled-data.md): the platform of
// sim/models/platform_alignment.hpp linearised in its misalignment x = (θ_E, θ_N, ψ) at the steady misalignment
// of the biases and drifts, by central differences of its own kinematics (q_GP from x, the quaternion rate,
// back through the misalignment's Jacobian); the inputs through the plant's own actuate() (torquers M = −H ω,
// the zenith torquer's voltage); the outputs θ̂ = a/g0 of the model's accelerometers at rest (the plumb line's
// g against the sensor's g0 kept); and the firmware's exact discrete law, probed from
// firmware::PlatformAlignmentLoops in its azimuth phase (integrators, the integrate-then-output order, k_a on
// the updated integrator) — sampled with the zero-order hold at the law's period and the latency
// (sim/analysis/sampled_loop_roots.hpp). Unlike the check's azimuth polynomial (platform_alignment_loops.hpp),
// nothing here is expanded to first order in Ω T: the Earth-rate coupling, Ω_U's cross terms and the
// accelerometer scale g/g0 are the model's.
#pragma once

#include <complex>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/platform_alignment/platform_alignment_scene.hpp"

namespace gyrostab::tools {

struct PlatformAlignmentSampled {
  std::complex<double> slow_root{0.0, 0.0};  // the sampled loop's root nearest the cubic's slow root [1/s]
  analysis::SampledLoopRoots roots;
};
// `continuous_slow_root`: the azimuth cubic's slow root (oracles::azimuth_slow_root) [1/s], which picks the mode.
PlatformAlignmentSampled platform_alignment_sampled(const PlatformAlignmentScene& s, double continuous_slow_root);

}  // namespace gyrostab::tools
