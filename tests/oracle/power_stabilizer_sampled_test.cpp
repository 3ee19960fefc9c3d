// The power stabilizer's sampled-data prediction (tools/devices/power_stabilizer/power_stabilizer_sampled.hpp,
// docs/sampled-data.md) against the firmware law and the shipped scenes:
//   (a) the law's matrix probed from PowerStabilizerLoops::compute is the law: on random unsaturated frames
//       D y equals compute()'s command (both modes);
//   (b) the continuous limit: the eigenvalues of A + B D C include the root of (14.23)/(14.29) the
//       `_predicted` figures use, and the sampled root at T = 1 µs lies within O(T) of it;
//   (c) the shipped scenes as they are (seeded rate noise, encoder counts, on the moving base too): the measured
//       nutation (the fit of α[k] with the sensor errors as inputs, linear_prediction_fit.hpp) agrees with the
//       sampled roots within 1e-3, and the continuous roots miss by more than 2.5e-3 on the base at rest — the
//       1 ms hold and the 1 ms latency are what the prediction adds;
//   (c') the same root identified here, independently of the run's meter, from the recorded α[k] alone with
//       noise off: within 1e-5;
//   (d) the window follows the inner-axis step and the prediction the platform load's deflection: with the
//       platform step first, at a 55 rad/s nutation, within 1e-3; a platform step alone (β moving during the
//       window) moves the decay by an amount second order in the step;
//   (e) the check refuses a loop that is stable in continuous time but not sampled, and says so.
#include "tests/support/scene_run.hpp"
#include "tests/support/scene_text.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_sampled.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/QR>

#include "sim/dynamics/eigenvalues.hpp"
#include "tools/commands.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_checks.hpp"

namespace gyrostab::power_stabilizer_sampled_test {

using firmware::PowerStabilizerConfig;
using firmware::PowerStabilizerOutput;

using gyrostab::testing::read_text;
using gyrostab::testing::replaced;

const std::string kScenes = GYROSTAB_SOURCE_DIR "/sim/scenes/";

nlohmann::json figures_of(const std::string& path, const std::string& text) {
  return testing::figures_of(path, text, kScenes);
}


TEST(PowerStabilizerSampled, ProbedLawIsTheFirmwareLaw) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (const PowerStabilizerOutput mode : {PowerStabilizerOutput::kTorque, PowerStabilizerOutput::kBackEmfVoltage}) {
    PowerStabilizerConfig c;
    c.output = mode;
    c.d_c = 0.3;
    c.A = 2.0;
    c.B = 1.5;
    c.H = 200.0;
    c.k1 = 200.0;
    c.k2 = 150.0;
    c.d1 = 5.0;
    c.d2 = 4.0;
    const analysis::DiscreteLaw law = tools::power_stabilizer_probed_law(c);
    const firmware::PowerStabilizerLoops loops(c);
    ASSERT_TRUE(loops.armed());
    for (int n = 0; n < 100; ++n) {
      msg::power_stabilizer::SensorFrame in{};
      Eigen::Vector4d y(u(rng), u(rng), u(rng), u(rng));
      in.alpha_rad = y[0];
      in.beta_rad = y[1];
      in.alpha_rate_rad_s = y[2];
      in.beta_rate_rad_s = y[3];
      msg::power_stabilizer::ActuatorFrame out{};
      loops.compute(in, out);
      const Eigen::VectorXd cmd = law.D * y;
      if (mode == PowerStabilizerOutput::kTorque) {
        ASSERT_EQ(cmd.size(), 2);
        EXPECT_NEAR(cmd[0], out.motor1_torque_Nm, 1e-13 * 100.0);
        EXPECT_NEAR(cmd[1], out.motor2_torque_Nm, 1e-13 * 100.0);
      } else {
        ASSERT_EQ(cmd.size(), 1);
        EXPECT_NEAR(cmd[0], out.motor1_voltage_V, 1e-13 * 10.0);
      }
    }
    EXPECT_EQ(law.F.rows(), 0);  // memoryless: compute() keeps no state
  }
}

