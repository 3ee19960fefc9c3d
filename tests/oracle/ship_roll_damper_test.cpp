// Oracle tests of the gyroscopic ship roll damper (sim/models/ship_roll_damper.hpp) against Magnus §14.2
// (docs/models/ship-roll-damper.md): steady roll and precession amplitudes (14.11), the invariant points
// (14.17)-(14.18), the minimax precession brake, the locked ship (14.15); and of the model's own
// additions: energy conservation with the large-angle terms and the end stops, the stop's restitution.
//
// Forcing: E is a zero-order-hold input, set each step to E0 cos ω(t + h/2). The fundamental of that
// staircase is exactly E0 sinc(ωh/2) cos ωt (the mid-step sample removes the h/2 delay), so the expected
// amplitudes are (14.11) × sinc(ωh/2); its images near 2π/h ± ω reach the sampled response at ≲ 1e-7.
// Amplitudes are fitted over whole periods with h = T/M, where the discrete Fourier sums are exact.
// Integrator: RK4 at h ≤ 0.1/|λ|max of (14.8)'s state matrix. The steady response of a mode forced at ω
// errs by about (h|λ|)⁴/120 × its resonant amplification: ≲ 3e-6 at h|λ|max = 0.1 (measured below by
// halving h twice, which also shows the fourth order).
#include "sim/models/ship_roll_damper.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sim/dynamics/rk4.hpp"
#include "tests/support/alloc_counter.hpp"
#include "sim/dynamics/eigenvalues.hpp"

namespace gyrostab {
namespace ship_roll_damper_test {

using models::ShipRollDamper;
using models::ShipRollDamperParams;
using Rk4 = dynamics::Rk4<ShipRollDamper>;
constexpr double kPi = std::numbers::pi;

// ---- the book's small-angle theory, (14.8)-(14.18)

// (14.11): roll and precession amplitude per unit wave moment E0.
double book_phi_amplitude(const ShipRollDamperParams& p, double w) {
  const double w2 = w * w, a = p.c - p.A * w2, b = p.q - p.B * w2;
  const double re = a * b - w2 * (p.H * p.H + p.d1 * p.d2), im = w * (p.d1 * b + p.d2 * a);
  return std::sqrt((b * b + p.d2 * p.d2 * w2) / (re * re + im * im));
}
double book_beta_amplitude(const ShipRollDamperParams& p, double w) {
  const double w2 = w * w, a = p.c - p.A * w2, b = p.q - p.B * w2;
  const double re = a * b - w2 * (p.H * p.H + p.d1 * p.d2), im = w * (p.d1 * b + p.d2 * a);
  return std::sqrt(p.H * p.H * w2 / (re * re + im * im));
}
// (14.15) with roll damping: the ship with the case locked.
double book_locked_amplitude(const ShipRollDamperParams& p, double w) {
  return 1.0 / std::hypot(p.c - p.A * w * w, p.d1 * w);
}
// (14.18): ω_II, ω_III (the third invariant point is ω_I = 0).
void invariant_frequencies(const ShipRollDamperParams& p, double& w2, double& w3) {
  const double S = p.H * p.H + 2.0 * p.c * p.B + 2.0 * p.q * p.A;
  const double r = std::sqrt(1.0 - 16.0 * p.c * p.q * p.A * p.B / (S * S));
  w2 = std::sqrt(S / (4.0 * p.A * p.B) * (1.0 - r));
  w3 = std::sqrt(S / (4.0 * p.A * p.B) * (1.0 + r));
}
// Peak of (14.11) over ω in [lo, hi]: a grid, then golden-section refinement on the best cell.
void book_peak(const ShipRollDamperParams& p, double lo, double hi, double& w_peak, double& peak) {
  const int n = 20000;
  int best = 0;
  for (int i = 1; i <= n; ++i) {
    if (book_phi_amplitude(p, lo + (hi - lo) * i / n) > book_phi_amplitude(p, lo + (hi - lo) * best / n))
      best = i;
  }
  double a = lo + (hi - lo) * std::max(best - 1, 0) / n, b = lo + (hi - lo) * std::min(best + 1, n) / n;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 200; ++it) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    if (book_phi_amplitude(p, x1) > book_phi_amplitude(p, x2)) {
      b = x2;
    } else {
      a = x1;
    }
  }
  w_peak = 0.5 * (a + b);
  peak = book_phi_amplitude(p, w_peak);
}

