// The servo gyro's rate loop as the closed loop runs it (docs/sampled-data.md): the axis-2 inertia of
// sim/models/servo_gyro.hpp, B β'' = M2 − d2 β' (+ H cosβ α', which the law's feed-forward of (14.43)
// cancels but for its one-tick hold: a forcing at the drive's harmonics, not a change of the loop), driven by
// the firmware's discrete PI (firmware/control/servo_gyro_law.hpp, probed with unit inputs, its limit lifted)
// through the zero-order hold and the latency (sim/analysis/sampled_loop_roots.hpp). The loop is designed as
// a double pole at −ω_c/2 (k_p = B ω_c, k_i = k_p ω_c/4); near a double root the roots themselves are
// ill-conditioned (a perturbation δ splits them by √δ), so the figures are the pair's natural frequency
// ω_n = √(s1 s2) and damping ratio ζ = −(s1 + s2)/(2 ω_n), smooth in the loop's coefficients. At
// ω_c T = 0.2 with one tick of latency the sampling moves them by several per cent.
#pragma once

#include <complex>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/servo_gyro/servo_gyro_scene.hpp"

namespace gyrostab::tools {

struct ServoGyroSampled {
  std::complex<double> continuous[2]{};  // the continuous loop's pair [1/s]
  std::complex<double> sampled[2]{};     // the sampled loop's roots nearest them [1/s]
  analysis::SampledLoopRoots roots;
};
ServoGyroSampled servo_gyro_sampled(const ServoGyroScene& s);

}  // namespace gyrostab::tools