TEST(PowerStabilizerSampled, ContinuousLimitIsTheCharacteristicEquation) {
  for (const PowerStabilizerOutput mode : {PowerStabilizerOutput::kTorque, PowerStabilizerOutput::kBackEmfVoltage}) {
    PowerStabilizerConfig c;
    c.output = mode;
    c.bearing_d1 = 0.05;
    c.bearing_d2 = 0.05;
    const analysis::LinearPlant p = tools::power_stabilizer_linear_plant(c);
    const analysis::DiscreteLaw law = tools::power_stabilizer_probed_law(c);
    const Eigen::VectorXcd ev = dynamics::eigenvalues(Eigen::MatrixXd(p.A + p.B * law.D * p.C));
    const std::complex<double> want = tools::predicted_nutation(c);
    double best = 1e300;
    for (Eigen::Index i = 0; i < ev.size(); ++i) best = std::min(best, std::abs(ev(i) - want));
    EXPECT_LT(best, 1e-9 * std::abs(want)) << "mode " << static_cast<int>(mode);
    // T = 1 µs, one tick of latency: the root moves by ≈ 1.5 T |λ|² ~ 5e-3 /s (ω ≈ 56 rad/s) — O(T).
    const tools::PowerStabilizerSampled s = tools::power_stabilizer_sampled(c, {1e-6, 1e-6});
    EXPECT_LT(std::abs(s.nutation - want), 2e-2) << s.nutation << " vs " << want;
    EXPECT_TRUE(s.roots.stable());
  }
}

// (c) The shipped scenes as they are. Their first step is on the inner axis: it moves α, which enters no
// equation, so the loop stays at its linearisation point β = 0 and is the sampled prediction's loop exactly.
// The run's meter fits α[k] at the law's rate with the frames' sensor errors (rate noise, encoder counts) as
// inputs: that recurrence is exact, so at rest the measured root is the prediction's to the fit's round-off
// (measured 2.7e-7 decay, 1.6e-8 frequency). On the moving base the base's rates reach the gimbals and add a
// forced response that two spare orders of the fit absorb: 1.2e-4 decay, 3.6e-5 frequency. Tolerance 1e-3 (the
// issue's), and at rest the continuous roots must miss by more than 2.5e-3 (measured 9.5e-3, 2.9e-3).
TEST(PowerStabilizerSampled, ShippedScenesMeasureTheSampledRoots) {
  for (const char* name : {"power-stabilizer", "power-stabilizer-ship-motion", "power-stabilizer-recorded-motion"}) {
    SCOPED_TRACE(name);
    const std::string path = kScenes + name + ".toml";
    const nlohmann::json f = figures_of(path, read_text(path));
    const testing::ModeFigures n = testing::ModeFigures::of(f);
    n.print(name);
    EXPECT_LT(std::fabs(n.decay_vs_sampled()), 1e-3);
    EXPECT_LT(std::fabs(n.freq_vs_sampled()), 1e-3);
    if (std::string(name) == "power-stabilizer") {
      EXPECT_LT(std::fabs(n.decay_vs_sampled()), 1e-5);
      EXPECT_LT(std::fabs(n.freq_vs_sampled()), 1e-5);
      EXPECT_GT(std::fabs(n.decay_vs_continuous()), 2.5e-3);
      EXPECT_GT(std::fabs(n.freq_vs_continuous()), 2.5e-3);
    }
    EXPECT_LT(f["sampled_loop_max_abs_z"].get<double>(), 1.0);
    // The sampled steady state is the continuous one (a zero-order hold keeps equilibria).
    EXPECT_NEAR(f["steady_alpha_rad_predicted_sampled"].get<double>(), f["steady_alpha_rad_predicted"].get<double>(), 1e-12);
    EXPECT_NEAR(f["steady_beta_rad_predicted_sampled"].get<double>(), f["steady_beta_rad_predicted"].get<double>(), 1e-12);
  }
}

