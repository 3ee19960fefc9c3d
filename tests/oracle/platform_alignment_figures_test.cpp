// The platform alignment's east-gyro figure (tools/devices/platform_alignment/platform_alignment_run.cpp)
// measured from the run: the Earth's rate on the platform's east axis P1 from the platform's attitude q_GP when
// the azimuth phase begins, against (16.52) −ω^E cosφ sinψ at the heading error then. The platform is level
// only to the tilts θ_E, θ_N the levelling left (biases, gusts); with R_GP = Rz(−ψ) Rx(θ_E) Ry(θ_N) the exact
// rate is Ω_N(−sinψ cosθ_N + cosψ sinθ_E sinθ_N) − Ω_U cosθ_E sinθ_N (held to 1e-12 relative: the same
// kinematics in two roundings), and it differs from (16.52) by Ω_U |θ_N| + Ω_N (|θ_E θ_N| + θ_N²/2) at most
// (the tolerance against the book).
#include "tests/support/scene_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace gyrostab::platform_alignment_figures_test {

const std::string kScenes = GYROSTAB_SOURCE_DIR "/sim/scenes/";

TEST(PlatformAlignmentFigures, TheEastGyroRateIsMeasuredFromThePlatformAndHeldTo16_52) {
  for (const char* name : {"platform-alignment-aircraft.toml", "platform-alignment-high-latitude.toml"}) {
    const nlohmann::json f = testing::figures_of(kScenes + name);
    ASSERT_TRUE(f["east_gyro_rate_at_azimuth_start_rad_s"].is_number()) << name << ": " << f.dump();
    const double measured = f["east_gyro_rate_at_azimuth_start_rad_s"].get<double>();
    const double book = f["east_gyro_rate_at_azimuth_start_rad_s_predicted"].get<double>();
    const double phi = f["latitude_rad"].get<double>(), we = 7.292115e-5;
    const double tE = f["tilt_east_at_azimuth_start_rad"].get<double>();
    const double tN = f["tilt_north_at_azimuth_start_rad"].get<double>();
    const double psi = f["heading_error_at_azimuth_start_rad"].get<double>();
    const double WN = we * std::cos(phi), WU = we * std::sin(phi);
    const double exact = WN * (-std::sin(psi) * std::cos(tN) + std::cos(psi) * std::sin(tE) * std::sin(tN)) -
                         WU * std::cos(tE) * std::sin(tN);
    const double bound = WU * std::fabs(tN) + WN * (std::fabs(tE * tN) + 0.5 * tN * tN);
    std::printf("  %s: measured %.9e rad/s, (16.52) %.9e (rel %+.2e, bound %.2e), with the tilts %.9e\n", name,
                measured, book, measured / book - 1.0, bound / std::fabs(book), exact);
    EXPECT_NEAR(measured, exact, 1e-12 * std::fabs(exact)) << name;
    EXPECT_NEAR(measured, book, bound) << name;
    EXPECT_NEAR(f["east_gyro_rate_at_azimuth_start_rel_error"].get<double>(), measured / book - 1.0, 1e-15);
  }
}

}  // namespace gyrostab::platform_alignment_figures_test
