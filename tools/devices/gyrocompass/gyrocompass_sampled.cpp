// Docs: docs/sampled-data.md, docs/models/gyrocompass.md.
#include "tools/devices/gyrocompass/gyrocompass_sampled.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "sim/analysis/state_feedback_linearisation.hpp"
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
  const auto law = [&](const Model::State& x) {
    const firmware::GyrocompassTorques t = firmware::gyrocompass_torques(c.law, m.level_signal(0.0, x));
    return Eigen::Vector2d(t.M1, t.M2);
  };
  const auto f = [&](const Model::State& x, const Eigen::Vector2d& u) {
    m.inputs.M1 = u[0];
    m.inputs.M2 = u[1];
    Model::State dx;
    m.derivative(0.0, x, dx);
    return dx;
  };
  // The torques enter linearly: a unit step is exact.
  const analysis::StateFeedbackLinearisation lin = analysis::linearise_state_feedback(x0, f, law, 1e-7, 1.0);
  const Eigen::MatrixXd &A = lin.A, &B = lin.B, &K = lin.K;
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
