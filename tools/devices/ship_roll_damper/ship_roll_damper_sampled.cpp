// Docs: docs/sampled-data.md, docs/models/ship-roll-damper.md.
#include "tools/devices/ship_roll_damper/ship_roll_damper_sampled.hpp"

#include "sim/analysis/state_feedback_linearisation.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::tools {

ShipRollDamperSampled ship_roll_damper_sampled(const ShipRollDamperScene& s) {
  using Ship = models::ShipRollDamper;
  Ship m(s.plant.ship);
  m.inputs.E = 0.0;
  firmware::ShipRollDamperConfig c = s.controller;
  c.brake.torque_limit_Nm = c.active.torque_limit_Nm = 1e300;
  // The law on the frame the plant fills at x (exact sensors), a fresh copy each time (no braking latch).
  const auto law = [&](const Ship::State& x) {
    firmware::ShipRollDamperLaw::SensorFrame f{};
    f.roll_rad = x[Ship::kRoll];
    f.roll_rate_rad_s = x[Ship::kRollRate];
    f.precession_angle_rad = x[Ship::kPrecession];
    f.precession_rate_rad_s = x[Ship::kPrecessionRate];
    firmware::ShipRollDamperLaw l(c);
    firmware::ShipRollDamperLaw::ActuatorFrame cmd{};
    l.control(f, cmd);
    return Eigen::Matrix<double, 1, 1>(cmd.precession_torque_Nm);
  };
  const auto f = [&](const Ship::State& x, const Eigen::Matrix<double, 1, 1>& u) {
    m.inputs.M2 = u[0];
    Ship::State dx;
    m.derivative(0.0, x, dx);
    return dx;
  };
  // [rad], [rad/s]: the large-angle terms are O(h²) here; M2 enters linearly.
  const analysis::StateFeedbackLinearisation lin =
      analysis::linearise_state_feedback(Ship::State::Zero().eval(), f, law, 1e-7, 1.0);
  const Eigen::MatrixXd &A = lin.A, &B = lin.B, &K = lin.K;
  const analysis::StateFeedbackLoop loop = analysis::restrict_state_feedback(A, B, K, {0, 1, 2, 3});
  ShipRollDamperSampled r;
  const Eigen::VectorXcd ev = dynamics::eigenvalues(Eigen::MatrixXd(A + B * K));
  for (Eigen::Index i = 0; i < ev.size(); ++i)
    if (ev(i).imag() >= 0.0) r.continuous.push_back(ev(i));
  const double tick = s.loop.tick_s();
  r.roots = analysis::sampled_loop_roots(
      loop.plant, loop.law,
      {tick * static_cast<double>(s.controller.runtime.control_divisor), tick * static_cast<double>(s.loop.latency_ticks)});
  for (const std::complex<double>& c0 : r.continuous) r.sampled.push_back(analysis::nearest_root(r.roots.s, c0));
  return r;
}

}  // namespace gyrostab::tools
