// The roots of the position-gyro platform's loop (Magnus §16.2.2, (16.8)), for the run's report and the
// oracle test: the continuous loop's four non-zero roots (the quartic of (16.8) through its companion matrix),
// the sampled loop's roots as continuous equivalents ln(z)/Tc (the discrete closed loop built from
// firmware/control/position_gyro_platform_stability.hpp's Φ, Γ0, Γ1 and its delay slots), and the dominant
// root (largest real part, upper half-plane). Host only (Eigen's eigensolver allocates).
// Docs: docs/models/position-gyro-platform.md#stability
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

#include "firmware/control/position_gyro_platform_stability.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::oracles {

inline std::vector<std::complex<double>> platform_continuous_roots(const firmware::PositionGyroPlatformPlant& s,
                                                                   double k) {
  const firmware::PlatformQuartic a = firmware::platform_quartic(s, k);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(4, 4);
  const double c[4] = {a.a3 / a.a4, a.a2 / a.a4, a.a1 / a.a4, a.a0 / a.a4};
  for (int j = 0; j < 4; ++j) C(0, j) = -c[j];
  for (int i = 1; i < 4; ++i) C(i, i - 1) = 1.0;
  const Eigen::VectorXcd ev = dynamics::eigenvalues(C);
  return {ev.data(), ev.data() + ev.size()};
}

// The discrete closed loop w_{j+1} = M w_j, w = [x_j, u_{j−1} … u_{j−m−1}] (firmware's convention).
inline Eigen::MatrixXd platform_sampled_matrix(const firmware::PositionGyroPlatformPlant& s, double k, double Tc,
                                               double tau) {
  const firmware::PlatformDiscretized d = firmware::platform_discretized(s, Tc, tau);
  const int n = 5 + d.m, slot0 = 4;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) M(i, j) = d.Phi[i][j];
    if (d.m == 0) M(i, 0) += -k * d.G0[i];
    else M(i, slot0 + d.m - 1) += d.G0[i];
    M(i, slot0 + d.m) += d.G1[i];
  }
  M(slot0, 0) = -k;
  for (int i = 1; i <= d.m; ++i) M(slot0 + i, slot0 + i - 1) = 1.0;
  return M;
}

// The sampled loop's roots z (all 5 + m of them).
inline std::vector<std::complex<double>> platform_sampled_z(const firmware::PositionGyroPlatformPlant& s, double k,
                                                            double Tc, double tau) {
  const Eigen::VectorXcd ev = dynamics::eigenvalues(platform_sampled_matrix(s, k, Tc, tau));
  return {ev.data(), ev.data() + ev.size()};
}

// Its non-zero roots as ln(z)/Tc [1/s] (the delay slots' roots at z = 0 left out).
inline std::vector<std::complex<double>> platform_sampled_roots(const firmware::PositionGyroPlatformPlant& s,
                                                                double k, double Tc, double tau) {
  std::vector<std::complex<double>> out;
  for (const std::complex<double>& z : platform_sampled_z(s, k, Tc, tau))
    if (std::abs(z) > 1e-9) out.push_back(std::log(z) / Tc);
  return out;
}

inline std::complex<double> platform_dominant_root(const std::vector<std::complex<double>>& roots) {
  std::complex<double> best{-1e300, 0.0};
  for (const std::complex<double>& r : roots) {
    if (r.imag() < 0.0) continue;
    if (r.real() > best.real()) best = r;
  }
  return best;
}

}  // namespace gyrostab::oracles
