// Docs: docs/sampled-data.md, docs/models/gyrocompass.md.
#include "tools/devices/gyrocompass/gyrocompass_sampled.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::tools {

namespace {
using Plant = plants::GyrocompassPlant;
using Model = Plant::Model;
constexpr int kN = Model::kStateSize;
}  // namespace

GyrocompassSampled gyrocompass_sampled(const GyrocompassScene& s) {
  // The plant settled at the precession theory's equilibrium of the starting base, no offset, no noise.
  plants::GyrocompassPlantParams pp = s.plant;
  pp.alpha0 = pp.beta0 = 0.0;
  pp.start_settled = true;
  pp.level_noise_density = 0.0;
  const Plant plant(pp, s.loop.plant_timing());
  Model m = plant.model();
  const Model::State x0 = plant.state();
  firmware::GyrocompassConfig c = s.controller;
  c.law.torque_limit_Nm = std::numeric_limits<double>::max();
  const auto law = [&](const Model::State& x, double& M1, double& M2) {
    const firmware::GyrocompassTorques t = firmware::gyrocompass_torques(c.law, m.level_signal(0.0, x));
    M1 = t.M1;
    M2 = t.M2;
  };
  double M1 = 0.0, M2 = 0.0;
  law(x0, M1, M2);
  const auto f = [&](const Model::State& x, double u1, double u2) {
    m.inputs.M1 = u1;
    m.inputs.M2 = u2;
    Model::State dx;
    m.derivative(0.0, x, dx);
    return dx;
  };
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(kN, kN), B = Eigen::MatrixXd::Zero(kN, 2), K = Eigen::MatrixXd::Zero(2, kN);
  for (int i = 0; i < kN; ++i) {
    const double h = 1e-7;
    Model::State xp = x0, xm = x0;
    xp[i] += h;
    xm[i] -= h;
    A.col(i) = (f(xp, M1, M2) - f(xm, M1, M2)) / (2.0 * h);
    double a1, a2, b1, b2;
    law(xp, a1, a2);
    law(xm, b1, b2);
    K(0, i) = (a1 - b1) / (2.0 * h);
    K(1, i) = (a2 - b2) / (2.0 * h);
  }
  // The torques enter linearly: a unit step is exact.
  B.col(0) = f(x0, M1 + 1.0, M2) - f(x0, M1, M2);
  B.col(1) = f(x0, M1, M2 + 1.0) - f(x0, M1, M2);
  // The states that act: the swing γ only with Θ_s > 0 (else it stays at rest, a neutral pair); the precession
  // form leaves α', β' unused (zero rows and columns).
  std::vector<int> keep;
  const bool swing = s.plant.gyro.swing_inertia > 0.0;
  for (int i = 0; i < kN; ++i) {
    if (!swing && (i == Model::kSwing || i == Model::kSwingRate)) continue;
    if (A.col(i).cwiseAbs().maxCoeff() > 0.0 || K.col(i).cwiseAbs().maxCoeff() > 0.0 ||
        A.row(i).cwiseAbs().maxCoeff() > 0.0)
      keep.push_back(i);
  }
  const analysis::StateFeedbackLoop loop = analysis::restrict_state_feedback(A, B, K, keep);
  const analysis::LinearPlant& p = loop.plant;
  const analysis::DiscreteLaw& d = loop.law;
  GyrocompassSampled out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.continuous = {nan, nan};
  const Eigen::VectorXcd ev = dynamics::eigenvalues(Eigen::MatrixXd(p.A + p.B * d.D * p.C));
  for (Eigen::Index i = 0; i < ev.size(); ++i)
    if (ev(i).imag() > 0.0 && (std::isnan(out.continuous.imag()) || ev(i).imag() < out.continuous.imag()))
      out.continuous = ev(i);
  const double tick = s.loop.tick_s();
  out.roots = analysis::sampled_loop_roots(
      p, d, {tick * static_cast<double>(s.controller.runtime.control_divisor), tick * static_cast<double>(s.loop.latency_ticks)});
  out.sampled = std::isnan(out.continuous.real()) ? out.continuous : analysis::nearest_root(out.roots.s, out.continuous);
  return out;
}

}  // namespace gyrostab::tools
