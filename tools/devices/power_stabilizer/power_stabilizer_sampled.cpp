#include "tools/devices/power_stabilizer/power_stabilizer_sampled.hpp"

#include "tools/devices/power_stabilizer/power_stabilizer_checks.hpp"

namespace gyrostab::tools {

analysis::LinearPlant power_stabilizer_linear_plant(const firmware::PowerStabilizerConfig& l) {
  const bool emf = l.output == firmware::PowerStabilizerOutput::kBackEmfVoltage;
  const double D1 = l.bearing_d1 + (emf ? l.s * l.d_emf : 0.0), D2 = l.bearing_d2;
  analysis::LinearPlant p;
  p.A = Eigen::MatrixXd::Zero(4, 4);
  p.A(0, 2) = 1.0;
  p.A(1, 3) = 1.0;
  // A α'' = −H β' − D1 α' + M1,   B β'' = H α' − D2 β' + M2
  p.A(2, 2) = -D1 / l.A;
  p.A(2, 3) = -l.H / l.A;
  p.A(3, 2) = l.H / l.B;
  p.A(3, 3) = -D2 / l.B;
  p.B = Eigen::MatrixXd::Zero(4, emf ? 1 : 2);
  p.B(2, 0) = (emf ? l.s : 1.0) / l.A;
  if (!emf) p.B(3, 1) = 1.0 / l.B;
  p.C = Eigen::MatrixXd::Identity(4, 4);
  return p;
}

analysis::DiscreteLaw power_stabilizer_probed_law(const firmware::PowerStabilizerConfig& l) {
  firmware::PowerStabilizerConfig c = l;
  c.torque_limit_Nm[0] = c.torque_limit_Nm[1] = c.voltage_limit_V = 1e300;
  const firmware::PowerStabilizerLoops law(c);
  const bool emf = l.output == firmware::PowerStabilizerOutput::kBackEmfVoltage;
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(emf ? 1 : 2, 4);
  for (int j = 0; j < 4; ++j) {
    msg::power_stabilizer::SensorFrame in{};
    double* slot[4] = {&in.alpha_rad, &in.beta_rad, &in.alpha_rate_rad_s, &in.beta_rate_rad_s};
    *slot[j] = 1.0;
    msg::power_stabilizer::ActuatorFrame out{};
    law.compute(in, out);
    if (emf) {
      D(0, j) = out.motor1_voltage_V;
    } else {
      D(0, j) = out.motor1_torque_Nm;
      D(1, j) = out.motor2_torque_Nm;
    }
  }
  return analysis::DiscreteLaw::gain(D);
}

analysis::SampledTiming power_stabilizer_timing(const PowerStabilizerScene& s) {
  const double tick = s.loop.tick_s();
  return {tick * static_cast<double>(s.controller.runtime.control_divisor),
          tick * static_cast<double>(s.loop.latency_ticks)};
}

PowerStabilizerSampled power_stabilizer_sampled(const firmware::PowerStabilizerConfig& l,
                                                const analysis::SampledTiming& t) {
  PowerStabilizerSampled out;
  out.timing = t;
  analysis::LinearPlant p = power_stabilizer_linear_plant(l);
  const analysis::DiscreteLaw law = power_stabilizer_probed_law(l);
  // Back-EMF mode: α is neutral (the λ = 0 of (14.29): no torque depends on α, and the law reads β and α'
  // only), a root at z = 1 exactly that no verdict should weigh. α is dropped from the state when nothing
  // reads it; its row of C is then zero.
  if (l.output == firmware::PowerStabilizerOutput::kBackEmfVoltage && law.D.col(0).isZero(0.0) &&
      p.A.col(0).isZero(0.0)) {
    p.A = Eigen::MatrixXd(p.A.bottomRightCorner(3, 3));
    p.B = Eigen::MatrixXd(p.B.bottomRows(3));
    p.C = Eigen::MatrixXd(p.C.rightCols(3));
  }
  out.roots = analysis::sampled_loop_roots(p, law, t);
  out.nutation = analysis::nearest_root(out.roots.s, predicted_nutation(l));
  return out;
}

Eigen::Vector2d power_stabilizer_sampled_steady(const firmware::PowerStabilizerConfig& l,
                                                const analysis::SampledTiming& t, double M1, double M2) {
  const analysis::LinearPlant p = power_stabilizer_linear_plant(l);
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(4, 2);
  E(2, 0) = 1.0 / l.A;
  E(3, 1) = 1.0 / l.B;
  const Eigen::VectorXd x =
      analysis::sampled_steady_state(p, power_stabilizer_probed_law(l), t, E, Eigen::Vector2d(M1, M2));
  return {x[0], x[1]};
}

}  // namespace gyrostab::tools