// (c') The same loop's nutation root identified here from the recorded trajectory instead of the run's meter: α[k] of the
// sampled linear loop (4 states + 2 commands in flight; α itself enters no equation, so the 0.05 rad the
// inner-axis step moves it leaves the loop linear) obeys a recurrence of order 6 plus a constant (the new
// equilibrium); its least-squares fit over 1.5 s after the step has the loop's z. The encoder is set to its
// finest (2^30 counts: a torque jitter k·q = 1e-6 N m against the 10 N m step) so that only rounding
// remains. Tolerance 1e-5 on both figures (the gyro-exponential flow carries the gyroscopic pair exactly,
// and the nutation's β amplitude 4e-4 rad moves H cos β by 1e-7).
TEST(PowerStabilizerSampled, RootsIdentifiedFromTheShippedLoopAreTheSampledRoots) {
  const std::string path = kScenes + "power-stabilizer.toml";
  std::string text = read_text(path);
  text = replaced(text, "M1_Nm = 20.0 ", "M1_Nm = 0.0 ");
  text = replaced(text, "rate_noise_density = 1e-4", "rate_noise_density = 0.0");
  text = replaced(text, "encoder_counts_per_rev = 262144", "encoder_counts_per_rev = 1073741824");
  text = replaced(text, "record_every = 5", "record_every = 1");
  const testing::SceneRunResult run = testing::run_scene_in_memory(path, text);
  ASSERT_EQ(run.rc, 0);
  const nlohmann::json& report = run.report;
  std::vector<double> alpha;
  std::istringstream in(run.csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const auto a = line.find(','), b = line.find(',', a + 1);
    alpha.push_back(std::stod(line.substr(a + 1, b - a - 1)));
  }
  ASSERT_GT(alpha.size(), 4600u);
  // Rows at t = (k + 1) T: the inner-axis step acts from tick 1000; fit from 1.05 s to 2.5 s.
  const int n = 6, first = 1050, last = 2500, rows = last - first - n;
  Eigen::MatrixXd M(rows, n + 1);
  Eigen::VectorXd rhs(rows);
  for (int k = 0; k < rows; ++k) {
    for (int i = 0; i < n; ++i) M(k, i) = alpha[static_cast<std::size_t>(first + k + i)];
    M(k, n) = 1.0;
    rhs(k) = alpha[static_cast<std::size_t>(first + k + n)];
  }
  const Eigen::VectorXd a = M.colPivHouseholderQr().solve(rhs);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) C(0, i) = a(n - 1 - i);
  for (int i = 1; i < n; ++i) C(i, i - 1) = 1.0;
  const Eigen::VectorXcd z = dynamics::eigenvalues(C);
  std::vector<std::complex<double>> s;
  for (Eigen::Index i = 0; i < z.size(); ++i)
    if (std::abs(z(i)) > 1e-6) s.push_back(std::log(z(i)) / 1e-3);
  const nlohmann::json& f = report["figures"];
  const std::complex<double> sampled(-f["nutation_decay_rate_per_s_predicted_sampled"].get<double>(),
                                     f["nutation_frequency_rad_s_predicted_sampled"].get<double>());
  const std::complex<double> continuous(-f["nutation_decay_rate_per_s_predicted"].get<double>(),
                                        f["nutation_frequency_rad_s_predicted"].get<double>());
  const std::complex<double> measured = analysis::nearest_root(s, sampled);
  std::printf("  identified %.9f%+.9fi, sampled %.9f%+.9fi, continuous %.9f%+.9fi\n", measured.real(),
              measured.imag(), sampled.real(), sampled.imag(), continuous.real(), continuous.imag());
  EXPECT_NEAR(measured.real() / sampled.real(), 1.0, 1e-5);
  EXPECT_NEAR(measured.imag() / sampled.imag(), 1.0, 1e-5);
  EXPECT_GT(std::fabs(measured.real() / continuous.real() - 1.0), 5e-3);
  EXPECT_GT(std::fabs(measured.imag() / continuous.imag() - 1.0), 2e-3);
}

