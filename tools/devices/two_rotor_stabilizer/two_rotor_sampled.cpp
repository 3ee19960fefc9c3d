// Docs: docs/sampled-data.md, docs/models/two-rotor-stabilizer.md.
#include "tools/devices/two_rotor_stabilizer/two_rotor_sampled.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::tools {

namespace {
using Plant = plants::TwoRotorStabilizerPlant;
constexpr int kN = Plant::Dynamics::kStateSize;

// The plant's dynamics at rest: no disturbance, no base motion.
Plant::Dynamics dynamics_at_rest(const TwoRotorStabilizerScene& s) {
  plants::TwoRotorPlantParams p = s.plant;
  p.base = plants::TwoRotorBase{};
  p.disturbance = plants::TwoRotorDisturbance{};
  return Plant::Dynamics{p.kind, Plant::Dynamics::Frame(p.frame, p.base), models::TwoRotorTwoAxis(p.two_axis),
                         p.disturbance};
}
}  // namespace

TwoRotorLinearLoop two_rotor_linear_loop(const TwoRotorStabilizerScene& s) {
  Plant::Dynamics d = dynamics_at_rest(s);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(kN, kN), B = Eigen::MatrixXd::Zero(kN, 2), K = Eigen::MatrixXd::Zero(2, kN);
  Plant::State dx;
  for (int i = 0; i < kN; ++i) {
    d.derivative(0.0, Plant::State::Unit(i), dx);
    A.col(i) = dx;
  }
  for (int j = 0; j < 2; ++j) {
    d.M1K = j == 0 ? 1.0 : 0.0;
    d.M2K = j == 1 ? 1.0 : 0.0;
    d.derivative(0.0, Plant::State::Zero(), dx);
    B.col(j) = dx;
  }
  firmware::TwoRotorStabilizerConfig c = s.controller;
  c.law.torque_limit_Nm = std::numeric_limits<double>::max();
  firmware::TwoRotorStabilizerLaw law(c);
  Plant plant(s.plant, s.loop.plant_timing());
  for (int i = 0; i < kN; ++i) {
    plant.set_state(Plant::State::Unit(i));
    Plant::SensorFrame f{};
    plant.sense(0, f);
    firmware::TwoRotorStabilizerLaw::ActuatorFrame out{};
    law.control(f, out);
    K(0, i) = out.frame1_torque_Nm;
    K(1, i) = out.frame2_torque_Nm;
  }
  TwoRotorLinearLoop loop;
  for (int i = 0; i < kN; ++i)
    if (A.col(i).cwiseAbs().maxCoeff() > 0.0 || K.col(i).cwiseAbs().maxCoeff() > 0.0) loop.states.push_back(i);
  analysis::StateFeedbackLoop r = analysis::restrict_state_feedback(A, B, K, loop.states);
  loop.plant = std::move(r.plant);
  loop.law = std::move(r.law);
  return loop;
}

analysis::SampledTiming two_rotor_timing(const TwoRotorStabilizerScene& s) {
  const double tick = s.loop.tick_s();
  return {tick * static_cast<double>(s.controller.runtime.control_divisor),
          tick * static_cast<double>(s.loop.latency_ticks)};
}

TwoRotorSampled two_rotor_sampled(const TwoRotorStabilizerScene& s) {
  TwoRotorSampled out;
  const TwoRotorLinearLoop loop = two_rotor_linear_loop(s);
  const analysis::LinearPlant& p = loop.plant;
  out.timing = two_rotor_timing(s);
  const Eigen::VectorXcd ev = dynamics::eigenvalues(Eigen::MatrixXd(p.A + p.B * loop.law.D * p.C));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.continuous = {nan, nan};
  out.continuous_stable = true;
  for (Eigen::Index i = 0; i < ev.size(); ++i) {
    const std::complex<double> l = ev(i);
    if (!(l.real() < 0.0)) out.continuous_stable = false;
    if (l.imag() > 0.0 && (std::isnan(out.continuous.real()) || l.real() > out.continuous.real())) out.continuous = l;
  }
  out.roots = analysis::sampled_loop_roots(p, loop.law, out.timing);
  out.sampled = std::isnan(out.continuous.real()) ? out.continuous : analysis::nearest_root(out.roots.s, out.continuous);
  return out;
}

}  // namespace gyrostab::tools
