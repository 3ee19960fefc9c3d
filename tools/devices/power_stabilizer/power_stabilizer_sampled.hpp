// The power stabilizer's loop as the closed loop runs it: the plant of (14.20)/(14.26) linearised at the
// operating point (the `_predicted` figures' model: the loop of check_operating_points, A = I(β0),
// H cos β0, total viscous damping) driven through the zero-order hold by the firmware's law at its period,
// the command taking effect latency_ticks base ticks after its sample (sim/analysis/sampled_loop_roots.hpp).
// The law's matrix D is probed from PowerStabilizerLoops::compute itself with unit inputs (limits lifted), so
// the prediction follows the firmware, not a copy of its formula. Docs: docs/sampled-data.md.
#pragma once

#include <complex>

#include "firmware/control/power_stabilizer_loops.hpp"
#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_scene.hpp"

namespace gyrostab::tools {

// ẋ = A x + B u, y = C x with x = y = [α, β, α', β'] and u = [M1^K, M2^K] (torque mode) or [u_cmd]
// (back-EMF voltage mode: M1^K = s (u_cmd − d_emf α'), the back-EMF in A).
analysis::LinearPlant power_stabilizer_linear_plant(const firmware::PowerStabilizerConfig& l);
// u = D y from compute() on unit sensor frames (α, β, α', β' one at a time).
analysis::DiscreteLaw power_stabilizer_probed_law(const firmware::PowerStabilizerConfig& l);
// The law's period (control_divisor base ticks) and the latency (latency_ticks base ticks).
analysis::SampledTiming power_stabilizer_timing(const PowerStabilizerScene& s);

struct PowerStabilizerSampled {
  analysis::SampledLoopRoots roots;
  analysis::SampledTiming timing;
  std::complex<double> nutation;  // the sampled root nearest the continuous nutation root, Im ≥ 0
};
PowerStabilizerSampled power_stabilizer_sampled(const firmware::PowerStabilizerConfig& l,
                                                const analysis::SampledTiming& t);

// The sampled loop's steady α, β under constant disturbances M1^S, M2^S on axes 1, 2 (NaN where the loop
// leaves α neutral: back-EMF mode).
Eigen::Vector2d power_stabilizer_sampled_steady(const firmware::PowerStabilizerConfig& l,
                                                const analysis::SampledTiming& t, double M1, double M2);

}  // namespace gyrostab::tools
