// Docs: docs/sampled-data.md, docs/models/servo-gyro.md.
#include "tools/devices/servo_gyro/servo_gyro_sampled.hpp"

#include <cmath>

#include "firmware/control/servo_gyro_law.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::tools {

ServoGyroSampled servo_gyro_sampled(const ServoGyroScene& s) {
  const models::ServoGyroParams& g = s.plant.gyro;
  Eigen::MatrixXd A(1, 1), B(1, 1), C(1, 1);
  A << -g.d2 / g.B;
  B << 1.0 / g.B;
  C << 1.0;
  // The law probed: M2 = H_l I + D y, I⁺ = I + G y (y = β' read; the reference and the feed-forward are
  // inputs the loop does not feed back).
  firmware::ServoGyroParams lp = s.controller.law;
  lp.torque_limit_Nm = 1e300;
  lp.feedforward = false;
  const double T = s.controller.runtime.control_period_s();
  const firmware::ServoGyroRateLoop base(lp, T);
  const auto step = [](firmware::ServoGyroRateLoop& l, double y) {
    return l.step({0.0, 0.0, y, 0.0}).torque_Nm;
  };
  firmware::ServoGyroRateLoop zero = base, one = base;
  const double M0 = step(zero, 0.0), M1 = step(one, 1.0);
  const double G = one.integral_Nm() - base.integral_Nm();
  const double M1next = step(one, 0.0);
  firmware::ServoGyroRateLoop zero2 = zero;
  const double M0next = step(zero2, 0.0);
  analysis::DiscreteLaw law;
  law.F = Eigen::MatrixXd::Identity(1, 1);
  law.G = Eigen::MatrixXd::Constant(1, 1, G);
  law.H = Eigen::MatrixXd::Constant(1, 1, (M1next - M0next) / G);
  law.D = Eigen::MatrixXd::Constant(1, 1, M1 - M0);
  ServoGyroSampled r;
  // The continuous loop: B β'' = −d2 β' + k_p e + ∫k_i e, e = −β': s² + ((k_p + d2)/B) s + k_i/B = 0.
  const double a1 = (lp.rate_kp + g.d2) / g.B, a0 = lp.rate_ki / g.B;
  const std::complex<double> disc = std::sqrt(std::complex<double>(a1 * a1 / 4.0 - a0, 0.0));
  r.continuous[0] = -a1 / 2.0 + disc;
  r.continuous[1] = -a1 / 2.0 - disc;
  const double tick = s.loop.tick_s();
  r.roots = analysis::sampled_loop_roots({A, B, C}, law, {T, tick * static_cast<double>(s.loop.latency_ticks)});
  // The sampled pair: the two roots nearest the continuous pair's centre.
  const std::array<std::complex<double>, 2> pair = analysis::nearest_pair(r.roots.s, {-a1 / 2.0, 0.0});
  r.sampled[0] = pair[0];
  r.sampled[1] = pair[1];
  return r;
}

}  // namespace gyrostab::tools
