// The monorail's loop as the closed loop runs it: (14.2)/(14.6) linearised at the path's turning rate Ω3
// (c → c − HΩ3, q → q − HΩ3, the `_predicted` figures' model) driven through the zero-order hold by the
// firmware's law M2 = k φ − d β' at its period, the command taking effect latency_ticks base ticks after its
// sample (sim/analysis/sampled_loop_roots.hpp). The law's matrix is probed from MonorailLaw::control (the
// firmware app's step) with unit sensor values, the torque limit lifted. Docs: docs/sampled-data.md.
#pragma once

#include "firmware/app/monorail_controller.hpp"
#include "sim/analysis/sampled_loop_roots.hpp"
#include "sim/models/monorail.hpp"

namespace gyrostab::tools {

// x = [φ, β, φ', β'], u = [M2], y = [φ (carrier_angle_rad[kRoll]), β' (gimbal_rate_rad_s[kAxis2])]; the
// car's own passive d (d_mechanical) in A.
analysis::LinearPlant monorail_linear_plant(const models::MonorailParams& car, double Omega3);
// u = D y from MonorailLaw::control on unit sensor frames (φ, β' one at a time).
analysis::DiscreteLaw monorail_probed_law(const firmware::MonorailConfig& c);
// The law's period (control_divisor base ticks) and the latency (latency_ticks base ticks).
analysis::SampledTiming monorail_timing(const firmware::MonorailConfig& c, double tick_s, int latency_ticks);

struct MonorailSampled {
  analysis::SampledLoopRoots roots;
  double decay_rate_per_s{0.0};  // −max Re s: the slowest mode's decay (< 0: it grows)
};
MonorailSampled monorail_sampled(const models::MonorailParams& car, const firmware::MonorailConfig& c,
                                 double Omega3, const analysis::SampledTiming& t);

// The sampled loop's steady [φ, β] under a constant roll moment M1 on the car and a tilt-sensor bias (what
// the law reads is φ + bias).
Eigen::Vector2d monorail_sampled_steady(const models::MonorailParams& car, const firmware::MonorailConfig& c,
                                        double Omega3, const analysis::SampledTiming& t, double M1, double bias);

// The same fixed point with the car's large-angle terms (sim/models/monorail.hpp): a zero-order hold keeps the
// equilibria of the nonlinear loop too, so the sampled loop settles where the model's accelerations vanish at
// rest under the law's steady command M2 = D_φ (φ + bias). The roll moment is the gust plus the centrifugal
// c b cos φ of a lateral acceleration b (in g), as the plant applies it. Newton from the linear fixed point;
// NaN if it does not converge (the linear point is then the better guess, and the caller reports that one).
Eigen::Vector2d monorail_sampled_steady_large_angle(const models::MonorailParams& car,
                                                    const firmware::MonorailConfig& c, double Omega3,
                                                    const analysis::SampledTiming& t, double gust_Nm,
                                                    double lateral_g, double bias);
}  // namespace gyrostab::tools
