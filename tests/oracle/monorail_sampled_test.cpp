// The monorail's sampled-data prediction (tools/devices/monorail/monorail_sampled.hpp, docs/sampled-data.md)
// against the firmware law and the shipped scene:
//   (a) the law's matrix probed from MonorailLaw::control is the law (random unsaturated frames);
//   (b) the continuous limit: the sampled roots at T = 1 µs lie within O(T) of (14.3)'s;
//   (c) the roots measured on the shipped scene's loop — released from a small tilt, noise and gust off, on
//       the straight and in the curve at the scene's Ω3 (at zero speed: no lean) — identified from the recorded tilt φ[k] by
//       a least-squares linear-prediction fit (φ[k] of a linear sampled loop obeys a recurrence of the loop's
//       order; its characteristic roots are the loop's z): the slowest mode's decay within 1e-4 of the
//       sampled root, while the continuous root misses by more than 1.5e-3;
//   (d) the check refuses a loop stable in continuous time but not sampled (the law at 10 Hz), saying so;
//   (e) the shipped scene as it is: the steady lean and case angle under the gust and in the curve agree with
//       the sampled loop's fixed point within 1e-3. The fixed point is the large-angle one (a hold keeps the
//       nonlinear loop's equilibria): the case settles at 0.17-0.22 rad, where the linear fixed point is 0.5 %
//       and 0.8 % off. What is left is the transient (each window is the last second of a plateau 10-11 s
//       long; the slowest mode at 0.67-0.69/s leaves e^-7 ≈ 1e-3 of the step) and the seeded noise's mean
//       over one second: measured 3.5e-4, 4.8e-4 (gust), 7.4e-4, 9.2e-4 (curve).
//   (f) the run's measured release decay (the fit of φ[k] with the sensor errors as inputs) against the sampled
//       slowest root: +4.3e-4 from the shipped 0.5° release, second order in the release tilt.
// Tolerance (c): the run integrates with RK4 at the 1 ms tick (modes ≤ 9.3 rad/s: a relative error
// (hω)⁴/120 ≈ 6e-11 per step), the release tilt 0.015° keeps the large-angle terms at (φ²/6) ≈ 1e-8, the
// CSV's 17 digits and the fit's conditioning (the slowest |z| = 0.9993): measured 2e-7 on the straight, 4e-6
// in the curve (its frame-rate terms H Ω3 sinφ cosβ at second order); tolerance 1e-4.
#include "tests/support/scene_run.hpp"
#include "tests/support/scene_text.hpp"
#include "tools/devices/monorail/monorail_sampled.hpp"

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
#include "tools/devices/monorail/monorail_curve.hpp"

namespace gyrostab::monorail_sampled_test {

using gyrostab::testing::read_text;
using gyrostab::testing::replaced;

const std::string kScene = GYROSTAB_SOURCE_DIR "/sim/scenes/monorail.toml";

struct SceneRun {
  nlohmann::json figures;
  std::vector<double> tilt;  // φ at every tick from t = T
};

SceneRun run_text(const std::string& text) {
  const testing::SceneRunResult run = testing::run_scene_in_memory(kScene, text);
  EXPECT_EQ(run.rc, 0);
  SceneRun r;
  r.figures = run.report["figures"];
  std::istringstream in(run.csv);
  std::string line;
  std::getline(in, line);  // header: t_s, tilt_rad, ...
  while (std::getline(in, line)) {
    const auto a = line.find(','), b = line.find(',', a + 1);
    r.tilt.push_back(std::stod(line.substr(a + 1, b - a - 1)));
  }
  return r;
}

// The roots z of the order-n recurrence y[k+n] = Σ a_i y[k+i] (+ c, a constant: an equilibrium offset)
// fitted by least squares over y.
std::vector<std::complex<double>> identified_z(const std::vector<double>& y, int n, bool offset) {
  const int rows = static_cast<int>(y.size()) - n, cols = n + (offset ? 1 : 0);
  Eigen::MatrixXd M(rows, cols);
  Eigen::VectorXd rhs(rows);
  for (int k = 0; k < rows; ++k) {
    for (int i = 0; i < n; ++i) M(k, i) = y[static_cast<std::size_t>(k + i)];
    if (offset) M(k, n) = 1.0;
    rhs(k) = y[static_cast<std::size_t>(k + n)];
  }
  const Eigen::VectorXd a = M.colPivHouseholderQr().solve(rhs);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) C(0, i) = a(n - 1 - i);
  for (int i = 1; i < n; ++i) C(i, i - 1) = 1.0;
  const Eigen::VectorXcd ev = dynamics::eigenvalues(C);
  return {ev.data(), ev.data() + ev.size()};
}