// Slowest decay rate and largest |λ| of (14.8)'s state matrix (of the bare ship, Aλ² + d1λ + c, if locked):
// they set the settling time and the step.
void linear_rates(const ShipRollDamperParams& p, double& slowest_decay, double& fastest) {
  if (p.locked) {
    slowest_decay = p.d1 / (2.0 * p.A);  // underdamped for the ships used here
    fastest = std::sqrt(p.c / p.A);
    return;
  }
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  M(0, 2) = 1.0;
  M(1, 3) = 1.0;
  M(2, 0) = -p.c / p.A;
  M(2, 2) = -p.d1 / p.A;
  M(2, 3) = -p.H / p.A;
  M(3, 1) = -p.q / p.B;
  M(3, 2) = p.H / p.B;
  M(3, 3) = -p.d2 / p.B;
  const dynamics::EigenvaluesOf<4> ev = dynamics::eigenvalues<4>(M);
  slowest_decay = -ev.real().maxCoeff();
  fastest = ev.cwiseAbs().maxCoeff();
}

struct Steady {
  double phi_A{0}, beta_A{0};  // amplitudes of the fundamental [rad]
  double forcing{0};           // fundamental of the held input, E0 sinc(ωh/2) [N m]
  double h{0};
  long steps{0};
};

// Steady forced response at ω from rest: settle until the slowest transient has decayed by 1e-7, then fit
// the fundamental over two whole periods.
Steady steady_response(const ShipRollDamperParams& p, double E0, double w, double step_scale = 1.0) {
  double sigma = 0, fastest = 0;
  linear_rates(p, sigma, fastest);
  const double T = 2.0 * kPi / w;
  const double h_max = std::min(0.1 / fastest, T / 64.0) * step_scale;
  const long per_period = static_cast<long>(std::ceil(T / h_max));
  const double h = T / static_cast<double>(per_period);
  const long settle = static_cast<long>(std::ceil(std::log(1e7) / sigma / T)) * per_period;
  ShipRollDamper model(p);
  Rk4 integ(model);
  ShipRollDamper::State x = ShipRollDamper::State::Zero();
  long k = 0;
  auto step = [&] {
    const double t = static_cast<double>(k) * h;
    model.inputs.E = E0 * std::cos(w * (t + 0.5 * h));
    integ.step(t, h, x);
    ++k;
  };
  for (long i = 0; i < settle; ++i) step();
  double pc = 0, ps = 0, bc = 0, bs = 0;
  const long n = 2 * per_period;
  for (long i = 0; i < n; ++i) {
    step();
    const double t = static_cast<double>(k) * h, cw = std::cos(w * t), sw = std::sin(w * t);
    pc += x[0] * cw;
    ps += x[0] * sw;
    bc += x[1] * cw;
    bs += x[1] * sw;
  }
  Steady s;
  s.phi_A = 2.0 / static_cast<double>(n) * std::hypot(pc, ps);
  s.beta_A = 2.0 / static_cast<double>(n) * std::hypot(bc, bs);
  s.forcing = E0 * std::sin(0.5 * w * h) / (0.5 * w * h);
  s.h = h;
  s.steps = k;
  return s;
}

// The constructed reference ship (docs/models/ship-roll-damper.md): 2000 t, GM 0.6 m, radius of gyration 4 m.
ShipRollDamperParams digest_ship(double d1, double d2) {
  ShipRollDamperParams p;  // A, c, B, q, H default to the reference ship's values
  p.d1 = d1;
  p.d2 = d2;
  return p;
}

// E0 = 10 N m gives φ ≤ 1e-5 rad, β ≤ 1e-4 rad: the large-angle terms shift the amplitudes by ~φ²/8, β²/4
// ≲ 1e-8, far below the tolerances.
constexpr double kE0 = 10.0;

