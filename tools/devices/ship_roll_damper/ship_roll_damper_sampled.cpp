// Docs: docs/sampled-data.md, docs/models/ship-roll-damper.md.
#include "tools/devices/ship_roll_damper/ship_roll_damper_sampled.hpp"

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
    msg::SensorFrame f{};
    f.carrier_angle_rad[msg::kRoll] = x[Ship::kRoll];
    f.carrier_rate_rad_s[msg::kRoll] = x[Ship::kRollRate];
    f.gimbal_angle_rad[msg::kAxis2] = x[Ship::kPrecession];
    f.gimbal_rate_rad_s[msg::kAxis2] = x[Ship::kPrecessionRate];
    firmware::ShipRollDamperLaw l(c);
    msg::ActuatorFrame cmd{};
    l.control(f, cmd);
    return cmd.gimbal_torque_Nm[msg::kAxis2];
  };
  const auto f = [&](const Ship::State& x, double u) {
    m.inputs.M2 = u;
    Ship::State dx;
    m.derivative(0.0, x, dx);
    return dx;
  };
  const Ship::State x0 = Ship::State::Zero();
  constexpr int kN = Ship::kStateSize;
  Eigen::MatrixXd A(kN, kN), B(kN, 1), K(1, kN);
  constexpr double h = 1e-7;  // [rad], [rad/s]: the large-angle terms are O(h²) here
  for (int i = 0; i < kN; ++i) {
    Ship::State xp = x0, xm = x0;
    xp[i] += h;
    xm[i] -= h;
    A.col(i) = (f(xp, 0.0) - f(xm, 0.0)) / (2.0 * h);
    K(0, i) = (law(xp) - law(xm)) / (2.0 * h);
  }
  B.col(0) = f(x0, 1.0) - f(x0, 0.0);  // M2 enters linearly
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
