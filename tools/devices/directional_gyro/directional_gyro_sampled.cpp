// Docs: docs/sampled-data.md, docs/models/directional-gyro.md.
#include "tools/devices/directional_gyro/directional_gyro_sampled.hpp"

#include <cmath>
#include <vector>

#include "firmware/control/directional_gyro_corrections.hpp"
#include "sim/analysis/state_feedback_linearisation.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::tools {

DirectionalGyroSampled directional_gyro_sampled(const DirectionalGyroScene& s, const plants::DirectionalGyroPlant& p) {
  using Model = plants::DirectionalGyroPlant::Model;
  Model m = p.model();
  m.inputs.case_rate.hold(p.case_rate());
  const Model::State x0 = p.state();
  // The indication is the card's setting plus α: the law sees ψ0 + (α − α0).
  const double psi0 = p.indicated_heading_rad(), psi_ref = p.true_heading_rad();
  firmware::DirectionalGyroCorrectionParams lp = s.controller.law;
  lp.torque_limit_Nm = 1e300;
  const auto law = [&](const Model::State& x) {
    firmware::DirectionalGyroSignals sig;
    sig.heading = psi0 + (x[Model::kAlpha] - x0[Model::kAlpha]);
    sig.beta = x[Model::kBeta];
    sig.heading_ref = psi_ref;
    const firmware::DirectionalGyroTorques t = firmware::directional_gyro_corrections(lp, sig);
    return Eigen::Vector2d(t.M1, t.M2);
  };
  const auto f = [&](const Model::State& x, const Eigen::Vector2d& u) {
    m.inputs.M1 = u[0];
    m.inputs.M2 = u[1];
    Model::State dx;
    m.derivative(0.0, x, dx);
    return Eigen::Vector2d(dx[0], dx[1]);
  };
  // [rad]: the kinematics' curvature is O(1), truncation O(1e-12); the torques enter linearly.
  const analysis::StateFeedbackLinearisation lin = analysis::linearise_state_feedback(x0, f, law, 1e-6, 1e-6);
  const Eigen::MatrixXd &A = lin.A, &B = lin.B, &K = lin.K;
  const analysis::StateFeedbackLoop loop = analysis::restrict_state_feedback(A, B, K, {0, 1});
  DirectionalGyroSampled r;
  const double book = -s.controller.law.k / s.controller.law.H;
  const Eigen::VectorXcd ev = dynamics::eigenvalues(Eigen::MatrixXd(A + B * K));
  std::vector<std::complex<double>> cont(ev.data(), ev.data() + ev.size());
  r.continuous = analysis::nearest_root(cont, {book, 0.0}).real();
  const double tick = s.loop.tick_s();
  r.roots = analysis::sampled_loop_roots(
      loop.plant, loop.law,
      {tick * static_cast<double>(s.controller.runtime.control_divisor), tick * static_cast<double>(s.loop.latency_ticks)});
  r.sampled = analysis::nearest_root(r.roots.s, {r.continuous, 0.0});
  return r;
}

}  // namespace gyrostab::tools