TEST(ShipRollDamperOracle, DigestParametersAreWhatTheModelDefaultsTo) {
  const ShipRollDamperParams p;
  EXPECT_EQ(p.A, 3.2e7);
  EXPECT_EQ(p.c, 1.1772e7);
  EXPECT_EQ(p.B, 1.5e4);
  EXPECT_EQ(p.q, 1350.0);
  EXPECT_EQ(p.H, 1.018e6);
  EXPECT_EQ(p.invalid_reason(), nullptr);
  ShipRollDamperParams bad = p;
  bad.q = -1.0;  // top-heavy case: (14.8) needs a statically stable case
  EXPECT_NE(bad.invalid_reason(), nullptr);
}

// (14.11) at several ω, with roll damping d1 (ζ ≈ 0.026) so that every term of N is exercised.
TEST(ShipRollDamperOracle, SteadyRollAndPrecessionAmplitudesMatch14_11) {
  for (const double d2 : {1.5e4, 4.53e4}) {
    const ShipRollDamperParams p = digest_ship(1e6, d2);
    for (const double w : {0.1, 0.3, 0.6065, 1.0, 1.6, 2.5}) {
      const Steady s = steady_response(p, kE0, w);
      const double phi_book = s.forcing * book_phi_amplitude(p, w);
      const double beta_book = s.forcing * book_beta_amplitude(p, w);
      // The issue asks ≤ 1e-3 relative; the error budget (RK4 ≤ 3e-6 (next test), settling 1e-7,
      // images ≲ 1e-7, large-angle ≲ 1e-8) allows 1e-5.
      EXPECT_NEAR(s.phi_A / phi_book, 1.0, 1e-5) << "d2 " << d2 << " w " << w;
      EXPECT_NEAR(s.beta_A / beta_book, 1.0, 1e-5) << "d2 " << d2 << " w " << w;
      std::printf("d2 %g w %g phi %.3e beta %.3e steps %ld\n", d2, w, s.phi_A / phi_book - 1,
                  s.beta_A / beta_book - 1, s.steps);
    }
  }
}

TEST(ShipRollDamperOracle, Rk4ErrorOfTheSteadyAmplitudeIsFourthOrderAndBelow3e6) {
  // The worst case of the test above: the nutation resonance with the weaker brake.
  const ShipRollDamperParams p = digest_ship(1e6, 1.5e4);
  const double w = 1.6;
  const Steady a = steady_response(p, kE0, w, 1.0), b = steady_response(p, kE0, w, 0.5),
               c = steady_response(p, kE0, w, 0.25);
  ASSERT_LT(b.h, 0.6 * a.h);
  ASSERT_LT(c.h, 0.6 * b.h);
  // Amplitudes per unit held forcing (the sinc factor differs with h). The settling residual is the same
  // physical transient at every h and cancels in the differences.
  const double ab = std::abs((a.phi_A / a.forcing) / (b.phi_A / b.forcing) - 1.0);
  const double bc = std::abs((b.phi_A / b.forcing) / (c.phi_A / c.forcing) - 1.0);
  std::printf("RK4 step halving: %.3e %.3e ratio %.2f\n", ab, bc, ab / bc);
  // RK4 is fourth order: halving h divides the error by 16 (allow 12-20 for the next order's share).
  EXPECT_GT(ab / bc, 12.0);
  EXPECT_LT(ab / bc, 20.0);
  // So the error at the test's step is ≈ 16/15 of `ab`; the budget above allows 3e-6.
  EXPECT_LT(ab * 16.0 / 15.0, 3e-6);
}

// (14.15) with d1: the locked case gives the bare ship, resonant at ω^s = sqrt(c/A) (14.16).
TEST(ShipRollDamperOracle, LockedCaseGivesTheUnstabilizedShip14_15) {
  ShipRollDamperParams p = digest_ship(1e6, 4.53e4);
  p.locked = true;
  for (const double w : {0.3, std::sqrt(p.c / p.A), 1.0}) {
    const Steady s = steady_response(p, kE0, w);
    EXPECT_NEAR(s.phi_A / (s.forcing * book_locked_amplitude(p, w)), 1.0, 1e-5) << "w " << w;  // as above
    EXPECT_EQ(s.beta_A, 0.0);  // the case does not move
  }
  // The gyro matters: at ω^s the free case reduces roll by a large factor (not a tolerance: a sanity bound).
  ShipRollDamperParams free = p;
  free.locked = false;
  const double ws = std::sqrt(p.c / p.A);
  const double reduction = steady_response(free, kE0, ws).phi_A / steady_response(p, kE0, ws).phi_A;
  EXPECT_LT(reduction, 0.2);
  std::printf("roll at w_s with the gyro / locked = %.4f\n", reduction);
}