double slowest_decay(const std::vector<std::complex<double>>& z, double T) {
  double re = -1e300;
  for (const auto& x : z)
    if (std::abs(x) > 1e-3) re = std::max(re, std::log(std::abs(x)) / T);
  return -re;
}

TEST(MonorailSampled, ProbedLawIsTheFirmwareLaw) {
  firmware::MonorailConfig c;
  c.law.k = 5500.0;
  c.law.d = 200.0;
  const analysis::DiscreteLaw law = tools::monorail_probed_law(c);
  const firmware::MonorailLaw fw(c);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int n = 0; n < 100; ++n) {
    firmware::MonorailLaw::SensorFrame in{};
    in.tilt_rad = u(rng);
    in.case_rate_rad_s = u(rng);
    in.case_angle_rad = u(rng);  // not read by the law
    firmware::MonorailLaw::ActuatorFrame out{};
    fw.control(in, out);
    const double m = law.D(0, 0) * in.tilt_rad + law.D(0, 1) * in.case_rate_rad_s;
    EXPECT_NEAR(m, out.motor_torque_Nm, 1e-12 * 300.0);
  }
}

TEST(MonorailSampled, ContinuousLimitIsTheCharacteristicQuartic) {
  models::MonorailParams car;
  car.d = 0.0;  // the damper is the law's (as in the shipped scene)
  firmware::MonorailConfig c;
  c.law.k = 5500.0;
  for (double W : {0.0, 0.03}) {
    const tools::MonorailSampled s = tools::monorail_sampled(car, c, W, {1e-6, 1e-6});
    const double continuous = -tools::max_real_root(car, c.law.k, c.law.d, W);
    // O(T): the 1 ms loop moves it by 1.5e-3 /s, so 1 µs by ~1.5e-6.
    EXPECT_NEAR(s.decay_rate_per_s, continuous, 1e-5) << W;
  }
}

TEST(MonorailSampled, ShippedSceneLoopHasTheSampledRoots) {
  std::string base = read_text(kScene);
  base = replaced(base, "phi0_deg = 0.5 ", "phi0_deg = 0.015 ");
  base = replaced(base, "M1 = 300 ", "M1 = 0 ");
  base = replaced(base, "tilt_noise_rad = 1e-4", "tilt_noise_rad = 0");
  base = replaced(base, "tilt_rate_noise_density = 1e-4", "tilt_rate_noise_density = 0");
  base = replaced(base, "case_rate_noise_density = 1e-4", "case_rate_noise_density = 0");
  base = replaced(base, "record_every = 10", "record_every = 1");
  base = replaced(base, "duration_s = 60.0", "duration_s = 16.0");
  const double T = 1e-3;
  for (const bool curve : {false, true}) {
    SCOPED_TRACE(curve ? "curve" : "straight");
    // The curve from t = 0 at the scene's Ω3 (no clothoid) at walking pace zero: without the centrifugal
    // moment the equilibrium stays at φ = β = 0 and the loop is (14.6) itself (at 5 m/s the car leans
    // 0.015 rad and the case 0.22 rad, where the large-angle terms move the roots away from (14.6)).
    const std::string text =
        curve ? replaced(replaced(replaced(base, "curve_start_s = 32.0", "curve_start_s = 0.0"), "transition_s = 3.0 ",
                                  "transition_s = 0.0 "),
                         "speed_m_s = 5.0 ", "speed_m_s = 0.0 ")
              : replaced(base, "Omega3 = 0.03 ", "Omega3 = 0.0 ");
    const SceneRun r = run_text(text);
    ASSERT_GT(r.tilt.size(), 15000u);
    // From 1 s to 15 s: the loop (4 states + 1 command in flight) is of order 5.
    const std::vector<double> y(r.tilt.begin() + 1000, r.tilt.begin() + 15000);
    const double measured = slowest_decay(identified_z(y, 5, false), T);
    const std::string key = curve ? "curve_decay_rate_per_s_predicted" : "decay_rate_per_s_predicted";
    const double sampled = r.figures[key + "_sampled"].get<double>(), continuous = r.figures[key].get<double>();
    std::printf("  %s: measured %.9f, sampled %.9f (%+.2e), continuous %.9f (%+.2e)\n", curve ? "curve" : "straight",
                measured, sampled, measured / sampled - 1.0, continuous, measured / continuous - 1.0);
    EXPECT_NEAR(measured / sampled, 1.0, 1e-4);
    EXPECT_GT(std::fabs(measured / continuous - 1.0), 1.5e-3);
  }
}

