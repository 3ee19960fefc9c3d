// The generalized singularity-robust inverse of the CMG cluster (firmware/control/cmg_steering.hpp,
// A# = Aᵀ(AAᵀ + λE)⁻¹ with the dither ε_i = ε0 sin(ωt + φ_i); docs/models/cmg-cluster.md#singularities):
//   (a) the law is the formula: its rates equal −(1/h) Tᵀ(TTᵀ + λE)⁻¹u solved by Eigen, at random and at
//       singular configurations; at the singular configuration with u along the singular direction the plain
//       robust inverse gives no rates and the generalized one does;
//   (b) E keeps TTᵀ + λE positive definite: its smallest eigenvalue ≥ λ(1 − 2ε0) over the dither's period at
//       the singular configuration, the bound reached by E at ε_i = −ε0; the check refuses ε0 ≥ 1/2 and a
//       dither the control loop cannot sample;
//   (c) sim/scenes/cmg-cluster-singularity-generalized.toml (rate noise off) with the three laws: the
//       pseudo-inverse stalls on the internal singularity 2h cosβ, the plain robust inverse stays stuck on it,
//       the generalized inverse passes it and completes the slew.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Dense>

#include "tests/support/scene_run.hpp"
#include "tests/support/scene_text.hpp"
#include "firmware/app/cmg_cluster_controller.hpp"
#include "firmware/control/cmg_steering.hpp"
#include "sim/models/cmg_geometry.hpp"
#include "tools/commands.hpp"
#include "tools/devices/cmg_cluster/cmg_cluster_scene.hpp"