// (14.17)-(14.18), d1 = 0: at ω_II and ω_III every d2 gives φ_A = E0/|c − Aω²|.
TEST(ShipRollDamperOracle, ResponseCurvesForAllD2PassThroughTheInvariantPoints14_18) {
  const ShipRollDamperParams p0 = digest_ship(0.0, 0.0);
  double w2 = 0, w3 = 0;
  invariant_frequencies(p0, w2, w3);
  // The reference values (5-6 significant digits) confirm the oracle itself.
  EXPECT_NEAR(w2, 0.14780, 5e-6);
  EXPECT_NEAR(w3, 1.23107, 5e-6);
  EXPECT_NEAR(1.0 / std::abs(p0.c - p0.A * w2 * w2), 9.031e-8, 5e-12);
  EXPECT_NEAR(1.0 / std::abs(p0.c - p0.A * w3 * w3), 2.723e-8, 5e-12);
  for (const double wi : {w2, w3}) {
    // (14.17): the invariant-point condition H²ω²[H²ω² − 2(c − Aω²)(q − Bω²)] = 0 holds at ω_II, ω_III.
    const double cond = p0.H * p0.H * wi * wi - 2.0 * (p0.c - p0.A * wi * wi) * (p0.q - p0.B * wi * wi);
    EXPECT_LT(std::abs(cond), 1e-9 * p0.H * p0.H * wi * wi);
    const double ordinate = 1.0 / std::abs(p0.c - p0.A * wi * wi);
    for (const double d2 : {4.5e3, 4.53e4, 4.5e5}) {
      const Steady s = steady_response(digest_ship(0.0, d2), kE0, wi);
      EXPECT_NEAR(s.phi_A / (s.forcing * ordinate), 1.0, 1e-5) << "w " << wi << " d2 " << d2;  // as above
      std::printf("invariant point w %.5f d2 %.3g: phi_A/ordinate - 1 = %+.2e (%ld steps)\n", wi, d2,
                  s.phi_A / (s.forcing * ordinate) - 1.0, s.steps);
    }
  }
  // Not vacuous: between the invariant points the same three brakes give clearly different curves.
  const double a = steady_response(digest_ship(0.0, 4.5e3), kE0, 0.5).phi_A;
  const double b = steady_response(digest_ship(0.0, 4.53e4), kE0, 0.5).phi_A;
  const double c = steady_response(digest_ship(0.0, 4.5e5), kE0, 0.5).phi_A;
  EXPECT_GT(std::max({a, b, c}) / std::min({a, b, c}), 1.5);
  std::printf("at w = 0.5 the three curves spread by x%.2f\n", std::max({a, b, c}) / std::min({a, b, c}));
}

// The book's recipe for the optimum (§3.2): put ω_II (the highest invariant point) into d(φ_A²)/d(ω²) = 0;
// with φ_A² = (n + D ω²)/(m + D ω² k), D = d2², n = (q − Bω²)², m = [(c − Aω²)(q − Bω²) − H²ω²]²,
// k = (c − Aω²)² (d1 = 0), this is a quadratic in D.
double minimax_d2(const ShipRollDamperParams& p, double wi) {
  const double w = wi * wi, a = p.c - p.A * w, b = p.q - p.B * w;
  const double n = b * b, dn = -2.0 * p.B * b;
  const double g = a * b - w * p.H * p.H, dg = -p.A * b - p.B * a - p.H * p.H;
  const double m = g * g, dm = 2.0 * g * dg;
  const double k = a * a, dk = -2.0 * p.A * a;
  // (dn + D)(m + D w k) − (n + D w)(dm + D(k + w dk)) = 0
  const double c2 = -w * w * dk, c1 = dn * w * k + m - n * (k + w * dk) - w * dm, c0 = dn * m - n * dm;
  const double disc = std::sqrt(c1 * c1 - 4.0 * c2 * c0);
  const double D = std::max((-c1 + disc) / (2.0 * c2), (-c1 - disc) / (2.0 * c2));
  return std::sqrt(D);
}

