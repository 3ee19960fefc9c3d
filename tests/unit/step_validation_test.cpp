#include "sim/dynamics/step_validation.hpp"

#include <gtest/gtest.h>

#include "sim/models/gimbal_gyro.hpp"

namespace gyrostab {
namespace step_validation_test {

using Gyro = models::GimbalGyro<>;

// The example: C = 1 kg m², 6000 rpm, gimbal inertia 0.5 kg m² ⇒ ω_N = CΩ/A = 1256.6 rad/s (200 Hz).
Gyro stabilizer() {
  models::GimbalGyroParams p;
  p.AR = 0.5;
  p.CR = 1.0;
  return Gyro(p);
}
constexpr double kH = 628.3185307179586;

TEST(StepValidation, FastestModeOfTheGimbalGyroIsTheNutationHOverSqrtAB) {
  const Gyro g = stabilizer();
  const dynamics::Mode m = dynamics::fastest_mode(g, 0.0, Gyro::make_state(0, 0, 0, 0, kH));
  EXPECT_EQ(m.name, "nutation");
  // Finite-difference Jacobian (relative step 1e-7): eigenvalue good to ~1e-6 relative.
  EXPECT_NEAR(std::abs(m.lambda.imag()), kH / 0.5, 1e-6 * kH / 0.5);
  EXPECT_NEAR(m.frequency_hz(), 200.0, 2e-4);
}

TEST(StepValidation, RefusesRk4AtOneKilohertzWithModeFrequencyAndLargestStep) {
  const Gyro g = stabilizer();
  const dynamics::Mode m = dynamics::fastest_mode(g, 0.0, Gyro::make_state(0, 0, 0, 0, kH));
  const dynamics::StepCheck c = dynamics::check_step(dynamics::Method::kRk4, m, 1e-3);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.message.find("refused"), std::string::npos) << c.message;
  EXPECT_NE(c.message.find("nutation"), std::string::npos) << c.message;
  EXPECT_NE(c.message.find("200 Hz"), std::string::npos) << c.message;
  EXPECT_NE(c.message.find("largest usable step"), std::string::npos) << c.message;
  // RK4's per-step damping on iω is (hω)⁶/144 to leading order; 1e-3 over 10 s needs hω ≲ 0.1.
  EXPECT_GT(c.substeps_needed, 10);
  EXPECT_LT(c.substeps_needed, 16);
  // The suggested step passes, one sub-step fewer does not.
  EXPECT_TRUE(dynamics::check_step(dynamics::Method::kRk4, m, c.largest_usable_step).ok);
  EXPECT_FALSE(dynamics::check_step(dynamics::Method::kRk4, m, 1e-3 / (c.substeps_needed - 1)).ok);
}

TEST(StepValidation, RefusesRk4BeyondItsStabilityLimit) {
  // RK4 on iω is unstable beyond hω = 2√2 (2.25 ms for 200 Hz, docs/models/integrators.md).
  const dynamics::Mode m{"nutation", {0.0, 1256.6}};
  const auto c = dynamics::check_step(dynamics::Method::kRk4, m, 2.3e-3);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.message.find("unstable"), std::string::npos) << c.message;
}

TEST(StepValidation, AcceptsTheExponentialAndImplicitMidpointStepsAtOneKilohertz) {
  const dynamics::Mode m{"nutation", {0.0, 1256.6}};
  const auto e = dynamics::check_step(dynamics::Method::kGyroExponential, m, 1e-3);
  EXPECT_TRUE(e.ok) << e.message;
  EXPECT_EQ(e.frequency_error, 0.0);
  const auto i = dynamics::check_step(dynamics::Method::kImplicitMidpoint, m, 1e-3);
  EXPECT_TRUE(i.ok) << i.message;
  // Frequency compression 2 atan(hω/2)/(hω) - 1 = -10.7 % at hω = 1.257: reported, not hidden.
  EXPECT_NEAR(i.frequency_error, 2.0 * std::atan(0.6283) / 1.2566 - 1.0, 1e-3);
}

TEST(StepValidation, RefusesSplittingStepsNearTheKickResonance) {
  const dynamics::Mode m{"nutation", {0.0, 1256.6}};
  // h ω = 6.28 (one full nutation per step) is the k = 1 resonance.
  const auto c = dynamics::check_step(dynamics::Method::kStrang, m, 5e-3);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.message.find("resonance"), std::string::npos) << c.message;
  EXPECT_LE(c.largest_usable_step * 1256.6, 0.8 * 2.0 * std::numbers::pi);
}

}  // namespace step_validation_test
}  // namespace gyrostab
