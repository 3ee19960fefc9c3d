// The gyro vertical's erection loop linearised and sampled (tools/devices/gyro_vertical/gyro_vertical_sampled.hpp,
// docs/sampled-data.md) against the shipped scenes:
//   (a) `gyro-vertical-aircraft-turn`: the erection root measured in the first, straight segment — Φ of a
//       planar recurrence (α, β)[k+1] = Φ (α, β)[k] + b + c k fitted to 1 s means of the tilt (the nutation
//       averaged out) from 47.6 s, when the start's nutation has decayed by e^-5, to 197.6 s, with the sensor
//       errors' response through the sampled loop taken off — is the sampled loop's to 1e-4 (measured −2.3e-6
//       decay, −6.4e-6 frequency) and nearer to it than to the continuous loop's, which the hold and the latency
//       move by 3.0e-5: the measurement resolves the computer;
//   (b) the compensation is a small correction (the sensor errors' response, 3.4e-6 rad, against a transient
//       of 1e-3 to 1e-2 rad), and it is the right one: the same scene without sensor noise measures the same
//       root to 1e-6 (measured 1e-9);
//   (c) `gyro-vertical-dead-zone` (Coulomb friction, a non-linear loop): no erection root, and the reason.
// The book's δ = f/H and ω^P = c/H are the model's to 3.3e-4 and 1.8e-2: the frame's vertical rate (the Earth's
// and the transport rate) adds to ω^P in (12.45), and the bearing damping d shifts δ by d c/(f H).
#include "tests/support/scene_run.hpp"
#include "tests/support/scene_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace gyrostab::gyro_vertical_sampled_test {

const std::string kScenes = GYROSTAB_SOURCE_DIR "/sim/scenes/";

TEST(GyroVerticalSampled, ShippedTurnSceneMeasuresTheSampledErectionRoot) {
  const std::string path = kScenes + "gyro-vertical-aircraft-turn.toml";
  const nlohmann::json f = testing::figures_of(path);
  const testing::ModeFigures e = testing::ModeFigures::of(f, "erection");
  std::printf("  decay %.9g: sampled %+.2e, continuous %+.2e, book delta %+.2e\n", e.decay, e.decay / e.decay_sampled - 1.0,
              e.decay / e.decay_continuous - 1.0, e.decay_continuous / f["delta_s"].get<double>() - 1.0);
  std::printf("  frequency %.9g: sampled %+.2e, continuous %+.2e, book omega_P %+.2e\n", e.freq, e.freq / e.freq_sampled - 1.0,
              e.freq / e.freq_continuous - 1.0, e.freq_continuous / f["omega_P_rad_s"].get<double>() - 1.0);
  EXPECT_LT(std::fabs(e.decay / e.decay_sampled - 1.0), 1e-4);
  EXPECT_LT(std::fabs(e.freq / e.freq_sampled - 1.0), 1e-4);
  EXPECT_LT(std::fabs(e.decay / e.decay_sampled - 1.0), std::fabs(e.decay / e.decay_continuous - 1.0));
  EXPECT_LT(std::fabs(e.freq / e.freq_sampled - 1.0), std::fabs(e.freq / e.freq_continuous - 1.0));
  EXPECT_LT(f["sampled_loop_max_abs_z"].get<double>(), 1.0);
  // (b) a small correction ...
  const double noise = f["erection_noise_response_max_rad"].get<double>();
  std::printf("  sensor errors' response %.3e rad\n", noise);
  EXPECT_GT(noise, 0.0);
  EXPECT_LT(noise, 1e-4);
  // ... and the right one: without the sensors' noise the same root.
  const std::string quiet = testing::without_table(testing::read_text(path), "sensors");
  const nlohmann::json q = testing::figures_of(path, quiet, kScenes);
  const testing::ModeFigures n = testing::ModeFigures::of(q, "erection");
  EXPECT_EQ(q["erection_noise_response_max_rad"].get<double>(), 0.0);
  std::printf("  noiseless: decay %+.2e, frequency %+.2e from the shipped run\n", e.decay / n.decay - 1.0,
              e.freq / n.freq - 1.0);
  EXPECT_LT(std::fabs(e.decay / n.decay - 1.0), 1e-6);
  EXPECT_LT(std::fabs(e.freq / n.freq - 1.0), 1e-6);
}

TEST(GyroVerticalSampled, DeadZoneSceneHasNoErectionRoot) {
  const nlohmann::json f = testing::figures_of(kScenes + "gyro-vertical-dead-zone.toml");
  EXPECT_FALSE(f.contains("erection_decay_rate_per_s_predicted_sampled"));
  EXPECT_NE(f["erection_root"].get<std::string>().find("not the linear one"), std::string::npos);
}

}  // namespace gyrostab::gyro_vertical_sampled_test
