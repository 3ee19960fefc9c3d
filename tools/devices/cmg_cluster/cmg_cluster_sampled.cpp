// Docs: docs/sampled-data.md, docs/models/cmg-cluster.md.
#include "tools/devices/cmg_cluster/cmg_cluster_sampled.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "sim/analysis/state_feedback_linearisation.hpp"

namespace gyrostab::tools {

namespace {

using Model = plants::CmgClusterPlant::Model;
using Full = Model::State;
constexpr int kN = CmgClusterSampled::kN;
using Local = Eigen::Matrix<double, kN, 1>;

// The full state at local coordinates ξ around x0: q = q0 ⊗ (φ/2, √(1 − |φ/2|²)).
Full full_of(const Full& x0, const Local& xi) {
  Full x = x0;
  x.segment<3>(Model::kOmega) += xi.segment<3>(0);
  const dynamics::Quat q0(x0.segment<4>(Model::kQuat));
  const dynamics::Vec3 v = 0.5 * xi.segment<3>(3);
  const dynamics::Quat dq(std::sqrt(std::fmax(0.0, 1.0 - v.squaredNorm())), v.x(), v.y(), v.z());
  x.segment<4>(Model::kQuat) = (q0 * dq).coeffs();
  x.segment<12>(Model::kDelta) += xi.segment<12>(6);
  return x;
}

// φ of a quaternion q (not necessarily unit) around q0.
dynamics::Vec3 phi_of(const dynamics::Quat& q0, const Eigen::Vector4d& qc) {
  const dynamics::Quat q(Eigen::Vector4d(qc.normalized()));
  const dynamics::Quat d = q0.conjugate() * q;
  return 2.0 * (d.w() < 0.0 ? -1.0 : 1.0) * d.vec();
}

}  // namespace

CmgClusterSampled cmg_cluster_sampled(const CmgClusterScene& s, const plants::CmgClusterPlant::State& x0, double t0,
                                      int axis) {
  Model m(s.plant.model);
  const dynamics::Quat q0(x0.segment<4>(Model::kQuat));
  const int count = s.plant.model.geometry.count;
  firmware::CmgClusterConfig c = s.controller;
  c.steering.max_rate = std::numeric_limits<double>::max();
  firmware::CmgClusterLaw law(c);
  const double T = s.controller.runtime.control_period_s();
  const auto tick = static_cast<std::uint64_t>(std::llround(t0 / s.loop.tick_s()));
  // The law on the frame the plant would fill at ξ (no noise, exact encoders), with a body-rate error v.
  const auto command = [&](const Local& xi, const Eigen::Vector3d& v) {
    const Full x = full_of(x0, xi);
    firmware::CmgClusterLaw::SensorFrame f{};
    f.tick = tick;
    const dynamics::Vec3 e = plants::euler321_of(dynamics::Quat(x.segment<4>(Model::kQuat)));
    for (int k = 0; k < 3; ++k) {
      f.attitude_rad[k] = e[k];
      f.body_rate_rad_s[k] = x[Model::kOmega + k] + v[k];
    }
    double d[4];
    for (int i = 0; i < 4; ++i) {
      d[i] = i < count ? x[Model::kDelta + i] : 0.0;
      d[i] = std::remainder(d[i], 2.0 * std::numbers::pi);
    }
    for (int i = 0; i < 4; ++i) f.delta_rad[i] = d[i];
    firmware::CmgClusterLaw::ActuatorFrame cmd{};
    law.control(f, cmd);
    return Eigen::Vector4d(cmd.gimbal_rate_command_rad_s[0], cmd.gimbal_rate_command_rad_s[1],
                           cmd.gimbal_rate_command_rad_s[2], cmd.gimbal_rate_command_rad_s[3]);
  };
  // ξ' at ξ under the held rate commands u: the model's derivative, the quaternion's through φ's Jacobian.
  const auto rate = [&](const Local& xi, const Eigen::Vector4d& u) {
    for (int i = 0; i < 4; ++i) m.inputs.rate_command[i] = i < count ? u[i] : 0.0;
    const Full x = full_of(x0, xi);
    Full dx;
    m.derivative(0.0, x, dx);
    Local r;
    r.segment<3>(0) = dx.segment<3>(Model::kOmega);
    const Eigen::Vector4d q = x.segment<4>(Model::kQuat), dq = dx.segment<4>(Model::kQuat);
    const double eps = 1e-6 / std::fmax(dq.norm(), 1e-300);
    r.segment<3>(3) = dq.norm() > 0.0 ? Eigen::Vector3d((phi_of(q0, q + eps * dq) - phi_of(q0, q - eps * dq)) / (2.0 * eps))
                                      : Eigen::Vector3d::Zero();
    r.segment<12>(6) = dx.segment<12>(Model::kDelta);
    return r;
  };
  const Local zero = Local::Zero();
  constexpr double h = 1e-6;
  const analysis::StateFeedbackLinearisation lin = analysis::linearise_state_feedback(
      zero, rate, [&](const Local& xi) { return command(xi, Eigen::Vector3d::Zero()); }, h, h);
  const Eigen::MatrixXd &A = lin.A, &B = lin.B, &K = lin.K;
  Eigen::MatrixXd Kv(4, 3);
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d v = h * Eigen::Vector3d::Unit(j);
    Kv.col(j) = (command(zero, v) - command(zero, -v)) / (2.0 * h);
  }
  // The states that act (unused CMG slots are zero rows and columns).
  std::vector<int> keep;
  for (int i = 0; i < kN; ++i)
    if (A.col(i).cwiseAbs().maxCoeff() > 0.0 || A.row(i).cwiseAbs().maxCoeff() > 0.0 ||
        K.col(i).cwiseAbs().maxCoeff() > 0.0)
      keep.push_back(i);
  const analysis::StateFeedbackLoop loop = analysis::restrict_state_feedback(A, B, K, keep);
  CmgClusterSampled r;
  const double Jk = s.plant.model.J(axis, axis);
  const double a1 = s.controller.attitude.kd[axis] / Jk, a0 = 0.5 * s.controller.attitude.kp[axis] / Jk;
  const std::complex<double> disc = std::sqrt(std::complex<double>(0.25 * a1 * a1 - a0, 0.0));
  r.design[0] = -0.5 * a1 + disc;
  r.design[1] = -0.5 * a1 - disc;
  r.roots = analysis::sampled_loop_roots(loop.plant, loop.law, {T, s.loop.tick_s() * static_cast<double>(s.loop.latency_ticks)});
  // Every axis has its pair near the same design root (K_p, K_d scale with J): the axis's pair is the two
  // roots, among those within a design decay rate of it, whose eigenvectors weigh most on ω_k and φ_k.
  const auto pos = [&](int full) {
    for (std::size_t i = 0; i < keep.size(); ++i)
      if (keep[i] == full) return static_cast<Eigen::Index>(i);
    return Eigen::Index{-1};
  };
  const Eigen::EigenSolver<Eigen::MatrixXd> es(r.roots.M, true);
  const std::complex<double> centre(-0.5 * a1, 0.0);
  struct Candidate {
    std::complex<double> s;
    double weight;
    Eigen::Matrix<std::complex<double>, 6, 1> out;  // (q, ω) of its eigenvector
  };
  std::vector<Candidate> near;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
    const std::complex<double> z = es.eigenvalues()(i);
    if (std::abs(z) < 1e-12) continue;
    const std::complex<double> sv = std::log(z) / T;
    if (std::abs(sv - centre) > 0.5 * a1) continue;
    const Eigen::VectorXcd v = es.eigenvectors().col(i);
    Eigen::Matrix<std::complex<double>, 6, 1> out = Eigen::Matrix<std::complex<double>, 6, 1>::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index a = pos(3 + k), b = pos(k);
      if (a >= 0) out(k) = 0.5 * v(a);
      if (b >= 0) out(3 + k) = v(b);
    }
    // ω_k against φ_k = 2 q_k: both in the units of the loop's torque.
    const double w = (std::norm(out(3 + axis)) + 4.0 * a0 * a0 * std::norm(out(axis))) * Jk * Jk;
    near.push_back({sv, w / v.squaredNorm(), out});
  }
  double total = 0.0;
  for (const Candidate& cand : near) total += cand.weight;
  double chosen = 0.0;
  for (int i = 0; i < 2 && !near.empty(); ++i) {
    std::size_t best = 0;
    for (std::size_t j = 1; j < near.size(); ++j)
      if (near[j].weight > near[best].weight) best = j;
    r.sampled[i] = near[best].s;
    chosen += near[best].weight;
    near.erase(near.begin() + static_cast<std::ptrdiff_t>(best));
  }
  r.share = total > 0.0 ? chosen / total : 0.0;
  // The modal filter: the plane orthogonal to the other attitude pairs' output directions. The gimbals' null
  // motions (roots near 0 that barely reach the attitude: weight ~1e-9 of the pair's) are not pairs to null:
  // the fit's drift terms take them. Where the other pairs do not span four directions (they do not reach
  // the outputs), the slew axis's own (q_k, ω_k).
  r.filter.setZero();
  r.filter(0, axis) = 1.0;
  r.filter(1, 3 + axis) = 1.0;
  std::erase_if(near, [&](const Candidate& cand) { return cand.weight < 1e-6 * chosen; });
  if (!near.empty()) {
    Eigen::MatrixXd other(6, 2 * static_cast<Eigen::Index>(near.size()));
    for (std::size_t j = 0; j < near.size(); ++j) {
      const auto col = static_cast<Eigen::Index>(2 * j);
      const double n = near[j].out.norm();
      other.col(col) = near[j].out.real() / n;
      other.col(col + 1) = near[j].out.imag() / n;
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(other, Eigen::ComputeFullU);
    const Eigen::VectorXd& sv = svd.singularValues();
    Eigen::Index rank = 0;
    while (rank < sv.size() && sv(rank) > 1e-6 * sv(0)) ++rank;
    if (rank == 4) r.filter = svd.matrixU().rightCols(2).transpose();
  }
  const analysis::ZohStep z = analysis::zoh_step(A, B, T);
  r.Phi = z.Phi;
  r.Gamma = z.Gamma;
  r.Kx = K;
  r.Kv = Kv;
  return r;
}

}  // namespace gyrostab::tools
