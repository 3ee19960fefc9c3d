// Suspension-motion generators: prescribed base rotation and vibration (kinematics against finite differences
// of the attitude and displacement), the regular wave moment (Magnus 14.9), the wave transfers, and the
// irregular sea's fast grid evaluation against its direct sum.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/motion/base_vibration.hpp"
#include "sim/motion/irregular_sea.hpp"
#include "sim/motion/prescribed_base_rotation.hpp"
#include "sim/motion/regular_wave_moment.hpp"

namespace gyrostab {
namespace base_motion_generators_test {

using dynamics::Quat;
using dynamics::Vec3;
constexpr double kPi = std::numbers::pi;

motion::PrescribedBaseRotation<4> ship_motion() {
  motion::PrescribedBaseRotation<4> m;
  m.roll.count = 3;
  m.roll.harmonics[0] = {0.2, 0.6, 0.1};
  m.roll.harmonics[1] = {0.05, 1.3, -0.7};
  m.roll.harmonics[2] = {0.01, 7.0, 2.0};
  m.pitch.offset = 0.03;
  m.pitch.count = 2;
  m.pitch.harmonics[0] = {0.08, 0.9, 0.4};
  m.pitch.harmonics[1] = {0.02, 2.1, 1.1};
  m.yaw.rate = 0.02;  // turning ship
  m.yaw.count = 1;
  m.yaw.harmonics[0] = {0.03, 0.45, -0.2};
  return m;
}

TEST(PrescribedBaseRotation, RollOnlyReproducesHarmonicBaseRotation) {
  motion::PrescribedBaseRotation<1> m;
  m.roll.count = 1;
  m.roll.harmonics[0] = {0.1, 0.5, 0.0};
  const models::HarmonicBaseRotation ref{Vec3::UnitX(), 0.1, 0.5, Vec3::UnitZ()};
  for (double t = 0.0; t < 20.0; t += 0.37) {
    const auto a = m(t), b = ref(t);
    EXPECT_LT((a.w_B - b.w_B).norm(), 1e-15);
    EXPECT_LT((a.dw_B - b.dw_B).norm(), 1e-15);
    EXPECT_LT((a.up_B - b.up_B).norm(), 1e-15);
  }
}

TEST(PrescribedBaseRotation, RatesAndUpMatchTheAttitudeByFiniteDifferences) {
  // ω_B = 2 vec(q* q̇) with q̇ by a centred difference (h = 1e-5: truncation ~h²|q'''| ≈ 1e-10, rounding ~ε/h ≈
  // 1e-11), ω̇_B by a centred difference of ω_B; up_B = q* e₃ q exactly. Tolerances 1e-8 and 1e-7.
  const auto m = ship_motion();
  const double h = 1e-5;
  for (double t = 0.0; t < 30.0; t += 0.731) {
    const Quat q = m.attitude(t), qp = m.attitude(t + h), qm = m.attitude(t - h);
    Quat qdot;
    qdot.coeffs() = (qp.coeffs() - qm.coeffs()) / (2 * h);
    const Vec3 w_fd = 2.0 * (q.conjugate() * qdot).vec();
    const Vec3 dw_fd = (m(t + h).w_B - m(t - h).w_B) / (2 * h);
    const models::BaseSample b = m(t);
    EXPECT_LT((b.w_B - w_fd).norm(), 1e-8) << t;
    EXPECT_LT((b.dw_B - dw_fd).norm(), 1e-7) << t;
    EXPECT_LT((b.up_B - q.conjugate() * Vec3::UnitZ()).norm(), 1e-14) << t;
  }
}

TEST(PrescribedBaseRotation, LeverArmAddsTheAccelerationOfTheSuspensionPoint) {
  // Suspension 12 m above and 3 m aft of the centre of rotation. Specific force/g = R^T(e₃ + p̈_W/g) with
  // p_W = R r_B differentiated twice by the fourth-order centred stencil (h = 1e-3: truncation h⁴|p⁽⁶⁾|/90 ≈
  // 2e-10 m/s² for the 7 rad/s roll harmonic, rounding ~64ε|p|/(12h²) ≈ 1e-8 m/s²): tolerance 1e-8 in g.
  auto m = ship_motion();
  m.lever_arm_B = {-3.0, 0.0, 12.0};
  const double h = 1e-3;
  for (double t = 0.5; t < 30.0; t += 1.37) {
    const auto p = [&](double s) -> Vec3 { return m.attitude(s) * m.lever_arm_B; };
    const Vec3 a_W =
        (-p(t + 2 * h) + 16 * p(t + h) - 30 * p(t) + 16 * p(t - h) - p(t - 2 * h)) / (12 * h * h);
    const Vec3 want = m.attitude(t).conjugate() * (Vec3::UnitZ() + a_W / m.g);
    EXPECT_LT((m(t).up_B - want).norm(), 1e-8) << t;
  }
}

TEST(BaseVibration, AccelerationIsTheSecondDerivativeOfTheDisplacementAndAddsToUp) {
  motion::VibratingBase<models::FixedBase, 2> base;
  base.vibration.count = 2;
  base.vibration.harmonics[0] = {Vec3(0, 0, 1e-3), 2 * kPi * 50, 0.3};   // vertical, 1 mm at 50 Hz
  base.vibration.harmonics[1] = {Vec3(2e-4, 0, 0), 2 * kPi * 120, 1.0};  // horizontal, 0.2 mm at 120 Hz
  const double h = 1e-6;
  for (double t = 0.0; t < 0.05; t += 0.00173) {
    const auto& v = base.vibration;
    const Vec3 a_fd = (v.displacement_B(t + h) - 2 * v.displacement_B(t) + v.displacement_B(t - h)) / (h * h);
    const Vec3 a = v.acceleration_B(t);
    EXPECT_LT((a - a_fd).norm(), 1e-4 * a.norm() + 1e-3) << t;  // FD: ~4ε·1e-3/h² ≈ 1e-3 m/s²
    EXPECT_LT((base(t).up_B - (Vec3::UnitZ() + a / base.g)).norm(), 1e-15);
    EXPECT_EQ(base(t).w_B, Vec3::Zero());
  }
  // Peak vertical specific force of the 50 Hz component: s ν²/g = 1e-3 (100π)²/9.80665 = 10.06 g.
  EXPECT_NEAR(1e-3 * std::pow(2 * kPi * 50, 2) / base.g, 10.064, 1e-3);
}

TEST(RegularWaveMoment, IsE0CosOmegaTAndFromWaveUsesTheWaveSlope) {
  const motion::RegularWaveMoment e{2.5e5, 0.6, 0.0};
  EXPECT_EQ(e(0.0), 2.5e5);
  EXPECT_NEAR(e(2 * kPi / 0.6 / 4), 0.0, 1e-9);
  const double h = 1e-4;
  for (double t = 0.0; t < 20.0; t += 0.77) EXPECT_NEAR(e.rate(t), (e(t + h) - e(t - h)) / (2 * h), 1e-3);
  // c = 1.1772e7 N m/rad (the reference ship of docs/models/ship-roll-damper.md), κ = 0.8, a = 1 m, ω =
  // 0.6 rad/s: E0 = c κ ω² a / g.
  const auto w = motion::RegularWaveMoment::from_wave(1.1772e7, 0.8, 1.0, 0.6);
  EXPECT_NEAR(w.E0, 1.1772e7 * 0.8 * 0.36 / 9.80665, 1e-6);
}

TEST(WaveTransfer, RollMomentSeaIsTheElevationSeaScaledByCKappaKAndShiftedByMinusNinetyDegrees) {
  const motion::WaveSpectrum s({motion::WaveSpectrumParams::Kind::kJonswap, 3.0, 9.0, 3.3, 0.07, 0.09});
  motion::IrregularSeaParams p;
  p.components = 40;
  random::SeededRng r1(5), r2(5);
  const motion::IrregularSea<64> eta(s, p, r1);
  const motion::IrregularSea<64> moment(s, p, r2, motion::WaveRollMomentTransfer{1.1772e7, 0.8});
  for (int i = 0; i < 40; ++i) {
    const double k = eta.frequency(i) * eta.frequency(i) / motion::kStandardGravity;
    EXPECT_NEAR(moment.amplitude(i), 1.1772e7 * 0.8 * k * eta.amplitude(i), 1e-9 * moment.amplitude(i));
    EXPECT_NEAR(moment.phase(i), eta.phase(i) - kPi / 2, 1e-14);
  }
  motion::TabulatedRao<4> rao;
  rao.rows[0] = {0.5, 1.0, 0.0};
  rao.rows[1] = {1.0, 3.0, -1.0};
  rao.count = 2;
  EXPECT_NEAR(std::abs(rao(0.75)), 2.0, 1e-15);
  EXPECT_NEAR(std::arg(rao(0.75)), -0.5, 1e-15);
  EXPECT_NEAR(std::abs(rao(5.0)), 3.0, 1e-15);
}

TEST(IrregularSea, FastEvaluationMatchesTheDirectSumAndIsAPureFunctionOfTime) {
  const motion::WaveSpectrum s(
      {motion::WaveSpectrumParams::Kind::kPiersonMoskowitz, 4.0, 10.0, 1.0, 0.07, 0.09});
  motion::IrregularSeaParams p;
  p.components = 64;
  p.grid_period = 1e-3;
  random::SeededRng rng(77);
  const motion::IrregularSea<64> sea(s, p, rng);
  double sum_b = 0.0, sum_wb = 0.0;
  for (int i = 0; i < 64; ++i) sum_b += sea.amplitude(i), sum_wb += sea.frequency(i) * sea.amplitude(i);
  // (1) Sequential grid values vs the direct sum over 20 anchor blocks: phasor rotation error ≤ ~1024·4ε per
  //     component, so |Δy| ≤ 1e-12 Σb (and Σωb for the rate).
  double worst = 0.0;
  for (std::int64_t n = 0; n < 20 * 1024; ++n) {
    const auto g = sea.sample(n);
    const auto d = sea.at(static_cast<double>(n) * 1e-3);
    worst = std::max(worst, std::abs(g.value - d.value) / sum_b);
    ASSERT_NEAR(g.value, d.value, 1e-12 * sum_b) << n;
    ASSERT_NEAR(g.rate, d.rate, 1e-12 * sum_wb) << n;
  }
  std::printf("worst |grid - direct| / sum b over 20480 steps: %.2e\n", worst);
  // (2) Random access gives bit-identical values to the sequential path (same anchor, same rotations).
  motion::IrregularSea<64> other(sea);
  for (const std::int64_t n : {std::int64_t{5000}, std::int64_t{17}, std::int64_t{1023}, std::int64_t{1024},
                               std::int64_t{-3}, std::int64_t{19999}}) {
    const double v = other.sample(n).value;
    std::int64_t n0 = n - (((n % 1024) + 1024) % 1024);
    motion::IrregularSea<64> seq(sea);
    for (std::int64_t k = n0; k <= n; ++k) seq.sample(k);
    EXPECT_EQ(v, seq.sample(n).value) << n;
  }
  // (3) Far from t = 0 (t = 1e6 s): still the direct sum, to the rounding of ω t (≈ 1e-10 rad).
  const std::int64_t far = 1000000000;
  EXPECT_NEAR(sea.sample(far).value, sea.at(1e6).value, 1e-9 * sum_b);
  // (4) operator(): grid times (as an RK4 stage computes them) use the grid sample bit for bit; between grid
  //     points the cubic Hermite interpolant, within its bound dt⁴/384 Σbω⁴ plus the grid's 1e-12 Σb.
  const double t_stage = 12.0 + 0.0005 + 0.0005;
  EXPECT_EQ(sea(t_stage), sea.sample(12001).value);
  double sum_bw4 = 0.0;
  for (int i = 0; i < 64; ++i) sum_bw4 += sea.amplitude(i) * std::pow(sea.frequency(i), 4);
  const double hermite_bound = std::pow(1e-3, 4) / 384 * sum_bw4 + 1e-12 * sum_b;
  double worst_h = 0.0;
  for (double t = 12.0; t < 14.0; t += 0.000317) {
    const double err = std::abs(sea(t) - sea.at(t).value);
    worst_h = std::max(worst_h, err);
    ASSERT_LE(err, hermite_bound) << t;
  }
  std::printf("worst |Hermite - direct| %.2e, bound %.2e (sum b %.3f)\n", worst_h, hermite_bound, sum_b);
  // (5) The rate is the derivative of the value.
  const double h = 1e-5;
  for (double t = 0.0; t < 100.0; t += 3.3)
    EXPECT_NEAR(sea.at(t).rate, (sea.at(t + h).value - sea.at(t - h).value) / (2 * h), 1e-7 * sum_wb);
}

TEST(MotionParameters, ImpossibleSeaParametersAreRefusedWithAMessage) {
  using motion::WaveSpectrum;
  using Kind = motion::WaveSpectrumParams::Kind;
  EXPECT_EQ(WaveSpectrum::check({}), nullptr);
  EXPECT_NE(WaveSpectrum::check({Kind::kPiersonMoskowitz, 0.0, 8.0, 1.0, 0.07, 0.09}), nullptr);
  EXPECT_NE(WaveSpectrum::check({Kind::kJonswap, 2.0, -1.0, 3.3, 0.07, 0.09}), nullptr);
  EXPECT_NE(WaveSpectrum::check({Kind::kJonswap, 2.0, 8.0, 0.5, 0.07, 0.09}), nullptr);
  EXPECT_NE(WaveSpectrum::check({Kind::kJonswap, 2.0, 8.0, 3.3, 0.2, 0.09}), nullptr);
  using Sea = motion::IrregularSea<32>;
  EXPECT_EQ(Sea::check({32, 0, 0, 1.0, 1e-3}), nullptr);
  EXPECT_NE(Sea::check({}), nullptr);  // the default 64 components exceed a capacity of 32
  EXPECT_NE(Sea::check({33, 0, 0, 1.0, 1e-3}), nullptr);
  EXPECT_NE(Sea::check({16, 2.0, 1.0, 1.0, 1e-3}), nullptr);
  EXPECT_NE(Sea::check({16, 0, 0, 1.5, 1e-3}), nullptr);
  EXPECT_NE(Sea::check({16, 0, 0, 1.0, 0.0}), nullptr);
  // DNV's default γ for a steep and a swell-like sea state.
  EXPECT_EQ(WaveSpectrum::dnv_gamma(4.0, 7.0), 5.0);
  EXPECT_EQ(WaveSpectrum::dnv_gamma(1.0, 6.0), 1.0);
  EXPECT_NEAR(WaveSpectrum::dnv_gamma(4.0, 8.4), std::exp(5.75 - 1.15 * 4.2), 1e-12);
}

}  // namespace base_motion_generators_test
}  // namespace gyrostab
