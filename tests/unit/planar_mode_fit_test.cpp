// sim/analysis/planar_mode_fit.hpp: one mode of a planar signal, with its equilibrium drifting linearly.
#include "sim/analysis/planar_mode_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

namespace gyrostab::analysis {
namespace {

// x(t) = x_eq + v t + Re(w e^{λt}), y(t) likewise with another complex amplitude (an elliptic mode).
TEST(PlanarModeFit, RecoversAnEllipticModeOnADriftingEquilibrium) {
  const std::complex<double> lambda(-0.02, 0.0049);
  const double dt = 1.0;
  PlanarModeFit fit(0.0, 150.0, dt);
  for (int k = 0; k <= 150; ++k) {
    const double t = k * dt;
    const std::complex<double> e = std::exp(lambda * t);
    fit.add(t, 3e-3 + 1e-6 * t + (std::complex<double>(0.03, 0.01) * e).real(),
            -2e-3 - 4e-7 * t + (std::complex<double>(-0.005, 0.02) * e).real());
  }
  ASSERT_TRUE(fit.valid());
  const std::complex<double> got = fit.root();
  EXPECT_NEAR(got.real() / lambda.real(), 1.0, 1e-10);
  EXPECT_NEAR(got.imag() / lambda.imag(), 1.0, 1e-9);
}

TEST(PlanarModeFit, TooFewSamplesIsNotValid) {
  PlanarModeFit fit(0.0, 5.0, 1.0);
  for (int k = 0; k <= 5; ++k) fit.add(k, 1.0 * k, 0.0);
  EXPECT_FALSE(fit.valid());
  EXPECT_TRUE(std::isnan(fit.root().real()));
}

}  // namespace
}  // namespace gyrostab::analysis