namespace gyrostab {
namespace cmg_cluster_generalized_test {

using firmware::SteeringLaw;
constexpr double kPi = std::numbers::pi;

firmware::CmgArray pyramid_array(double h) { return tools::cmg_array_of(models::pyramid_geometry(), h); }

Eigen::Matrix3d t_t_transpose(const firmware::CmgArray& a, const double* d) {
  const firmware::CmgAxes ax = firmware::cmg_axes(a, d);
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (int i = 0; i < a.count; ++i) {
    const Eigen::Vector3d t(ax.t[i][0], ax.t[i][1], ax.t[i][2]);
    M += t * t.transpose();
  }
  return M;
}

Eigen::Matrix3d dither_matrix(double e1, double e2, double e3) {
  Eigen::Matrix3d E;
  E << 1.0, e3, e2, e3, 1.0, e1, e2, e1, 1.0;
  return E;
}

// The pyramid's internal singularity along x: H = (2h cosβ, 0, 0), every t_i ⟂ x.
constexpr double kSingular[4] = {-kPi / 2, 0.0, kPi / 2, 0.0};

// (a) The firmware's rates against the formula solved independently (Eigen's LDLᵀ), with ε_i from sin.
TEST(CmgGeneralizedInverse, RatesAreTheFormula) {
  const double h = 5.0;
  const firmware::CmgArray a = pyramid_array(h);
  firmware::SteeringParams p;
  p.law = SteeringLaw::kGeneralizedSingularityRobust;
  p.max_rate = 1e9;  // the formula, not the limiter
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ang(-kPi, kPi), tu(-1.0, 1.0), tt(0.0, 100.0);
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    double d[4];
    for (double& x : d) x = ang(rng);
    if (n % 4 == 0) {
      for (int i = 0; i < 4; ++i) d[i] = kSingular[i] + 1e-4 * ang(rng);  // close to the singular surface
    }
    const double u[3] = {tu(rng), tu(rng), tu(rng)}, t = tt(rng);
    const firmware::SteeringOutput o = firmware::steer_cmg(a, p, d, u, t);
    const Eigen::Matrix3d M = t_t_transpose(a, d);
    const double lambda = p.lambda0 * std::exp(-p.mu * M.determinant());
    double e[3];
    for (int i = 0; i < 3; ++i) e[i] = p.dither_amplitude * std::sin(p.dither_frequency * t + firmware::kDitherPhase[i]);
    const Eigen::Vector3d v = (M + lambda * dither_matrix(e[0], e[1], e[2])).ldlt().solve(-Eigen::Vector3d(u[0], u[1], u[2]) / h);
    const firmware::CmgAxes ax = firmware::cmg_axes(a, d);
    double scale = 0.0;
    for (int i = 0; i < 4; ++i) scale = std::max(scale, std::fabs(Eigen::Vector3d(ax.t[i][0], ax.t[i][1], ax.t[i][2]).dot(v)));
    for (int i = 0; i < 4; ++i) {
      const double ref = Eigen::Vector3d(ax.t[i][0], ax.t[i][1], ax.t[i][2]).dot(v);
      worst = std::max(worst, std::fabs(o.rate[i] - ref) / scale);
    }
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(o.eps[i], e[i], 1e-17);  // deterministic sin: ≤ 1 ulp of libm's
  }
  std::printf("generalized inverse against Eigen: worst relative rate error %.2e\n", worst);
  // Two 3 × 3 solves of the same matrix, condition ≤ 1/(λ0 e^{−μm}(1 − 2ε0)) ~ 1e2 near the surface: round-off
  // 1e-16 × 1e2 × a few. Tolerance 1e-12 relative to the largest rate.
  EXPECT_LT(worst, 1e-12);
}

// (a) At the singular configuration with u along x: Aᵀ(AAᵀ + λI)⁻¹u vanishes, A#u does not.
TEST(CmgGeneralizedInverse, MovesWhereThePlainRobustInverseCannot) {
  const firmware::CmgArray a = pyramid_array(5.0);
  const double u[3] = {-1.0, 0.0, 0.0};
  firmware::SteeringParams p;
  p.law = SteeringLaw::kSingularityRobust;
  const firmware::SteeringOutput sr = firmware::steer_cmg(a, p, kSingular, u, 0.3);
  p.law = SteeringLaw::kGeneralizedSingularityRobust;
  double worst_sr = 0.0, least_gsr = 1e9;
  for (int k = 0; k < 400; ++k) {  // one dither period, 10 ms apart
    const double t = 0.01 * k;
    const firmware::SteeringOutput g = firmware::steer_cmg(a, p, kSingular, u, t);
    double n = 0.0;
    for (double r : g.rate) n = std::max(n, std::fabs(r));
    least_gsr = std::min(least_gsr, n);
  }
  for (double r : sr.rate) worst_sr = std::max(worst_sr, std::fabs(r));
  std::printf("at the singularity, u along x: robust max|nu| %.2e, generalized min over a period of max|nu| %.3e rad/s\n",
              worst_sr, least_gsr);
  // The plain inverse: t_i·x ~ 1e-17 (the pyramid's axes to round-off), so ν ~ 1e-17/(λ h) ~ 1e-15.
  EXPECT_LT(worst_sr, 1e-12);
  // The generalized inverse: v ≈ u/(λh) minus the λε share off x, so ν_i ~ ε/(σ h) ~ 1e-3 rad/s; at every phase
  // one |ε_i| ≥ ε0/√2, so it never vanishes. Lower bound 1e-4 rad/s.
  EXPECT_GT(least_gsr, 1e-4);
}

// (b) Positive definiteness: the smallest eigenvalue of TTᵀ + λE over a dither period at the singular
// configuration (where TTᵀ contributes nothing along x), for Wie's ε0 = 0.01 and for ε0 = 0.49.
TEST(CmgGeneralizedInverse, DampedMatrixStaysPositiveDefinite) {
  const firmware::CmgArray a = pyramid_array(1.0);
  const Eigen::Matrix3d M = t_t_transpose(a, kSingular);
  for (const double e0 : {0.01, 0.49}) {
    firmware::SteeringParams p;
    p.law = SteeringLaw::kGeneralizedSingularityRobust;
    p.dither_amplitude = e0;
    const double lambda = p.lambda0 * std::exp(-p.mu * M.determinant());
    double least = 1e9;
    for (int k = 0; k <= 4000; ++k) {
      double e[3];
      firmware::dither_epsilons(p, 1e-3 * k, e);
      const Eigen::Matrix3d D = M + lambda * dither_matrix(e[0], e[1], e[2]);
      least = std::min(least, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(D).eigenvalues()(0));
    }
    std::printf("eps0 %.2f: least eigenvalue of TT' + lambda E %.4e, bound lambda(1 - 2 eps0) = %.4e\n", e0, least,
                lambda * (1.0 - 2.0 * e0));
    EXPECT_GE(least, lambda * (1.0 - 2.0 * e0) * (1.0 - 1e-9));
    EXPECT_TRUE(firmware::check_cmg_steering(a, p).ok);
  }
  // The bound is tight: all ε_i = −ε0 gives E the eigenvalue 1 − 2ε0 (eigenvector (1, 1, 1)), 0 at ε0 = 1/2.
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(dither_matrix(-0.5, -0.5, -0.5)).eigenvalues();
  EXPECT_NEAR(ev(0), 0.0, 1e-15);
  firmware::SteeringParams p;
  p.law = SteeringLaw::kGeneralizedSingularityRobust;
  for (const double bad : {0.5, 0.7, -0.01, std::nan("")}) {
    p.dither_amplitude = bad;
    const firmware::ConfigCheck c = firmware::check_cmg_steering(a, p);
    EXPECT_FALSE(c.ok) << bad;
    EXPECT_NE(std::string(c.reason).find("dither_amplitude"), std::string::npos);
  }
  // The controller refuses a dither its loop cannot sample: ω T_c = 600 rad/s × 1 ms > 0.5.
  firmware::CmgClusterConfig c;
  c.array = a;
  c.steering.law = SteeringLaw::kGeneralizedSingularityRobust;
  c.steering.dither_frequency = 400.0;
  EXPECT_TRUE(firmware::CmgClusterController::check(c).ok) << firmware::CmgClusterController::check(c).reason;
  c.steering.dither_frequency = 600.0;
  EXPECT_FALSE(firmware::CmgClusterController::check(c).ok);
}

// (c) The shipped scene with each law.
using gyrostab::testing::read_text;
using gyrostab::testing::replaced;

// The text without the line that starts with `key =` (the dither keys apply to the generalized inverse only).
std::string without_key(std::string t, const std::string& key) {
  const auto at = t.find("\n" + key + " =");
  EXPECT_NE(at, std::string::npos) << key;
  if (at == std::string::npos) return t;
  const auto end = t.find('\n', at + 1);
  t.erase(at, end - at);
  return t;
}

nlohmann::json figures_of(const std::string& path, const std::string& text) {
  const testing::SceneRunResult r = testing::run_scene_in_memory(path, text);
  EXPECT_EQ(r.rc, 0);
  return r.report["figures"];
}

void print(const char* what, const nlohmann::json& f) {
  std::printf("%-15s min det %.2e, near-singular %.3f s, final error %.3e deg, settled %s, peak |H| %.3f N m s "
              "(2h cos beta %.3f, envelope %.3f)\n",
              what, f["min_singularity_measure"].get<double>(), f["near_singular_time_s"].get<double>(),
              f["final_attitude_error_deg"].get<double>(), f["settling_time_s"].dump().c_str(),
              f["peak_cmg_momentum_Nms"].get<double>(), f["pyramid_internal_singularity_Nms"].get<double>(),
              f["envelope_along_slew_axis_Nms"].get<double>());
}

TEST(CmgGeneralizedInverse, NoiselessSceneOnlyTheGeneralizedInversePasses) {
  const std::string path = GYROSTAB_SOURCE_DIR "/sim/scenes/cmg-cluster-singularity-generalized.toml";
  const std::string text = read_text(path);
  ASSERT_NE(text.find("rate_noise_density = 0.0"), std::string::npos);
  const std::string law = "steering = \"generalized_singularity_robust\"";
  const nlohmann::json gsr = figures_of(path, text);
  const std::string plain = without_key(without_key(text, "dither_amplitude"), "dither_frequency");
  const nlohmann::json sr = figures_of(path, replaced(plain, law, "steering = \"singularity_robust\""));
  const std::string pinv_text =
      without_key(without_key(replaced(plain, law, "steering = \"pseudo_inverse\""), "lambda0"), "mu");
  const nlohmann::json pinv = figures_of(path, pinv_text);
  print("pseudo-inverse", pinv);
  print("robust", sr);
  print("generalized", gsr);
  const double internal = gsr["pyramid_internal_singularity_Nms"].get<double>();  // 2h cosβ = 5.7735 N m s
  const double envelope = gsr["envelope_along_slew_axis_Nms"].get<double>();      // 2h(1 + cosβ) = 15.77 N m s
  // Stalled: the momentum never exceeds 2h cosβ (by more than 1e-6 of it: the servo's settling), the
  // measure falls below 1e-9 (from 1.185), more than 5 s near-singular (measure < 0.01).
  for (const nlohmann::json* f : {&pinv, &sr}) {
    EXPECT_LT((*f)["peak_cmg_momentum_Nms"].get<double>(), internal * (1.0 + 1e-6));
    EXPECT_LT((*f)["min_singularity_measure"].get<double>(), 1e-9);
    EXPECT_GT((*f)["near_singular_time_s"].get<double>(), 5.0);
  }
  // The pseudo-inverse backs out once the loop's demand reverses and reaches the attitude late (its rates
  // never reach the surface exactly); the plain robust inverse reaches it exactly (measure ~ 1e-16), where no
  // demand along x moves a gimbal: it spins on past the target and is still stuck at the end.
  EXPECT_GT(sr["near_singular_time_s"].get<double>(), 25.0);
  EXPECT_GT(sr["final_attitude_error_deg"].get<double>(), 10.0);
  EXPECT_TRUE(sr["settling_time_s"].is_null());
  // Passed: beyond 2h cosβ by more than 50 %, inside the envelope, near-singular under 2 s, settled inside
  // the 0.1° band, the final error below 1e-3° (the loop's decay after settling), sooner than the pseudo-inverse.
  EXPECT_GT(gsr["peak_cmg_momentum_Nms"].get<double>(), 1.5 * internal);
  EXPECT_LT(gsr["peak_cmg_momentum_Nms"].get<double>(), envelope);
  EXPECT_LT(gsr["near_singular_time_s"].get<double>(), 2.0);
  ASSERT_FALSE(gsr["settling_time_s"].is_null());
  EXPECT_LT(gsr["settling_time_s"].get<double>(), pinv["settling_time_s"].get<double>() - 1.0);
  EXPECT_LT(gsr["final_attitude_error_deg"].get<double>(), 1e-3);
  EXPECT_EQ(gsr["steering"], "generalized_singularity_robust");
}

}  // namespace cmg_cluster_generalized_test
}  // namespace gyrostab
