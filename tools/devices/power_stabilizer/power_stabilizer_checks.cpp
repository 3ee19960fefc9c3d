#include "tools/devices/power_stabilizer/power_stabilizer_checks.hpp"

#include <algorithm>
#include <cmath>

#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab::tools {
namespace {

template <int N>
std::complex<double> nutation_root(const double (&c)[N + 1]) {
  Eigen::Matrix<double, N, N> companion = Eigen::Matrix<double, N, N>::Zero();
  for (int i = 0; i < N; ++i) companion(0, i) = -c[i + 1] / c[0];
  for (int i = 1; i < N; ++i) companion(i, i - 1) = 1.0;
  const dynamics::EigenvaluesOf<N> ev = dynamics::eigenvalues<N>(companion);
  std::complex<double> best{0.0, 0.0};
  for (int i = 0; i < N; ++i) {
    if (std::abs(ev[i].imag()) > std::abs(best.imag())) best = ev[i];
  }
  return {best.real(), std::abs(best.imag())};
}

}  // namespace

bool check_power_stabilizer_plant(SceneReader& r, PowerStabilizerScene& s) {
  if (s.precession()) return check_power_stabilizer_precession(r, s);
  if (s.elastic()) return check_power_stabilizer_elastic(r, s);
  return check_power_stabilizer_rigid(r, s);
}

std::vector<std::string> power_stabilizer_plant_rules() {
  return {
      "the plant built with the scene's options is physically possible (inertias > 0; back_emf: s > 0, d ≥ "
      "0; elastic: c, AP > 0)",
      "the controller's start-up check (firmware/app/power_stabilizer_controller.hpp) with A, B as the plant "
      "has them: the Hurwitz test (14.25), or r < H d/A (14.30) with back_emf",
      "the loop (14.23)/(14.29) linearised at the inner gimbal's operating points — `beta0_deg` and the "
      "steady deflection M1/k1 (14.21) — with H cos β and I(β) passes the same test, else \"gimbal-lock "
      "approach\" names the angle and the coupling",
      "the loop as it runs — sampled at the law's period (control_divisor ticks) through the zero-order hold with "
      "latency_ticks of latency, at the same operating points — has every root |z| < 1 (docs/sampled-data.md); "
      "the message says when the continuous verdict differs",
      "the plant step resolves the fastest mode (step validation: the sub-steps needed are printed); "
      "dc_motor: the step is below the explicit drive coupling's 2J/(b + b_e)",
      "precession: ε = ω_P/ω_N < 0.1 at the operating point, no `dc_motor`; the full model for the "
      "comparison needs at most 100000 sub-steps",
  };
}

std::complex<double> predicted_nutation(const firmware::PowerStabilizerConfig& l) {
  const double A = l.A, B = l.B, H = l.H;
  if (l.output == firmware::PowerStabilizerOutput::kBackEmfVoltage) {
    const double D1 = l.s * (l.d_emf + l.d_c) + l.bearing_d1, d2 = l.bearing_d2;
    const double c[4] = {A * B, A * d2 + B * D1, H * H + D1 * d2, H * l.r * l.s};
    return nutation_root<3>(c);
  }
  const double d1 = l.d1 + l.bearing_d1, d2 = l.d2 + l.bearing_d2;
  const double c[5] = {A * B, A * d2 + B * d1, H * H + d1 * d2, H * (l.k1 + l.k2), l.k1 * l.k2};
  return nutation_root<4>(c);
}

NutationWindow nutation_window(const plants::PowerDisturbance& d, double window_s) {
  NutationWindow w;
  w.step_s = d.M2 != 0.0 && d.t2 > 0.0 ? d.t2 : first_step_s(d);
  w.end_s = w.step_s + window_s;
  if (d.M1 != 0.0 && d.t1 > w.step_s) w.end_s = std::min(w.end_s, d.t1);
  if (d.M2 != 0.0 && d.t2 > w.step_s) w.end_s = std::min(w.end_s, d.t2);
  return w;
}

double first_step_s(const plants::PowerDisturbance& d) {
  const bool s1 = d.M1 != 0.0 && d.t1 > 0.0, s2 = d.M2 != 0.0 && d.t2 > 0.0;
  if (s1 && s2) return std::min(d.t1, d.t2);
  if (s1) return d.t1;
  if (s2) return d.t2;
  return std::min(d.t1, d.t2);
}

}  // namespace gyrostab::tools