TEST(MonorailSampled, ShippedSceneSteadyFiguresAreTheSampledFixedPoint) {
  const SceneRun r = run_text(read_text(kScene));
  for (const char* key : {"gust_lean_rad", "gust_case_angle_rad", "curve_lean_rad", "curve_case_angle_rad"}) {
    SCOPED_TRACE(key);
    const std::string k(key);
    ASSERT_TRUE(r.figures[k].is_number()) << r.figures.dump();
    const double measured = r.figures[k].get<double>(), sampled = r.figures[k + "_predicted_sampled"].get<double>();
    const double linear = r.figures[k + "_predicted"].get<double>();
    std::printf("  %s: measured %.9f, sampled (large angle) %.9f (%+.2e), linear %.9f (%+.2e)\n", key, measured,
                sampled, measured / sampled - 1.0, linear, measured / linear - 1.0);
    EXPECT_LT(std::fabs(measured / sampled - 1.0), 1e-3);
  }
  // The case angles are where the large-angle terms count: the linear fixed point misses by > 4e-3.
  EXPECT_GT(std::fabs(r.figures["gust_case_angle_rad"].get<double>() /
                      r.figures["gust_case_angle_rad_predicted"].get<double>() - 1.0), 4e-3);
  EXPECT_GT(std::fabs(r.figures["curve_case_angle_rad"].get<double>() /
                      r.figures["curve_case_angle_rad_predicted"].get<double>() - 1.0), 4e-3);
}

// (f) The run's own measurement of the release: `decay_rate_per_s` is the slowest root of the recurrence fitted
// to φ[k] from 20 ms to the gust, with the frames' errors (tilt and rate noise, encoder counts) as inputs. On
// the shipped scene (released from 0.5°) it is the sampled root to +4.3e-4 (tolerance 1e-3) while the
// continuous root misses by 2.6e-3; what is left is the loop's own nonlinearity — second order in the release
// tilt: 1.0° gives +1.63e-3 (ratio 3.8 for twice the tilt, ≥ 3.5 asserted), 0.015° gives 1.5e-7.
TEST(MonorailSampled, ShippedReleaseMeasuresTheSampledSlowestRoot) {
  const auto error_at = [](const std::string& text, double* continuous) {
    const SceneRun r = run_text(text);
    const double d = r.figures["decay_rate_per_s"].get<double>();
    if (continuous != nullptr) *continuous = d / r.figures["decay_rate_per_s_predicted"].get<double>() - 1.0;
    return d / r.figures["decay_rate_per_s_predicted_sampled"].get<double>() - 1.0;
  };
  double vs_continuous = 0.0;
  const std::string shipped = read_text(kScene);
  const double e05 = error_at(shipped, &vs_continuous);
  const double e10 = error_at(replaced(shipped, "phi0_deg = 0.5 ", "phi0_deg = 1.0 "), nullptr);
  std::printf("  release decay against the sampled root: 0.5 deg %+.3e (continuous %+.3e), 1.0 deg %+.3e\n", e05,
              vs_continuous, e10);
  EXPECT_LT(std::fabs(e05), 1e-3);
  EXPECT_GT(std::fabs(vs_continuous), 1.5e-3);
  EXPECT_GT(e10 / e05, 3.5);
}

TEST(MonorailSampled, CheckRefusesALoopStableOnlyInContinuousTime) {
  // The law at 10 Hz (tick 100 ms, the plant in 8 sub-steps): (14.5) accepts k = 5500, the sampled loop
  // with one tick of latency has |z| = 1.01559 on the straight (1.01927 in the curve).
  std::string text = replaced(read_text(kScene), "tick_us = 1000 ", "tick_us = 100000 ");
  text = replaced(text, "plant_substeps = 1", "plant_substeps = 8");
  std::vector<std::string> problems;
  EXPECT_EQ(tools::check_scene_text(text, "slow", &problems), 2);
  std::string all;
  for (const std::string& p : problems) all += p + "\n";
  std::printf("%s", all.c_str());
  EXPECT_NE(all.find("[controller] k"), std::string::npos) << all;
  EXPECT_NE(all.find("stable in continuous time but unstable"), std::string::npos) << all;
  EXPECT_NE(all.find("|z| = 1.01559"), std::string::npos) << all;
  problems.clear();
  EXPECT_EQ(tools::check_scene_text(read_text(kScene), "shipped", &problems), 0);
}

}  // namespace gyrostab::monorail_sampled_test
