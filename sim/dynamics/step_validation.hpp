// Step validation: refuse, before running, a step that is unstable on a model's fastest mode or that
// cannot keep that mode's amplitude, and say which mode, at what frequency, and the largest usable step.
//
// The fastest mode is the eigenvalue λ of largest |λ| of the model's linearisation at the initial state
// (for a gimbal gyro this is the nutation H cosβ/sqrt(I(β) B), Magnus (4.65)/(10.15)).
// For each integrator the test equation y' = λy gives the per-step amplification R(hλ):
//   rk4                 R = 1 + z + z²/2 + z³/6 + z⁴/24
//   implicit-midpoint   R = (1 + z/2)/(1 - z/2)               (|R| = 1 on undamped modes)
//   strang, yoshida4, gyro-exponential
//                       R = e^z on oscillatory modes (solved exactly), but the kicks resonate at
//                       h·|Im λ| = 2πk: refused beyond h·|Im λ| ≤ 0.8·2π (docs/models/integrators.md);
//                       R = 1 + z + z²/2 on non-oscillatory modes (the kicks are second order).
// Bounds (StepBounds):
//   stable:      |R| ≤ 1 on every mode with Re λ ≤ 0;
//   amplitude:   on lightly damped modes (|Re λ| ≤ 0.1 |Im λ|) the numerical amplitude factor
//                (|R| / |e^z|)^(keep_time/h) stays within amplitude_tolerance of 1
//                (default: within 1e-3 over 10 s, the foundation's nutation-damping test).
// Docs: docs/models/integrators.md#step-validation-step_validationhpp
#pragma once

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>

#include "sim/dynamics/eigenvalues.hpp"
#include "sim/dynamics/implicit_midpoint.hpp"

namespace gyrostab::dynamics {

enum class Method { kRk4, kImplicitMidpoint, kStrang, kYoshida4, kGyroExponential };

inline const char* method_name(Method m) {
  switch (m) {
    case Method::kRk4: return "rk4";
    case Method::kImplicitMidpoint: return "implicit-midpoint";
    case Method::kStrang: return "strang";
    case Method::kYoshida4: return "yoshida4";
    case Method::kGyroExponential: return "gyro-exponential";
  }
  return "?";
}

struct Mode {
  std::string name;           // "nutation", "decay", ...
  std::complex<double> lambda;  // eigenvalue [1/s]
  double frequency_hz() const { return std::abs(lambda.imag()) / (2.0 * std::numbers::pi); }
};

struct StepBounds {
  double keep_time{10.0};             // [s]
  double amplitude_tolerance{1e-3};   // allowed |amplitude factor - 1| over keep_time
  double resonance_fraction{0.8};     // of 2π, for the splitting/exponential kicks
};

struct StepCheck {
  bool ok{false};
  double step{0.0};               // the step checked [s]
  double amplitude_factor{1.0};   // numerical amplitude factor over keep_time on the mode
  double frequency_error{0.0};    // relative numerical frequency error on the mode
  double largest_usable_step{0.0};
  int substeps_needed{1};         // sub-steps of `step` that make it usable
  std::string message;
};

namespace detail {

inline bool oscillatory(std::complex<double> l) { return std::abs(l.imag()) > std::abs(l.real()); }

inline std::complex<double> amplification(Method m, std::complex<double> z) {
  switch (m) {
    case Method::kRk4: return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)));
    case Method::kImplicitMidpoint: return (1.0 + 0.5 * z) / (1.0 - 0.5 * z);
    default:
      return oscillatory(z) ? std::exp(z) : 1.0 + z * (1.0 + 0.5 * z);
  }
}

struct Verdict {
  bool ok;
  double amplitude_factor;
  double frequency_error;
  const char* reason;
};

inline Verdict judge(Method m, std::complex<double> lambda, double h, const StepBounds& b) {
  const std::complex<double> z = h * lambda;
  const std::complex<double> R = amplification(m, z);
  const double per_step = std::abs(R) / std::exp(z.real());
  const double steps = b.keep_time / h;
  const double factor = std::exp(steps * std::log(per_step));
  double freq_err = 0.0;
  if (std::abs(z.imag()) > 0.0) freq_err = std::arg(R) / z.imag() - 1.0;
  const bool splitting = m == Method::kStrang || m == Method::kYoshida4 || m == Method::kGyroExponential;
  if (splitting && oscillatory(lambda) && std::abs(z.imag()) > b.resonance_fraction * 2.0 * std::numbers::pi) {
    return {false, factor, freq_err, "resonance"};
  }
  if (lambda.real() <= 0.0 && std::abs(R) > 1.0 + 1e-12) return {false, factor, freq_err, "unstable"};
  const bool lightly_damped = std::abs(lambda.real()) <= 0.1 * std::abs(lambda.imag());
  if (lightly_damped && std::abs(factor - 1.0) > b.amplitude_tolerance) return {false, factor, freq_err, "amplitude"};
  return {true, factor, freq_err, ""};
}

