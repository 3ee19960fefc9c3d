// Docs: docs/sampled-data.md, docs/models/gyro-vertical.md.
#include "tools/devices/gyro_vertical/gyro_vertical_sampled.hpp"

#include <vector>

#include "firmware/control/gyro_vertical_correction.hpp"
#include "sim/analysis/state_feedback_linearisation.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::tools {

namespace {
using Plant = plants::GyroVerticalPlant;
using Model = Plant::Model;
constexpr int kN = Model::kStateSize;
}  // namespace

GyroVerticalSampled gyro_vertical_sampled(const GyroVerticalScene& s, std::complex<double> book) {
  plants::GyroVerticalPlantParams pp = s.plant;
  pp.sensors.erection_noise_density = pp.sensors.rate_noise_density = 0.0;
  const Plant plant(pp, s.loop.plant_timing());
  Model m = plant.model();
  const double t0 = m.inputs.frame.t0;
  Model::State x0 = Model::State::Zero();
  firmware::GyroVerticalCorrectionParams lp = s.controller.law;
  lp.torque_limit_Nm = 1e300;
  // The law on the signals the model gives at x (the turn rate of the straight frame: zero).
  const auto law = [&](const Model::State& x) {
    firmware::CorrectionSignals sig;
    m.erection_signal(t0, x, sig.e1, sig.e2);
    m.rates(t0, x, sig.alpha_rate, sig.beta_rate);
    sig.turn_rate = 0.0;
    const firmware::CorrectionTorques t = firmware::gyro_vertical_correction(lp, sig);
    return Eigen::Vector2d(t.M1, t.M2);
  };
  const auto f = [&](const Model::State& x, const Eigen::Vector2d& u) {
    m.inputs.M1 = u[0];
    m.inputs.M2 = u[1];
    Model::State dx;
    m.derivative(t0, x, dx);
    return dx;
  };
  // The model and the law are linear here: the differences are exact.
  const analysis::StateFeedbackLinearisation lin = analysis::linearise_state_feedback(x0, f, law, 1e-6, 1.0);
  const Eigen::MatrixXd &A = lin.A, &B = lin.B, &K = lin.K;
  GyroVerticalSampled r;
  r.Kx = K;
  {
    firmware::CorrectionSignals sig;
    const firmware::CorrectionTorques none = firmware::gyro_vertical_correction(lp, sig);
    for (int j = 0; j < 4; ++j) {
      firmware::CorrectionSignals p = sig;
      double* slot[4] = {&p.e1, &p.e2, &p.alpha_rate, &p.beta_rate};
      *slot[j] = 1.0;
      const firmware::CorrectionTorques t = firmware::gyro_vertical_correction(lp, p);
      r.Kv(0, j) = t.M1 - none.M1;
      r.Kv(1, j) = t.M2 - none.M2;
    }
  }
  // The states that act (the precession form leaves α', β' unused: zero rows and columns).
  std::vector<int> keep;
  for (int i = 0; i < kN; ++i)
    if (A.col(i).cwiseAbs().maxCoeff() > 0.0 || K.col(i).cwiseAbs().maxCoeff() > 0.0 ||
        A.row(i).cwiseAbs().maxCoeff() > 0.0)
      keep.push_back(i);
  const analysis::StateFeedbackLoop loop = analysis::restrict_state_feedback(A, B, K, keep);
  const Eigen::VectorXcd ev =
      dynamics::eigenvalues(Eigen::MatrixXd(loop.plant.A + loop.plant.B * loop.law.D * loop.plant.C));
  std::vector<std::complex<double>> cont(ev.data(), ev.data() + ev.size());
  r.continuous = analysis::nearest_root(cont, book);
  const double tick = s.loop.tick_s();
  r.roots = analysis::sampled_loop_roots(
      loop.plant, loop.law,
      {tick * static_cast<double>(s.controller.runtime.control_divisor), tick * static_cast<double>(s.loop.latency_ticks)});
  r.sampled = analysis::nearest_root(r.roots.s, r.continuous);
  const analysis::ZohStep z = analysis::zoh_step(A, B, tick * static_cast<double>(s.controller.runtime.control_divisor));
  r.Phi = z.Phi;
  r.Gamma = z.Gamma;
  return r;
}

}  // namespace gyrostab::tools