TEST(ShipRollDamperOracle, MinimaxBrakePutsTheRollPeakOnTheHighestInvariantPoint) {
  ShipRollDamperParams p = digest_ship(0.0, 0.0);
  double w2 = 0, w3 = 0;
  invariant_frequencies(p, w2, w3);
  const double ordinate = 1.0 / std::abs(p.c - p.A * w2 * w2), stat = 1.0 / p.c;
  p.d2 = minimax_d2(p, w2);
  // The reference gives d2_opt ≈ 4.53e4 N m s/rad (3 digits): within half a unit of the last digit.
  EXPECT_NEAR(p.d2, 4.53e4, 50.0) << p.d2;
  std::printf("minimax d2 = %.1f N m s/rad\n", p.d2);
  // (14.11) at d2_opt: the global maximum over ω is the invariant ordinate, at ω_II (grid+golden search;
  // the search's resolution in height is ~1e-12 relative), i.e. 1.06 × static as the reference says.
  double w_peak = 0, peak = 0;
  book_peak(p, 0.01, 3.0, w_peak, peak);
  EXPECT_NEAR(peak / ordinate, 1.0, 1e-9);
  EXPECT_NEAR(w_peak / w2, 1.0, 1e-4);  // the peak is flat: its abscissa is found only to ~sqrt(1e-9)
  EXPECT_NEAR(peak / stat, 1.06, 0.005);
  std::printf("peak %.6e at w %.6f (w_II %.6f) = %.5f x static\n", peak, w_peak, w2, peak / stat);
  // Minimax: a brake 20 % weaker or stronger has a higher peak (by more than 0.2 %).
  for (const double f : {0.8, 1.25}) {
    ShipRollDamperParams q = p;
    q.d2 = f * p.d2;
    double wq = 0, pq = 0;
    book_peak(q, 0.01, 3.0, wq, pq);
    EXPECT_GT(pq, 1.002 * peak) << "d2 factor " << f;
    std::printf("d2 x %.2f: peak %.5f x static\n", f, pq / stat);
  }
  // The simulated ship agrees: at d2_opt the response at ω_II is the ordinate and falls off on both sides.
  const Steady top = steady_response(p, kE0, w2);
  EXPECT_NEAR(top.phi_A / (top.forcing * ordinate), 1.0, 1e-5);  // budget of the (14.11) test
  std::printf("simulated top at w_II: %+.2e from the ordinate\n", top.phi_A / (top.forcing * ordinate) - 1.0);
  for (const double f : {0.9, 1.1}) {
    const Steady side = steady_response(p, kE0, f * w2);
    EXPECT_LT(side.phi_A / side.forcing, top.phi_A / top.forcing) << "w/w_II " << f;
  }
  // The reference's other two brakes (peak × static). Recomputed from (14.11): 2.632 and 8.437; the
  // reference table gives 2.62 and 8.49 (0.4 % and 0.6 % off). The simulated peaks confirm the recomputed
  // values to 1e-5.
  struct Case {
    double d2, lo, hi, peak_x_static;
  };
  for (const Case cs : {Case{4.5e3, 0.05, 0.5, 2.6316}, Case{4.5e5, 0.3, 1.0, 8.4371}}) {
    ShipRollDamperParams q = p;
    q.d2 = cs.d2;
    double wq = 0, pq = 0;
    book_peak(q, cs.lo, cs.hi, wq, pq);
    EXPECT_NEAR(pq / stat, cs.peak_x_static, 1e-4) << cs.d2;
    const Steady s = steady_response(q, kE0, wq);
    EXPECT_NEAR(s.phi_A / (s.forcing * pq), 1.0, 1e-5) << cs.d2;
    std::printf("d2 %.3g: peak %.5f x static at w %.5f, simulated %+.2e\n", cs.d2, pq / stat, wq,
                s.phi_A / (s.forcing * pq) - 1.0);
  }
}

// ---- large angles and end stops