inline std::string format_step(double h) {
  char buf[64];
  if (h >= 1e-3) std::snprintf(buf, sizeof buf, "%.4g ms", h * 1e3);
  else std::snprintf(buf, sizeof buf, "%.4g us", h * 1e6);
  return buf;
}

}  // namespace detail

// Check step h of method m against a mode.
inline StepCheck check_step(Method m, const Mode& mode, double h, const StepBounds& b = {}) {
  StepCheck out;
  out.step = h;
  const detail::Verdict v = detail::judge(m, mode.lambda, h, b);
  out.ok = v.ok;
  out.amplitude_factor = v.amplitude_factor;
  out.frequency_error = v.frequency_error;
  int n = 1;
  for (; n <= 1000000; n = n < 16 ? n + 1 : n + n / 8) {
    if (detail::judge(m, mode.lambda, h / n, b).ok) break;
  }
  // Refine: the smallest n in the last bracket that passes.
  for (int k = n; k >= 1; --k) {
    if (!detail::judge(m, mode.lambda, h / k, b).ok) break;
    n = k;
  }
  out.substeps_needed = n;
  out.largest_usable_step = h / n;
  char buf[512];
  const double w = std::abs(mode.lambda.imag()) > 0 ? std::abs(mode.lambda.imag()) : std::abs(mode.lambda);
  if (v.ok) {
    std::snprintf(buf, sizeof buf,
                  "step %s accepted for %s: %s mode %.4g Hz (%.6g rad/s), amplitude factor %.6f over %g s, "
                  "frequency error %.2e",
                  detail::format_step(h).c_str(), method_name(m), mode.name.c_str(), mode.frequency_hz(), w,
                  v.amplitude_factor, b.keep_time, v.frequency_error);
  } else {
    const char* why = v.reason;
    std::string what;
    if (std::string(why) == "resonance") {
      what = "h·ω = " + std::to_string(h * std::abs(mode.lambda.imag())) + " is beyond the kick-resonance bound " +
             std::to_string(b.resonance_fraction) + "·2π";
    } else if (std::string(why) == "unstable") {
      what = "the step is unstable (|R(hλ)| > 1)";
    } else {
      char a[160];
      std::snprintf(a, sizeof a, "it keeps a factor %.3g of the amplitude over %g s (bound: within %g)",
                    v.amplitude_factor, b.keep_time, b.amplitude_tolerance);
      what = a;
    }
    std::snprintf(buf, sizeof buf,
                  "step %s refused for %s: %s mode at %.4g Hz (%.6g rad/s, λ = %.4g%+.4gi): %s; largest usable "
                  "step %s (%d sub-steps)",
                  detail::format_step(h).c_str(), method_name(m), mode.name.c_str(), mode.frequency_hz(), w,
                  mode.lambda.real(), mode.lambda.imag(), what.c_str(), detail::format_step(out.largest_usable_step).c_str(),
                  n);
  }
  out.message = buf;
  return out;
}

// The eigenvalue of largest |λ| of the model's linearisation at (t, x), named `oscillatory_name` when it
// oscillates, "divergence"/"decay" otherwise. Start-up only (not allocation-free by contract).
template <class Model>
Mode fastest_mode(const Model& model, double t, const typename Model::State& x,
                  const char* oscillatory_name = "nutation") {
  constexpr int N = Model::kStateSize;
  Eigen::Matrix<double, N, N> J;
  finite_difference_jacobian(model, t, x, J);
  const EigenvaluesOf<N> ev = eigenvalues<N>(J);
  std::complex<double> best{0.0, 0.0};
  for (int i = 0; i < N; ++i) {
    const std::complex<double> l = ev[i];
    if (std::abs(l) > std::abs(best) || (std::abs(l) == std::abs(best) && l.imag() > best.imag())) best = l;
  }
  Mode m;
  m.lambda = best;
  m.name = detail::oscillatory(best) ? oscillatory_name : (best.real() > 0 ? "divergence" : "decay");
  return m;
}

}  // namespace gyrostab::dynamics
