// The CMG pyramid driven to its momentum envelope along a principal axis (sim/scenes/cmg-cluster-envelope-x.toml,
// figures of tools/devices/cmg_cluster/cmg_cluster_run.cpp): a 180° slew about x asks for more momentum than the
// cluster holds, the generalized inverse takes it past the internal singularity at 2h cosβ, and it saturates at
// the envelope along −x. The momentum reached along x against the closed form 2h(1 + cosβ)
// (docs/models/cmg-cluster.md#momentum-envelope, Magnus §14.4 with the pyramid's geometry).
// It cannot exceed the envelope (H·e ≤ h Σ sqrt(1 − (e·g_i)²) for every δ: asserted to rounding, 1e-12); it
// approaches it as far as the steering's damping lets the gimbals go — near the external singularity the rates
// along the singular direction vanish as σ/(σ² + λ), so the gimbals stop short of the maximizing angles by
// |Δδ| ~ 1e-2 rad, and the projection, quadratic there, by ~ ½ Δδ² ≈ 1e-4 (the oracle's robust inverse at a
// constant demand: 2.6e-4, docs/models/cmg-cluster.md (d)). Tolerance 1e-4; measured −2.9e-5. The slew still
// completes (the cluster comes back from the envelope).
#include "tests/support/scene_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace gyrostab::cmg_cluster_envelope_test {

const std::string kScenes = GYROSTAB_SOURCE_DIR "/sim/scenes/";

TEST(CmgClusterEnvelopeScene, TheClusterReachesItsEnvelopeAlongX) {
  const nlohmann::json f = testing::figures_of(kScenes + "cmg-cluster-envelope-x.toml");
  ASSERT_TRUE(f["envelope_reached_rel_error"].is_number()) << f.dump();
  const double h = 5.0, beta = std::atan(std::sqrt(2.0));
  const double reached = f["peak_cmg_momentum_along_slew_axis_Nms"].get<double>();
  const double closed = f["envelope_along_slew_axis_closed_form_Nms"].get<double>();
  std::printf("  reached %.6f N m s along x, envelope 2h(1 + cosβ) = %.6f (rel %+.2e); internal singularity "
              "2h cosβ = %.4f; final error %.2e deg, settled %.2f s\n",
              reached, closed, f["envelope_reached_rel_error"].get<double>(),
              f["pyramid_internal_singularity_Nms"].get<double>(), f["final_attitude_error_deg"].get<double>(),
              f["settling_time_s"].is_number() ? f["settling_time_s"].get<double>() : -1.0);
  EXPECT_NEAR(closed, 2.0 * h * (1.0 + std::cos(beta)), 1e-4);  // the scene's skew is arctan √2 to 6 digits
  EXPECT_NEAR(closed, f["envelope_along_slew_axis_Nms"].get<double>(), 1e-12 * closed);
  EXPECT_LE(reached, closed * (1.0 + 1e-12));
  EXPECT_LT(std::fabs(f["envelope_reached_rel_error"].get<double>()), 1e-4);
  EXPECT_GT(reached, 2.0 * f["pyramid_internal_singularity_Nms"].get<double>());
  EXPECT_TRUE(f["settling_time_s"].is_number());
  EXPECT_LT(f["final_attitude_error_deg"].get<double>(), 1e-3);
}

}  // namespace gyrostab::cmg_cluster_envelope_test