// Without damping and inputs the large-angle model is conservative (the gyroscopic terms do no work): a
// wrong sign or a missing cosβ in any large-angle term shows as energy drift of order the term itself.
struct EnergyRun {
  double drift{0}, beta_max{0}, case_share{0};
};
EnergyRun energy_run(double beta_stop, double h) {
  ShipRollDamperParams p = digest_ship(0.0, 0.0);
  p.w = 0.5;                   // wall-sided righting arm
  p.Q = 0.4 * p.B;             // unequal case inertias: I(β) and the φ'β', φ'² terms
  p.q = 2.0e5;                 // a heavier pendulum so the case-gravity terms carry energy
  p.stop_damping_ratio = 0.0;  // elastic stops (the damper would dissipate)
  p.beta_stop = beta_stop;
  const ShipRollDamper model(p);
  Rk4 integ(model);
  ShipRollDamper::State x = ShipRollDamper::make_state(0.35, 0.0, 0.0, 0.0);
  const double E0 = model.energy(x);
  EnergyRun r;
  const long n = std::lround(60.0 / h);
  for (long i = 0; i < n; ++i) {
    integ.step(static_cast<double>(i) * h, h, x);
    r.drift = std::max(r.drift, std::abs(model.energy(x) - E0) / E0);
    r.beta_max = std::max(r.beta_max, std::abs(x[1]));
    r.case_share = std::max(r.case_share, (0.5 * p.B * x[3] * x[3] + p.q * (1.0 - std::cos(x[1]))) / E0);
  }
  return r;
}

TEST(ShipRollDamperModel, EnergyIsConservedWithTheLargeAngleTerms) {
  const EnergyRun r = energy_run(1.2217, 1e-3);
  std::printf("energy drift %.3e beta_max %.3f case share %.3f\n", r.drift, r.beta_max, r.case_share);
  // Not vacuous: β swings to ~57° (cosβ = 0.55) and the case carries a good part of the energy.
  EXPECT_GT(r.beta_max, 0.9);
  EXPECT_LT(r.beta_max, 1.2217);  // but stays off the stops (tested next)
  EXPECT_GT(r.case_share, 0.05);
  // RK4 at h|λ|max ≈ 1e-3·2: energy error ~(hλ)⁶/144 per step; 1e-9 of E0 is 1e7 times below the energy
  // error a 1 % mistake in any large-angle term produces over this run.
  EXPECT_LT(r.drift, 1e-9);
}

TEST(ShipRollDamperModel, EnergyIsConservedThroughElasticStopContacts) {
  const EnergyRun a = energy_run(0.8, 1e-3), b = energy_run(0.8, 2.5e-4);
  std::printf("energy drift %.3e %.3e beta_max %.3f case share %.3f\n", a.drift, b.drift, a.beta_max,
              a.case_share);
  EXPECT_GT(a.beta_max, 0.8);  // the stops are hit
  // At contact onset the force is continuous (ζ_s = 0) but its slope jumps by k_s β': RK4 loses its order
  // at each contact, ~(hω_s)² × the case's energy (≈ 1e-2 × 0.1 E0 ... of which a small part accumulates)
  // at the 1 ms tick. 1e-4 of E0 is still 100 times below a 1 % error in any term.
  EXPECT_LT(a.drift, 1e-4);
  // Quartering h shrinks it by ≈ 16 (second order through the kinks), not by 4⁴: allow > 10.
  EXPECT_GT(a.drift / b.drift, 10.0);
}

// ζ_s = 1: a case arriving at the stop with β' = v0 leaves it with −e^-2 v0 (contact ends when the clipped
// force k_s δ + d_s β' reaches zero, at ω_s t = 2). Decoupled case (H = 0, q = 0) so that only the stop acts.
double rebound_speed(double h, double onset_fraction) {
  ShipRollDamperParams p = digest_ship(0.0, 0.0);
  p.H = 0.0;
  p.q = 0.0;
  const ShipRollDamper model(p);
  Rk4 integ(model);
  const double v0 = 0.5;
  // The case reaches the stop `onset_fraction` of a step after t = 0 (0: at a step boundary, just inside).
  ShipRollDamper::State x =
      ShipRollDamper::make_state(0.0, p.beta_stop - onset_fraction * v0 * h + 1e-15, 0.0, v0);
  int i = 0;
  while ((x[1] > p.beta_stop || x[3] > 0.0) && i < 1000000) integ.step(i * h, h, x), ++i;
  return -x[3] / v0;
}

