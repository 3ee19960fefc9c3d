// The gyrocompass's loop as the closed loop runs it (docs/sampled-data.md): the model of
// sim/models/gyrocompass.hpp (the full form with the nutation, or the precession form, as the scene has it)
// linearised at its equilibrium on the scene's starting base by central differences of its own derivative, the
// level sensor and the firmware law probed the same way (u = K x: M1 = −f β_lvl, M2 = −c_e β_lvl), sampled with
// the zero-order hold at the law's period and the latency (sim/analysis/sampled_loop_roots.hpp). The compass mode
// is the oscillatory pair of the smallest frequency (the nutation, in the full form, is the fast one). Unlike
// (13.12), this keeps the sphere's inertia, its damping d1, d2 and the vertical Earth rate's coupling: the
// root the model has, which the book's precession theory approximates to O(A c/H²).
#pragma once

#include <complex>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/gyrocompass/gyrocompass_scene.hpp"

namespace gyrostab::tools {

struct GyrocompassSampled {
  std::complex<double> continuous{0.0, 0.0};  // the compass mode of the linearised loop (Im > 0; NaN if none)
  std::complex<double> sampled{0.0, 0.0};     // the sampled root nearest it
  analysis::SampledLoopRoots roots;
};
GyrocompassSampled gyrocompass_sampled(const GyrocompassScene& s);

}  // namespace gyrostab::tools