// (d) The measurement's window and operating point (power_stabilizer_checks.hpp, nutation_window). With the
// platform step first (the shipped order swapped) the nutation is still measured after the inner-axis step,
// and predicted at the platform load's steady deflection β = M1/k1 = 0.1 rad (H cos β, I(β)). At a 55 rad/s
// nutation (rotor at 9120 rpm: the precession k1/H = 2.1/s has settled β by then, β' = 3e-3 rad/s) the
// measured root is the sampled one to 2.4e-4 (decay) and 9.5e-5 (frequency); tolerance 1e-3. A scene with
// the platform step only is measured after it while β moves from 0 towards 0.1 rad: the decay leaves the
// prediction at β0 by +1.9e-3 at 20 N m and +2.8e-4 at 10 N m — second order in the step (ratio ≥ 3.5
// asserted), the loop's nonlinearity, not the meter's.
TEST(PowerStabilizerSampled, MeasurementWindowAndOperatingPointFollowTheSteps) {
  const std::string path = kScenes + "power-stabilizer.toml";
  const std::string shipped = read_text(path);
  std::string swapped = replaced(shipped, "M1_time_s = 3.0", "M1_time_s = 1.0");
  swapped = replaced(swapped, "M2_time_s = 1.0", "M2_time_s = 3.0");
  const nlohmann::json f55 = figures_of(path, replaced(swapped, "rpm = 19098.6 ", "rpm = 9120.0 "));
  const testing::ModeFigures n55 = testing::ModeFigures::of(f55);
  n55.print("platform step first, 55 rad/s");
  EXPECT_DOUBLE_EQ(f55["nutation_window_from_s"].get<double>(), 3.02);
  EXPECT_NEAR(f55["nutation_operating_point_beta_rad"].get<double>(), 0.1, 1e-12);
  EXPECT_LT(std::fabs(n55.decay_vs_sampled()), 1e-3);
  EXPECT_LT(std::fabs(n55.freq_vs_sampled()), 1e-3);
  const std::string only_m1 = replaced(shipped, "M2_Nm = -10.0", "M2_Nm = 0.0");
  const auto decay_error = [&](const std::string& t) {
    const nlohmann::json f = figures_of(path, t);
    EXPECT_DOUBLE_EQ(f["nutation_operating_point_beta_rad"].get<double>(), 0.0);
    return testing::ModeFigures::of(f).decay_vs_sampled();
  };
  const double e20 = decay_error(only_m1), e10 = decay_error(replaced(only_m1, "M1_Nm = 20.0 ", "M1_Nm = 10.0 "));
  std::printf("  platform step only, decay against the prediction at beta0: 20 N m %+.3e, 10 N m %+.3e (ratio %.2f)\n",
              e20, e10, e20 / e10);
  EXPECT_GT(e20, 1e-3);
  EXPECT_LT(e20, 3e-3);
  EXPECT_GT(e20 / e10, 3.5);
}

// (e) The shipped scene with the rotor 10× faster (nutation 1155 rad/s at the 1 kHz law): (14.25) accepts
// the gains (gain margin 29), the sampled loop with one tick of latency does not (|z| = 1.00041: the rate
// damping lags the nutation by ~100°); without the latency it is stable again.
TEST(PowerStabilizerSampled, CheckRefusesALoopStableOnlyInContinuousTime) {
  const std::string path = kScenes + "power-stabilizer.toml";
  const std::string fast = replaced(read_text(path), "rpm = 19098.6 ", "rpm = 190986.0 ");
  std::vector<std::string> problems;
  EXPECT_EQ(tools::check_scene_text(fast, "fast", &problems), 2);
  std::string all;
  for (const std::string& p : problems) all += p + "\n";
  std::printf("%s", all.c_str());
  EXPECT_NE(all.find("[controller] k1"), std::string::npos) << all;
  EXPECT_NE(all.find("stable in continuous time but unstable"), std::string::npos) << all;
  EXPECT_NE(all.find("|z| = 1.0004"), std::string::npos) << all;
  problems.clear();
  EXPECT_EQ(tools::check_scene_text(replaced(fast, "latency_ticks = 1", "latency_ticks = 0"), "fast-no-latency", &problems), 0)
      << (problems.empty() ? "" : problems.front());
}

}  // namespace gyrostab::power_stabilizer_sampled_test
