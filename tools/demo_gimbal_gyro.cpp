#include "tools/demo_gimbal_gyro.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "sim/analysis/zero_crossing_meter.hpp"
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/implicit_midpoint.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/step_validation.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/gimbal_gyro.hpp"
#include "sim/oracles/gyro_pendulum_quartic.hpp"

namespace gyrostab::tools {
namespace {

using Gyro = models::GimbalGyro<models::FixedBase>;

struct Measured {
  double omega;
  double amplitude_ratio;  // modal amplitude sqrt(α² + (α'/ω)²) at the end / at the start
};

// Excite one pure mode of the linear pendulum and measure its frequency from α's zero crossings over
// `periods` whole periods, running the plant tick by tick with the chosen integrator.
template <class Integrator>
Measured measure(const Gyro& gyro, double H, double omega, double periods, std::int64_t tick_ns, int substeps) {
  const double alpha0 = 1e-4;  // small: the oracle is the linear model (amplitude² effects ~1e-8)
  const auto& p = gyro.params();
  Gyro::State x = Gyro::make_state(alpha0, 0.0, 0.0,
                                   oracles::pure_mode_beta_rate(p.B(), H, p.Gs, omega, alpha0), H);
  Integrator integrator(gyro);
  dynamics::SubstepDriver<Integrator> driver(integrator, tick_ns, substeps);
  analysis::ZeroCrossingMeter meter;
  const double period = 2.0 * std::numbers::pi / omega;
  const auto ticks = static_cast<std::int64_t>(std::ceil((periods + 1.0) * period / (1e-9 * static_cast<double>(tick_ns))));
  // For a pure mode α = a cos ωt, so sqrt(α² + (α'/ω)²) = a at every sample.
  const auto amplitude = [omega](const Gyro::State& s) { return std::hypot(s[0], s[2] / omega); };
  const double a_start = amplitude(x);
  for (std::int64_t k = 0; k < ticks; ++k) {
    driver.advance_tick(k, x);
    meter.add(1e-9 * static_cast<double>((k + 1) * tick_ns), x[0], x[2]);
  }
  return {meter.angular_frequency(), amplitude(x) / a_start};
}

template <class Integrator>
void report(const Gyro& gyro, double H, const oracles::PendulumFrequencies& book, std::int64_t tick_ns,
            int substeps) {
  const Measured n = measure<Integrator>(gyro, H, book.nutation, 2000.0, tick_ns, substeps);
  const Measured p = measure<Integrator>(gyro, H, book.precession, 2.0, tick_ns, substeps);
  const auto& q = gyro.params();
  std::printf("%-22s %16s %18s %11s %20s\n", "", "simulated", "book exact (10.15)", "rel. error",
              "book approx (10.17)");
  std::printf("%-22s %16.9g %18.9g %11.2e %20.9g  (H/sqrt(AB))\n", "nutation  ω_N [rad/s]", n.omega,
              book.nutation, n.omega / book.nutation - 1.0, H / std::sqrt(q.A() * q.B()));
  std::printf("%-22s %16.9g %18.9g %11.2e %20.9g  (|Gs|/H)\n", "precession ω_P [rad/s]", p.omega,
              book.precession, p.omega / book.precession - 1.0, std::abs(q.Gs) / H);
  std::printf("nutation amplitude after 2000 periods: %.6f of the initial one (undamped model: 1)\n",
              n.amplitude_ratio);
}

}  // namespace

int run_demo(const DemoOptions& o) {
  models::GimbalGyroParams p;
  p.CR = o.CR;
  p.AR = o.B;            // B = B^J + A^R with a massless inner gimbal
  p.AA = o.A - o.B;      // A = A^A + A^J + A^R: the outer gimbal makes up the difference
  p.Gs = o.Gs;
  if (p.AA < 0.0) {
    std::fprintf(stderr, "demo: needs A >= B (the outer gimbal adds to A), got A = %g, B = %g\n", o.A, o.B);
    return 2;
  }
  const double H = o.CR * o.rpm * 2.0 * std::numbers::pi / 60.0;
  // Horizontal outer axis (δ = π/2): "up" is the rotor axis at α = β = 0 (10.11).
  const Gyro gyro(p, models::FixedBase{dynamics::Vec3::UnitZ()});
  const auto book = oracles::gyro_pendulum_frequencies(p.A(), p.B(), H, p.Gs);
  const auto tick_ns = static_cast<std::int64_t>(std::llround(o.tick_us * 1e3));

  dynamics::Method method;
  if (o.method == "gyro-exponential") method = dynamics::Method::kGyroExponential;
  else if (o.method == "rk4") method = dynamics::Method::kRk4;
  else if (o.method == "implicit-midpoint") method = dynamics::Method::kImplicitMidpoint;
  else {
    std::fprintf(stderr, "demo: unknown method '%s' (gyro-exponential, rk4, implicit-midpoint)\n", o.method.c_str());
    return 2;
  }

  std::printf("gimbal gyro pendulum, Magnus §10.1 with a horizontal outer axis:\n");
  std::printf("  C^R = %g kg m², %g rpm (H = %.6g N m s), A = %g, B = %g kg m², Gs = %g N m\n", o.CR, o.rpm, H,
              p.A(), p.B(), p.Gs);
  std::printf("  controller tick %g us, %d plant step(s) per tick, integrator %s\n", o.tick_us, o.substeps,
              o.method.c_str());
  const Gyro::State x0 = Gyro::make_state(0.0, 0.0, 0.0, 0.0, H);
  const dynamics::Mode mode = dynamics::fastest_mode(gyro, 0.0, x0);
  const double h = 1e-9 * static_cast<double>(tick_ns) / o.substeps;
  const dynamics::StepCheck check = dynamics::check_step(method, mode, h);
  std::printf("  %s\n\n", check.message.c_str());
  if (!check.ok && !o.force) {
    std::fprintf(stderr, "demo: refused (use --substeps %d, another --method, or --force to see the damage)\n",
                 check.substeps_needed * o.substeps);
    return 3;
  }
  switch (method) {
    case dynamics::Method::kGyroExponential:
      report<dynamics::GyroscopicExponential<Gyro>>(gyro, H, book, tick_ns, o.substeps);
      break;
    case dynamics::Method::kRk4: report<dynamics::Rk4<Gyro>>(gyro, H, book, tick_ns, o.substeps); break;
    default: report<dynamics::ImplicitMidpoint<Gyro>>(gyro, H, book, tick_ns, o.substeps); break;
  }
  std::printf("\nfrequency ratio ω_N/ω_P = %.3g: the scale separation ε = ω_P/ω_N = %.2e that the precession "
              "model neglects.\n",
              book.nutation / book.precession, book.precession / book.nutation);
  return 0;
}

}  // namespace gyrostab::tools
