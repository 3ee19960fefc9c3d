// The two-rotor stabilizers' loop as the closed loop runs it (docs/sampled-data.md): the plant of
// sim/plants/two_rotor_stabilizer_plant.hpp on a base at rest — linear already (the models are the small-angle
// equations (TR1) and those of two_rotor_two_axis.hpp), so A and B are read off its derivative with unit states
// and unit torques — under the firmware law, u = K x, with K probed through the plant's own sense() and
// TwoRotorStabilizerLaw::control (limit lifted), so the prediction follows both and copies neither. Sampled
// with the zero-order hold at the law's period and the latency (sim/analysis/sampled_loop_roots.hpp).
// The "nutation" is the closed loop's least-damped oscillatory pair: the cases' nutation against the motors'
// rate damping (the gyro frame's cubic (TR3) has one pair; P6 of the two-axis stabilizer has the two loops').
#pragma once

#include <complex>
#include <vector>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/two_rotor_stabilizer/two_rotor_stabilizer_scene.hpp"

namespace gyrostab::tools {

// ẋ = A x + B u, y = x, u = [M1^K, M2^K] = K x, over the plant's states that act: those that some
// derivative or the law reads. The frames' angles α, γ enter neither (the law reads the cases' angles and the
// frames' rates), and the gyro frame leaves γ, β2 at rest: they are dropped, their zero roots (a neutral
// equilibrium, z = 1 sampled) with them. `states` lists the plant indices kept.
struct TwoRotorLinearLoop {
  analysis::LinearPlant plant;
  analysis::DiscreteLaw law;  // u = K x from the plant's sense() and the firmware law on unit states
  std::vector<int> states;
};
TwoRotorLinearLoop two_rotor_linear_loop(const TwoRotorStabilizerScene& s);
analysis::SampledTiming two_rotor_timing(const TwoRotorStabilizerScene& s);

struct TwoRotorSampled {
  std::complex<double> continuous{0.0, 0.0};  // least-damped root of A + B K with Im > 0 (NaN if none)
  std::complex<double> sampled{0.0, 0.0};     // the sampled root nearest it
  analysis::SampledLoopRoots roots;
  analysis::SampledTiming timing;
  bool continuous_stable{false};              // every root of A + B K has Re < 0
};
TwoRotorSampled two_rotor_sampled(const TwoRotorStabilizerScene& s);

}  // namespace gyrostab::tools
