// The ship roll damper's loop as the closed loop runs it, in calm water near the upright (docs/sampled-data.md):
// the ship and case of sim/models/ship_roll_damper.hpp linearised at φ = β = 0 by central differences of their
// own derivative (E = 0), the firmware's law (the passive precession brake or the active control, near zero
// both linear in the rates and the angle) probed through the sensor frame the plant fills, its torque limit
// lifted; sampled with the zero-order hold at the law's period and the latency
// (sim/analysis/sampled_loop_roots.hpp). The continuous loop is (14.8) with the law's torque: its quartic has
// the roll pair near √(c/A) and the case's pair (or two real roots: the passive brake at its minimax d2 leaves
// a slow real root, the case creeping back on its pendulous stiffness).
#pragma once

#include <complex>
#include <vector>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_scene.hpp"

namespace gyrostab::tools {

struct ShipRollDamperSampled {
  std::vector<std::complex<double>> continuous;  // the linearised loop's roots (Im ≥ 0 of each pair) [1/s]
  std::vector<std::complex<double>> sampled;     // the sampled root nearest each [1/s]
  analysis::SampledLoopRoots roots;
};
ShipRollDamperSampled ship_roll_damper_sampled(const ShipRollDamperScene& s);

}  // namespace gyrostab::tools
