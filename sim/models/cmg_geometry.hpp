// Geometry of a cluster of single-gimbal control moment gyros (Magnus §14.4, (14.45): the three-axis servo
// gyro; the spacecraft with CMGs is the gyrostat of §4.1 with rotors whose axes turn in the carrier).
//
// CMG i has a body-fixed unit gimbal axis g_i and a rotor of constant spin momentum h along the unit spin axis
// s_i(δ_i), which turns in the plane ⟂ g_i with the gimbal angle δ_i [rad]:
//   s_i(δ) = cos δ s0_i + sin δ (g_i × s0_i),       s0_i ⟂ g_i the spin axis at δ = 0,
//   t_i(δ) = ∂s_i/∂δ = g_i × s_i(δ)                 (the direction of the rotor's momentum change),
// so the cluster's momentum is H_cmg = h Σ s_i and its Jacobian A = ∂H_cmg/∂δ = h [t_1 … t_N] (3 × N).
//
// The default is the four-unit pyramid of skew angle β (the angle between each gimbal axis and the pyramid's
// axis z, i.e. the inclination of the pyramid's faces, to which the gimbal axes are normal):
//   g_1 = ( sβ, 0, cβ), s0_1 = ( 0,  1, 0)     g_2 = (0,  sβ, cβ), s0_2 = (−1, 0, 0)
//   g_3 = (−sβ, 0, cβ), s0_3 = ( 0, −1, 0)     g_4 = (0, −sβ, cβ), s0_4 = ( 1, 0, 0)
// which gives the classic H = h (−cβ s1 − c2 + cβ s3 + c4,  c1 − cβ s2 − c3 + cβ s4,  sβ Σ s_i) with
// s_i = sin δ_i, c_i = cos δ_i, zero momentum at δ = 0. β = arctan √2 = 54.74° makes the momentum envelope
// nearly spherical: its extent is 4h sinβ = 3.27h along z and 2h(1 + cosβ) = 3.15h along x and y.
// Envelope along a unit direction e (the largest projection H·e over all δ, each CMG on its own):
//   max_δ H·e = h Σ sqrt(1 − (e·g_i)²)
// (the largest of h(cos δ a + sin δ b) is h sqrt(a² + b²) = h |e − (e·g_i) g_i|).
// Oracle: tests/oracle/cmg_cluster_test.cpp. Docs: docs/models/cmg-cluster.md
#pragma once

#include <array>
#include <cmath>

#include "sim/dynamics/quaternion.hpp"

namespace gyrostab::models {

inline constexpr int kMaxCmgs = 4;  // the contract's cluster units (msg::kClusterUnits)

struct CmgGeometry {
  int count{0};
  // Zeroed explicitly: a value-initialised Eigen vector is not.
  std::array<dynamics::Vec3, kMaxCmgs> gimbal_axis{dynamics::Vec3::Zero(), dynamics::Vec3::Zero(),
                                                   dynamics::Vec3::Zero(), dynamics::Vec3::Zero()};  // g_i, unit, body axes
  std::array<dynamics::Vec3, kMaxCmgs> spin_axis0{dynamics::Vec3::Zero(), dynamics::Vec3::Zero(), dynamics::Vec3::Zero(),
                                                  dynamics::Vec3::Zero()};  // s0_i, unit, ⟂ g_i: the spin axis at δ_i = 0

  // nullptr if usable, else the reason.
  const char* invalid_reason() const {
    if (count < 1 || count > kMaxCmgs) return "the cluster has 1 to 4 CMGs";
    for (int i = 0; i < count; ++i) {
      if (std::fabs(gimbal_axis[i].norm() - 1.0) > 1e-9 || std::fabs(spin_axis0[i].norm() - 1.0) > 1e-9) {
        return "gimbal and spin axes must be unit vectors";
      }
      if (std::fabs(gimbal_axis[i].dot(spin_axis0[i])) > 1e-9) return "each spin axis must be normal to its gimbal axis";
    }
    return nullptr;
  }

  dynamics::Vec3 spin_axis(int i, double delta) const {
    return std::cos(delta) * spin_axis0[i] + std::sin(delta) * gimbal_axis[i].cross(spin_axis0[i]);
  }
  dynamics::Vec3 torque_axis(int i, double delta) const {
    return -std::sin(delta) * spin_axis0[i] + std::cos(delta) * gimbal_axis[i].cross(spin_axis0[i]);
  }
  // H_cmg / h = Σ s_i(δ_i).
  dynamics::Vec3 unit_momentum(const double* delta) const {
    dynamics::Vec3 H = dynamics::Vec3::Zero();
    for (int i = 0; i < count; ++i) H += spin_axis(i, delta[i]);
    return H;
  }
  // det(T Tᵀ), T = A/h = [t_1 … t_N]: the singularity measure, dimensionless (det(A Aᵀ)/h⁶); 0 at a
  // singular configuration, 16 cos⁴β sin²β at δ = 0 of the pyramid.
  double singularity_measure(const double* delta) const {
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for (int i = 0; i < count; ++i) {
      const dynamics::Vec3 t = torque_axis(i, delta[i]);
      M += t * t.transpose();
    }
    return M.determinant();
  }
  // The envelope's extent along the unit direction e: max over δ of H·e / h = Σ sqrt(1 − (e·g_i)²).
  double envelope_extent(const dynamics::Vec3& e) const {
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
      const double c = e.dot(gimbal_axis[i]);
      sum += std::sqrt(std::fmax(0.0, 1.0 - c * c));
    }
    return sum;
  }
};

inline constexpr double kPyramidSkewRad = 0.9553166181245093;  // arctan √2 = 54.7356°

// The four-unit pyramid at skew angle beta [rad] (see the header).
inline CmgGeometry pyramid_geometry(double beta = kPyramidSkewRad) {
  const double s = std::sin(beta), c = std::cos(beta);
  CmgGeometry g;
  g.count = 4;
  g.gimbal_axis = {dynamics::Vec3(s, 0, c), dynamics::Vec3(0, s, c), dynamics::Vec3(-s, 0, c), dynamics::Vec3(0, -s, c)};
  g.spin_axis0 = {dynamics::Vec3(0, 1, 0), dynamics::Vec3(-1, 0, 0), dynamics::Vec3(0, -1, 0), dynamics::Vec3(1, 0, 0)};
  return g;
}

}  // namespace gyrostab::models
