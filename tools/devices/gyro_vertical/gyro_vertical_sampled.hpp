// The gyro vertical's erection loop as the closed loop runs it (docs/sampled-data.md): the instrument of
// sim/models/gyro_vertical.hpp (full form with the nutation, or the precession form, as the scene has it)
// linearised on the scene's starting frame (its Earth and transport rates, the apparent vertical) by central
// differences of its own derivative; the erection sensor and the gimbal-rate pick-offs as the model gives them;
// the firmware's memoryless correction (firmware/control/gyro_vertical_correction.hpp) probed with unit
// signals, its limit lifted; sampled with the zero-order hold at the law's period and the latency
// (sim/analysis/sampled_loop_roots.hpp). The erection mode is the root nearest the book's −δ + i ω^P
// (δ = f/H, ω^P = (c + c1)/H, (12.45) with ω = 0): the model keeps the rotor's inertia and the bearing damping
// that the precession theory drops (a relative shift d c/(f H) of δ, (12.45)'s derivation in the model header).
#pragma once

#include <complex>

#include <Eigen/Core>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "tools/devices/gyro_vertical/gyro_vertical_scene.hpp"

namespace gyrostab::tools {

struct GyroVerticalSampled {
  std::complex<double> continuous{0.0, 0.0};  // the linearised loop's erection root (Im ≥ 0) [1/s]
  std::complex<double> sampled{0.0, 0.0};     // the sampled loop's root nearest it [1/s]
  analysis::SampledLoopRoots roots;
  // The loop over one law period for the response to the sensor errors v = (e1, e2, α', β') sensed − true:
  // x⁺ = Φ x + Γ u[k − L],  u[k] = K_x x[k] + K_v v[k]  (x = [α, β, α', β'], whole periods of latency L).
  Eigen::Matrix4d Phi{Eigen::Matrix4d::Identity()};
  Eigen::Matrix<double, 4, 2> Gamma{Eigen::Matrix<double, 4, 2>::Zero()};
  Eigen::Matrix<double, 2, 4> Kx{Eigen::Matrix<double, 2, 4>::Zero()}, Kv{Eigen::Matrix<double, 2, 4>::Zero()};
};
// `book`: −δ + i ω^P, which picks the mode.
GyroVerticalSampled gyro_vertical_sampled(const GyroVerticalScene& s, std::complex<double> book);

}  // namespace gyrostab::tools