TEST(ShipRollDamperModel, CriticallyDampedStopHasRestitutionExpMinus2) {
  const double e = std::exp(-2.0);
  // Onset on a step boundary, h ω_s = 0.01: the only error is the slope kink at release, O((hω_s)²) ≈ 1e-4.
  EXPECT_NEAR(rebound_speed(1e-4, 0.0) / e, 1.0, 1e-3);
  std::printf("restitution at h = 0.1 ms: %.6f (exact %.6f)\n", rebound_speed(1e-4, 0.0), e);
  // At the controller tick with the onset inside a step the damper force jumps by d_s v0 mid-step; RK4's
  // stage weights (1/6, 4/6, 1/6) against the exact share (1 − θ) of the step misweight the jump by at most
  // 1/3: the header's bound (2/3) ζ_s ω_s h v0 = 0.067 v0. The energy kept, e², stays ≤ 6 %.
  for (const double f : {0.1, 0.37, 0.5, 0.8}) {
    const double r = rebound_speed(1e-3, f);
    std::printf("restitution at h = 1 ms, onset %.2f of a step: %.4f (exact %.4f)\n", f, r, e);
    EXPECT_NEAR(r, e, 2.0 / 3.0 * 0.1) << "onset fraction " << f;
    EXPECT_LT(r * r, 0.06);
  }
}

// Resonant sea with a light brake: the linear theory would swing the case to ~2 β_stop; the stops hold it,
// penetrating no more than the pressing torque and the arrival speed allow.
TEST(ShipRollDamperModel, StopsHoldThePrecessionAngleInAResonantSea) {
  ShipRollDamperParams p = digest_ship(1e6, 4.5e3);
  double w2 = 0, w3 = 0;
  invariant_frequencies(p, w2, w3);
  const double w = w2;
  const double E0 = 2.0 * p.beta_stop / book_beta_amplitude(p, w);
  ShipRollDamper model(p);
  Rk4 integ(model);
  ShipRollDamper::State x = ShipRollDamper::State::Zero();
  const double h = 1e-3;
  double beta_max = 0, rate_max = 0, roll_rate_max = 0;
  for (long i = 0; i < 600000; ++i) {
    const double t = static_cast<double>(i) * h;
    model.inputs.E = E0 * std::cos(w * (t + 0.5 * h));
    integ.step(t, h, x);
    beta_max = std::max(beta_max, std::abs(x[1]));
    rate_max = std::max(rate_max, std::abs(x[3]));
    roll_rate_max = std::max(roll_rate_max, std::abs(x[2]));
  }
  const double k_s = p.B * p.stop_frequency * p.stop_frequency;
  // Static penetration under the largest pressing torque (gyroscopic H φ' plus the pendulum q) and the
  // dynamic overshoot of a critically damped stop, v/(e ω_s).
  const double bound = (p.H * roll_rate_max + p.q) / k_s + rate_max / (std::exp(1.0) * p.stop_frequency);
  EXPECT_GT(beta_max, p.beta_stop);  // the stops are reached (the test is not vacuous)
  EXPECT_LT(beta_max, p.beta_stop + bound) << "penetration " << beta_max - p.beta_stop << " bound " << bound;
  EXPECT_LT(bound, 0.02);  // and the bound itself is small: ~1° at most
  std::printf("stops: beta_max - beta_stop = %.3e rad, bound %.3e rad\n", beta_max - p.beta_stop, bound);
}

// derivative() and the RK4 step allocate nothing, including on the stops and in the locked mode.
TEST(ShipRollDamperModel, StepsWithoutHeapAllocation) {
  for (const bool locked : {false, true}) {
    ShipRollDamperParams p;
    p.locked = locked;
    ShipRollDamper model(p);
    Rk4 integ(model);
    ShipRollDamper::State x = ShipRollDamper::make_state(0.1, 1.2, 0.0, 0.5);  // arriving at the stop
    const testing::AllocationCounter allocations;
    for (int i = 0; i < 10000; ++i) {
      model.inputs.E = 1e6 * std::cos(0.15 * i * 1e-3);
      model.inputs.M2 = -1e3;
      integ.step(i * 1e-3, 1e-3, x);
    }
    EXPECT_EQ(allocations.count(), 0u);  // exact: any allocation is a defect
  }
}

}  // namespace ship_roll_damper_test
}  // namespace gyrostab
