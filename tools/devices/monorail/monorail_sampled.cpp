#include "tools/devices/monorail/monorail_sampled.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

namespace gyrostab::tools {

analysis::LinearPlant monorail_linear_plant(const models::MonorailParams& car, double Omega3) {
  const double c = car.c - car.H * Omega3, q = car.q - car.H * Omega3;
  analysis::LinearPlant p;
  p.A = Eigen::MatrixXd::Zero(4, 4);
  p.A(0, 2) = 1.0;
  p.A(1, 3) = 1.0;
  // A φ'' = c φ − H β' + M1,   B β'' = q β − d β' + H φ' + M2 (the plant's own analog k φ, if any, too)
  p.A(2, 0) = c / car.A;
  p.A(2, 3) = -car.H / car.A;
  p.A(3, 0) = car.k / car.B;
  p.A(3, 1) = q / car.B;
  p.A(3, 2) = car.H / car.B;
  p.A(3, 3) = -car.d / car.B;
  p.B = Eigen::MatrixXd::Zero(4, 1);
  p.B(3, 0) = 1.0 / car.B;
  p.C = Eigen::MatrixXd::Zero(2, 4);
  p.C(0, 0) = 1.0;
  p.C(1, 3) = 1.0;
  return p;
}

analysis::DiscreteLaw monorail_probed_law(const firmware::MonorailConfig& c) {
  firmware::MonorailConfig lifted = c;
  lifted.law.torque_limit_Nm = 1e300;
  const firmware::MonorailLaw law(lifted);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(1, 2);
  for (int j = 0; j < 2; ++j) {
    firmware::MonorailLaw::SensorFrame in{};
    (j == 0 ? in.tilt_rad : in.case_rate_rad_s) = 1.0;
    firmware::MonorailLaw::ActuatorFrame out{};
    law.control(in, out);
    D(0, j) = out.motor_torque_Nm;
  }
  return analysis::DiscreteLaw::gain(D);
}

analysis::SampledTiming monorail_timing(const firmware::MonorailConfig& c, double tick_s, int latency_ticks) {
  return {tick_s * static_cast<double>(c.runtime.control_divisor), tick_s * static_cast<double>(latency_ticks)};
}

MonorailSampled monorail_sampled(const models::MonorailParams& car, const firmware::MonorailConfig& c,
                                 double Omega3, const analysis::SampledTiming& t) {
  MonorailSampled out;
  out.roots = analysis::sampled_loop_roots(monorail_linear_plant(car, Omega3), monorail_probed_law(c), t);
  double re = -std::numeric_limits<double>::infinity();
  for (const std::complex<double>& s : out.roots.s) re = std::max(re, s.real());
  out.decay_rate_per_s = -re;
  return out;
}

Eigen::Vector2d monorail_sampled_steady(const models::MonorailParams& car, const firmware::MonorailConfig& c,
                                        double Omega3, const analysis::SampledTiming& t, double M1, double bias) {
  const analysis::DiscreteLaw law = monorail_probed_law(c);
  // The bias reaches the motor through the law's φ gain: a constant M2 = D_φ · bias.
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(4, 2);
  E(2, 0) = 1.0 / car.A;
  E(3, 1) = 1.0 / car.B;
  const Eigen::VectorXd x = analysis::sampled_steady_state(monorail_linear_plant(car, Omega3), law, t, E,
                                                           Eigen::Vector2d(M1, law.D(0, 0) * bias));
  return {x[0], x[1]};
}

Eigen::Vector2d monorail_sampled_steady_large_angle(const models::MonorailParams& car,
                                                    const firmware::MonorailConfig& c, double Omega3,
                                                    const analysis::SampledTiming& t, double gust_Nm,
                                                    double lateral_g, double bias) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d x = monorail_sampled_steady(car, c, Omega3, t, gust_Nm + car.c * lateral_g, bias);
  if (!x.allFinite()) return {nan, nan};
  const double D_phi = monorail_probed_law(c).D(0, 0);
  models::Monorail m(car);
  const auto residual = [&](const Eigen::Vector2d& q) {
    m.inputs.Omega3 = Omega3;
    m.inputs.M1 = gust_Nm + car.c * lateral_g * std::cos(q[0]);
    m.inputs.M2 = D_phi * (q[0] + bias);
    models::Monorail::State dx;
    m.derivative(0.0, models::Monorail::make_state(q[0], q[1], 0.0, 0.0), dx);
    // Accelerations times the inertias: the torque balances, of one size on both axes.
    return Eigen::Vector2d(dx[2] * car.A, dx[3] * car.B);
  };
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector2d r = residual(x);
    Eigen::Matrix2d J;
    for (int j = 0; j < 2; ++j) {
      Eigen::Vector2d e = x;
      const double h = 1e-7 * std::max(1.0, std::fabs(x[j]));
      e[j] += h;
      J.col(j) = (residual(e) - r) / h;
    }
    const Eigen::Vector2d step = J.fullPivLu().solve(r);
    if (!step.allFinite()) return {nan, nan};
    x -= step;
    if (step.norm() <= 1e-15 * std::max(1.0, x.norm())) return x;
  }
  return residual(x).norm() <= 1e-9 * (std::fabs(gust_Nm) + car.c * std::fabs(lateral_g) + 1.0) ? x
                                                                                               : Eigen::Vector2d(nan, nan);
}

}  // namespace gyrostab::tools
