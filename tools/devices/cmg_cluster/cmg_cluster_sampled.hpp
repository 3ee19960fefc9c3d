// The CMG cluster's attitude loop as the closed loop runs it near the target (docs/sampled-data.md): the
// 19-state model of sim/models/cmg_cluster_spacecraft.hpp (spacecraft, gimbals, their rate servos with the
// rotors' gyroscopic load) linearised where the run ends, in 18 local coordinates (the attitude as a small
// rotation φ from there), by central differences of its own derivative; the firmware's law (quaternion
// feedback and steering, firmware/app/cmg_cluster_controller.hpp) probed through the sensor frame the plant
// fills (3-2-1 angles, body rates, the cluster's gimbal angles), its rate limit lifted; sampled with
// the zero-order hold at the law's period and the latency (sim/analysis/sampled_loop_roots.hpp). The attitude
// mode about the slew axis k is the pair nearest the design's J_kk s² + K_d s + K_p/2 (ω_a, ζ of the scene:
// a double root at ζ = 1), given as ω_n = √(s1 s2) and ζ = −(s1 + s2)/(2 ω_n) — a double root's own position
// is ill-conditioned, its sum and product are not. The gimbal configuration can couple the axes: the rotors'
// load on the gimbal servos, h ω·t_i on gimbal i, turns a body rate into gimbal rate errors ∝ Aᵀ ω and a torque
// error ∝ A Aᵀ ω, diagonal in body axes for the pyramid at δ = 0 but not where the singularity-robust scenes end (δ ≈
// (0.58, 1.63, −1.63, −0.58) rad): there two pairs share the slew axis's motion (`share`), and the run
// measures the pair through the modal filter (`filter`). Also the loop over one period for the response to the
// body-rate noise (x⁺ = Φ x + Γ u[k − L], u = K x + K_v v), which the run takes off before it fits.
#pragma once

#include <complex>

#include <Eigen/Core>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/cmg_cluster/cmg_cluster_scene.hpp"

namespace gyrostab::tools {

struct CmgClusterSampled {
  static constexpr int kN = 18;  // ω (3), φ (3), δ (4), ν (4), servo integrals (4)
  std::complex<double> design[2]{};   // J_kk s² + K_d s + K_p/2 [1/s]
  std::complex<double> sampled[2]{};  // the sampled loop's pair nearest the design's [1/s]
  // The pair's share of the slew axis's motion: its roots' eigenvector weight on ω_k, φ_k over that of every
  // root near the design [-]. Near 1 where the axes decouple (δ = 0: 0.996 on the slew scene); where the
  // configuration couples them, another pair carries the rest, and a planar fit of (q_k, ω_k) alone would
  // measure the two pairs' mixture (+9.1e-3 in ω_n on the singularity-robust scene).
  double share{0.0};
  // The modal filter: y = W (q, ω) (rows orthonormal, q = φ/2 per axis) nulls the output directions of the
  // other two attitude pairs, so that a planar fit of y sees this pair alone; the slew axis's own (q_k, ω_k)
  // when the other pairs do not span four output directions.
  Eigen::Matrix<double, 2, 6> filter{Eigen::Matrix<double, 2, 6>::Zero()};
  analysis::SampledLoopRoots roots;
  Eigen::MatrixXd Phi, Gamma, Kx, Kv;  // kN×kN, kN×4, 4×kN, 4×3
};
// Linearised at the plant state x0 (the run's end) at time t0 [s] (the generalized inverse's dither).
CmgClusterSampled cmg_cluster_sampled(const CmgClusterScene& s, const plants::CmgClusterPlant::State& x0, double t0,
                                      int axis);

}  // namespace gyrostab::tools
