// The recorded base motion (sim/motion/recorded_motion.hpp, tools/scene/motion_csv.hpp): the cubic Hermite
// interpolation stays within its derived bound, the shipped record replays its generator within that bound
// (inputs and closed-loop run), and bad files and paths are refused with their line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/motion/recorded_motion.hpp"
#include "tools/commands.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/motion_csv.hpp"
#include "tools/scene/motion_file.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab {
namespace {

using dynamics::Quat;
using dynamics::Vec3;

struct Errors {
  double w{0}, dw{0}, f{0};  // max |Δ| over the samples [rad/s, rad/s², m/s²]
};

// max |Δω|, |Δω̇|, |Δf| between a record's interpolant and the motion it sampled, at 16 points inside every
// interval (node times excluded: there the interpolant is exact in ω and f by construction).
template <class Truth>
Errors interpolation_errors(const motion::RecordedMotion& rec, const Truth& truth, double t0, double t1, double g) {
  Errors e;
  const std::vector<double>& ts = rec.record()->t;
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    for (int k = 1; k < 16; ++k) {
      const double t = ts[i] + (ts[i + 1] - ts[i]) * k / 16.0;
      if (t < t0 || t > t1) continue;
      const models::BaseSample a = rec(t), b = truth(t);
      e.w = std::max(e.w, (a.w_B - b.w_B).cwiseAbs().maxCoeff());
      e.dw = std::max(e.dw, (a.dw_B - b.dw_B).cwiseAbs().maxCoeff());
      e.f = std::max(e.f, g * (a.up_B - b.up_B).cwiseAbs().maxCoeff());
    }
  }
  return e;
}

// The bounds of recorded_motion.hpp for an interval h with derivative bounds M3, M4 (end intervals: the
// one-sided slopes' doubled constants; taken for every interval, the simplest safe reading).
double value_bound(double h, double M3, double M4) { return std::pow(h, 4) * M4 / 384 + std::pow(h, 3) * M3 / 12; }
double rate_bound(double h, double M3, double M4) {
  return std::sqrt(3.0) * std::pow(h, 3) * M4 / 216 + h * h * M3 / 3;
}

// ω = a (cos ν1 t, sin ν2 t, cos ν3 t) and f = b (sin μ t, …): every derivative bound is a νᵏ.
struct AnalyticMotion {
  double a{0.2}, b{3.0};
  Vec3 nu{1.3, 2.1, 0.7}, mu{6.0, 4.0, 12.566};
  double g{motion::kStandardGravity};
  models::BaseSample operator()(double t) const {
    models::BaseSample s;
    s.w_B = a * Vec3(std::cos(nu.x() * t), std::sin(nu.y() * t), std::cos(nu.z() * t));
    s.dw_B = a * Vec3(-nu.x() * std::sin(nu.x() * t), nu.y() * std::cos(nu.y() * t), -nu.z() * std::sin(nu.z() * t));
    s.up_B = b * Vec3(std::sin(mu.x() * t), std::sin(mu.y() * t), 1.0 + std::sin(mu.z() * t)) / g;
    return s;
  }
};

std::shared_ptr<motion::MotionRecord> sample(const AnalyticMotion& m, const std::vector<double>& ts) {
  auto r = std::make_shared<motion::MotionRecord>();
  for (double t : ts) {
    const models::BaseSample s = m(t);
    r->t.push_back(t);
    r->q_WB.push_back(Quat::Identity());
    r->w_B.push_back(s.w_B);
    r->f_B.push_back(s.up_B * m.g);
  }
  r->finish();
  return r;
}

TEST(RecordedMotion, HermiteInterpolationStaysWithinItsBoundOnUniformAndJitteredGrids) {
  const AnalyticMotion m;
  const double nu = m.nu.maxCoeff(), mu = m.mu.maxCoeff();
  for (const bool jitter : {false, true}) {
    std::vector<double> ts;
    double h_max = 0.0;
    // A deterministic ±30 % jitter of a 20 ms grid: the non-uniform stencil is exercised.
    for (int k = 0; k <= 500; ++k) ts.push_back(0.02 * k + (jitter && k > 0 && k < 500 ? 0.006 * std::sin(7.0 * k) : 0.0));
    for (std::size_t i = 1; i < ts.size(); ++i) h_max = std::max(h_max, ts[i] - ts[i - 1]);
    const motion::RecordedMotion rec(sample(m, ts), m.g);
    const Errors e = interpolation_errors(rec, m, 0.0, 10.0, m.g);
    const double bw = value_bound(h_max, m.a * std::pow(nu, 3), m.a * std::pow(nu, 4));
    const double bdw = rate_bound(h_max, m.a * std::pow(nu, 3), m.a * std::pow(nu, 4));
    const double bf = value_bound(h_max, m.b * std::pow(mu, 3), m.b * std::pow(mu, 4));
    std::printf("jitter %d h_max %.4g: |dw| %.3g (bound %.3g)  |d dw/dt| %.3g (bound %.3g)  |df| %.3g (bound %.3g)\n",
                jitter, h_max, e.w, bw, e.dw, bdw, e.f, bf);
    EXPECT_LE(e.w, bw);
    EXPECT_LE(e.dw, bdw);
    EXPECT_LE(e.f, bf);
    // Not vacuous: the bound is within 20× of what happens (the h³ term dominates and is nearly attained).
    EXPECT_GT(e.f, bf / 20);
  }
}

TEST(RecordedMotion, AttitudeFollowsTheRecordedRate) {
  // A constant-rate roll: q(t) = exp(½ ω t x̂); Hermite with q̇ = ½ q ⊗ ω is O(h⁴) (≤ h⁴ |q⁗|/384, |q⁗| = (ω/2)⁴).
  const double w = 0.8, h = 0.05;
  auto r = std::make_shared<motion::MotionRecord>();
  for (int k = 0; k <= 100; ++k) {
    const double t = h * k;
    r->t.push_back(t);
    r->q_WB.push_back(Quat(Eigen::AngleAxisd(w * t, Vec3::UnitX())));
    r->w_B.push_back(Vec3(w, 0, 0));
    r->f_B.push_back(Vec3(0, 0, 9.8));
  }
  r->finish();
  const motion::RecordedMotion rec(r, 9.8);
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double t = 0.00493 * k;
    worst = std::max(worst, rec.attitude(t).angularDistance(Quat(Eigen::AngleAxisd(w * t, Vec3::UnitX()))));
  }
  EXPECT_LE(worst, 2.0 * std::pow(h, 4) * std::pow(w / 2, 4) / 384 * 2.0);  // angle = 2 × quaternion error
}

// --- the shipped record against its generator --------------------------------------------------------------

std::unique_ptr<tools::DeviceScene> read_scene(const std::string& path, tools::SceneReader& r) {
  EXPECT_TRUE(r.open(path)) << path;
  auto s = tools::read_device_scene(r);
  EXPECT_NE(s, nullptr) << path << (r.errors().empty() ? "" : r.errors().front());
  return s;
}

// max |y⁽ᵏ⁾| of the generator's ω (k = 3, 4) and f (k = 3, 4) by central differences on a 2 ms grid.
struct DerivativeBounds {
  double w3{0}, w4{0}, f3{0}, f4{0};
};
DerivativeBounds derivative_bounds(const motion::SceneBaseMotion& m, double t0, double t1) {
  DerivativeBounds d;
  const double e = 2e-3;
  const auto w = [&](double t) { return m(t).w_B; };
  const auto f = [&](double t) -> Vec3 { return m(t).up_B * m.g(); };
  for (double t = t0 + 2 * e; t <= t1 - 2 * e; t += 1e-3) {
    const auto third = [&](auto y) { return ((y(t + 2 * e) - 2 * y(t + e) + 2 * y(t - e) - y(t - 2 * e)) / (2 * e * e * e)).cwiseAbs().maxCoeff(); };
    const auto fourth = [&](auto y) {
      return ((y(t + 2 * e) - 4 * y(t + e) + 6 * y(t) - 4 * y(t - e) + y(t - 2 * e)) / (e * e * e * e)).cwiseAbs().maxCoeff();
    };
    d.w3 = std::max(d.w3, third(w));
    d.w4 = std::max(d.w4, fourth(w));
    d.f3 = std::max(d.f3, third(f));
    d.f4 = std::max(d.f4, fourth(f));
  }
  // 10 % for the differences' own O(e²) error and the grid between the maxima.
  d.w3 *= 1.1, d.w4 *= 1.1, d.f3 *= 1.1, d.f4 *= 1.1;
  return d;
}

const std::string kScenes = GYROSTAB_SOURCE_DIR "/sim/scenes/";

// A shipped scene run to its end in process: its signals.csv text (and its report, if asked).
std::string run_csv(const std::string& path, nlohmann::json* report = nullptr) {
  tools::RunRequest req;
  req.scene_path = path;
  req.write_outputs = false;
  req.progress = false;
  std::string csv;
  req.csv_out = &csv;
  req.report_out = report;
  EXPECT_EQ(tools::run_scene(req), 0) << path;
  return csv;
}

TEST(RecordedMotion, ShippedRecordReplaysItsGeneratorWithinTheInterpolationBound) {
  tools::SceneReader rg, rr;
  const auto gen = read_scene(kScenes + "power-stabilizer-ship-motion.toml", rg);
  const auto rec = read_scene(kScenes + "power-stabilizer-recorded-motion.toml", rr);
  ASSERT_TRUE(gen && rec);
  const motion::SceneBaseMotion& g = *gen->base_motion();
  const motion::SceneBaseMotion& r = *rec->base_motion();
  ASSERT_EQ(r.kind, motion::BaseMotionKind::kRecorded);
  const double h = 0.02;  // the record's interval (`motion-record --step-s 0.02`)
  const DerivativeBounds d = derivative_bounds(g, 0.0, 60.0);
  const Errors e = interpolation_errors(r.recorded, g, 0.0, 60.0, g.g());
  const double bw = value_bound(h, d.w3, d.w4), bdw = rate_bound(h, d.w3, d.w4), bf = value_bound(h, d.f3, d.f4);
  std::printf("shipped record, h = %.3g s: |dw| %.3g rad/s (bound %.3g)  |d dw/dt| %.3g rad/s2 (bound %.3g)  "
              "|df| %.3g m/s2 (bound %.3g)\n", h, e.w, bw, e.dw, bdw, e.f, bf);
  EXPECT_LE(e.w, bw);
  EXPECT_LE(e.dw, bdw);
  EXPECT_LE(e.f, bf);
}

// The two scenes run closed loop: the gimbal angles agree to within what the input error moves them — a
// torque error I |Δω̇| against the loop's stiffness k = 200 N m/rad is ~1e-8 rad, far below one encoder count
// (2π/2¹⁸ = 2.4e-5 rad); a count that flips at a boundary feeds back through the law, so the tolerance is two
// counts.
TEST(RecordedMotion, ShippedRecordedSceneRunsLikeItsGeneratorScene) {
  const std::string a = run_csv(kScenes + "power-stabilizer-ship-motion.toml");
  const std::string b = run_csv(kScenes + "power-stabilizer-recorded-motion.toml");
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  std::getline(sa, la);
  std::getline(sb, lb);
  ASSERT_EQ(la, lb);  // the same columns: t, alpha_rad, beta_rad, ...
  double worst = 0.0;
  int rows = 0;
  while (std::getline(sa, la) && std::getline(sb, lb)) {
    double ta, aa, ba, tb, ab, bb;
    ASSERT_EQ(std::sscanf(la.c_str(), "%lf,%lf,%lf", &ta, &aa, &ba), 3);
    ASSERT_EQ(std::sscanf(lb.c_str(), "%lf,%lf,%lf", &tb, &ab, &bb), 3);
    ASSERT_EQ(ta, tb);
    worst = std::max({worst, std::abs(aa - ab), std::abs(ba - bb)});
    ++rows;
  }
  std::printf("closed loop over %d rows: max |d alpha|, |d beta| = %.3g rad\n", rows, worst);
  EXPECT_GT(rows, 1000);
  EXPECT_LE(worst, 2 * 2 * M_PI / (1 << 18));
}

// The coning platform (Magnus §15.5) driven by sim/motion_records/coning-vibration.csv, written by
// `motion-record --step-s 0.01 --duration-s 60` from coning-p-gyro-planar-vibration.toml: the record's
// interpolant against that scene's generator (Φ = 0.01 rad at 5 Hz: |ω⁽³⁾| = Φν⁴ ≈ 1e4 rad/s⁴, so the h³ term
// of the bound, with the end intervals' constant, dominates), then the two closed-loop runs over 45 s.
TEST(RecordedMotion, ConingRecordReplaysItsGeneratorWithinTheInterpolationBound) {
  tools::SceneReader rg, rr;
  const auto gen = read_scene(kScenes + "coning-p-gyro-planar-vibration.toml", rg);
  const auto rec = read_scene(kScenes + "coning-recorded-motion.toml", rr);
  ASSERT_TRUE(gen && rec);
  ASSERT_NE(gen->base_motion(), nullptr);
  const motion::SceneBaseMotion& g = *gen->base_motion();
  const motion::SceneBaseMotion& r = *rec->base_motion();
  ASSERT_EQ(r.kind, motion::BaseMotionKind::kRecorded);
  const double h = 0.01;
  const DerivativeBounds d = derivative_bounds(g, 0.0, 60.0);
  const Errors e = interpolation_errors(r.recorded, g, 0.0, 60.0, g.g());
  const double bw = value_bound(h, d.w3, d.w4), bdw = rate_bound(h, d.w3, d.w4), bf = value_bound(h, d.f3, d.f4);
  std::printf("coning record, h = %.3g s: |dw| %.3g rad/s (bound %.3g)  |d dw/dt| %.3g rad/s2 (bound %.3g)  "
              "|df| %.3g m/s2 (bound %.3g)\n", h, e.w, bw, e.dw, bdw, e.f, bf);
  EXPECT_LE(e.w, bw);
  EXPECT_LE(e.dw, bdw);
  EXPECT_LE(e.f, bf);
  EXPECT_GT(e.w, 0.0);  // a record, not the generator
}

// Closed loop: the rate error ε_ω (≤ the bound above) enters the P-gyro as an input rate, which it reads
// with its static scale H/c2 (|G(iν)| = 1.01 of it at ν/ω_n = 0.1): |Δβ| ≤ 1.1 (H/c2) ε_ω plus what the
// platform's own response adds, the same size again through the loop (|S(iν)| = 1.01) — tolerance
// 2.2 (H/c2) ε_ω. The loop nulls the reading, so the platform turns by the integrated rate error at most:
// |Δφ| ≤ T ε_ω (T = 45 s; a worst case: the error oscillates at ν and mostly cancels). And the drift figure
// (the mean over whole periods) against the generator's: the record moves it by 2 ε_ω/Ω0 relative at most.
TEST(RecordedMotion, ConingRecordedSceneRunsLikeItsGeneratorScene) {
  nlohmann::json ra, rb;
  const std::string a = run_csv(kScenes + "coning-p-gyro-planar-vibration.toml", &ra);
  const std::string b = run_csv(kScenes + "coning-recorded-motion.toml", &rb);
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  std::getline(sa, la);
  std::getline(sb, lb);
  ASSERT_EQ(la, lb);  // t_s, phi_rad, phi_rate_rad_s, platform_rate_rad_s, beta_rad, ...
  double dphi = 0.0, dbeta = 0.0;
  int rows = 0;
  while (std::getline(sa, la) && std::getline(sb, lb)) {
    double ta, pa, pra, wa, ba, tb, pb, prb, wb, bb;
    ASSERT_EQ(std::sscanf(la.c_str(), "%lf,%lf,%lf,%lf,%lf", &ta, &pa, &pra, &wa, &ba), 5);
    ASSERT_EQ(std::sscanf(lb.c_str(), "%lf,%lf,%lf,%lf,%lf", &tb, &pb, &prb, &wb, &bb), 5);
    ASSERT_EQ(ta, tb);
    dphi = std::max(dphi, std::abs(pa - pb));
    dbeta = std::max(dbeta, std::abs(ba - bb));
    ++rows;
  }
  tools::SceneReader rg;
  const auto gen = read_scene(kScenes + "coning-p-gyro-planar-vibration.toml", rg);
  ASSERT_TRUE(gen);
  const DerivativeBounds d = derivative_bounds(*gen->base_motion(), 0.0, 60.0);
  const double eps_w = value_bound(0.01, d.w3, d.w4);  // as in the test above
  const double H_over_c2 = 0.025 / 0.2;
  const double drift_a = ra["figures"]["drift_rate_rad_s"].get<double>();
  const double drift_b = rb["figures"]["drift_rate_rad_s"].get<double>();
  const double omega0 = 0.01 * 2 * M_PI * 5.0 * std::sqrt(0.5);  // Ω10 = Ω30 [rad/s]
  std::printf("coning closed loop over %d rows: max |d phi| %.3g rad (tol %.3g), |d beta| %.3g rad (tol %.3g); "
              "drift %.6g vs %.6g rad/s (rel %.3g, tol %.3g)\n",
              rows, dphi, 45.0 * eps_w, dbeta, 2.2 * H_over_c2 * eps_w, drift_b, drift_a,
              std::abs(drift_b / drift_a - 1), 2 * eps_w / omega0);
  EXPECT_GT(rows, 1000);
  EXPECT_LE(dphi, 45.0 * eps_w);
  EXPECT_LE(dbeta, 2.2 * H_over_c2 * eps_w);
  EXPECT_GT(dbeta, 0.0);
  EXPECT_LE(std::abs(drift_b / drift_a - 1), 2 * eps_w / omega0);
}

// The heading gyro in a level turn (gimbal_error, Magnus §12.1) driven by sim/motion_records/heading-gyro-turn.csv
// (`motion-record --step-s 0.5 --duration-s 600` of gimbal-error-heading-gyro-turn.toml). In the turn the body rates are constant
// (ψ' sinφ, ψ' cosφ), so the Hermite rates are exact and the integrated attitude — the gimbal angles α, β — agrees
// with the generator's to round-off (12 000 RK4 steps: 1e-12). The Euler angles the errors are measured against
// come from the record's attitude, a cubic Hermite on q with exact slopes: ≤ h⁴ |q⁗|/384 = 0.5⁴ (|ω|/2)⁴/384
// = 7.6e-11 rad (|ω| = 0.052 rad/s), so α − ψ and ψ within 2 × that.
TEST(RecordedMotion, GimbalErrorRecordedSceneRunsLikeItsGeneratorScene) {
  const std::string a = run_csv(kScenes + "gimbal-error-heading-gyro-turn.toml");
  const std::string b = run_csv(kScenes + "gimbal-error-recorded-motion.toml");
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  std::getline(sa, la);
  std::getline(sb, lb);
  ASSERT_EQ(la, lb);  // t_s, alpha_rad, beta_rad, alpha_error_rad, beta_error_rad, yaw_rad, ...
  double dgimbal = 0.0, deuler = 0.0;
  int rows = 0;
  while (std::getline(sa, la) && std::getline(sb, lb)) {
    double x[6], y[6];
    ASSERT_EQ(std::sscanf(la.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &x[0], &x[1], &x[2], &x[3], &x[4], &x[5]), 6);
    ASSERT_EQ(std::sscanf(lb.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &y[0], &y[1], &y[2], &y[3], &y[4], &y[5]), 6);
    ASSERT_EQ(x[0], y[0]);
    dgimbal = std::max({dgimbal, std::abs(x[1] - y[1]), std::abs(x[2] - y[2])});
    deuler = std::max({deuler, std::abs(std::remainder(x[3] - y[3], 2 * M_PI)),
                       std::abs(std::remainder(x[5] - y[5], 2 * M_PI))});
    ++rows;
  }
  const double w = std::hypot(0.026179938779914941, 0.045344984105855454);  // the record's |ω| [rad/s]
  const double q_bound = std::pow(0.5, 4) * std::pow(0.5 * w, 4) / 384;
  std::printf("heading gyro over %d rows: max |d alpha|, |d beta| %.3g rad (tol 1e-12); |d (alpha - psi)|, "
              "|d psi| %.3g rad (tol %.3g)\n", rows, dgimbal, deuler, 2 * q_bound);
  EXPECT_GT(rows, 1000);
  EXPECT_LE(dgimbal, 1e-12);
  EXPECT_LE(deuler, 2 * q_bound);
}

// --- refusals ----------------------------------------------------------------------------------------------

const std::string kHeader = "t [s], q0, q1, q2, q3, wx [rad/s], wy [rad/s], wz [rad/s], fx [m/s^2], fy [m/s^2], fz [m/s^2]\n";
std::string row(double t, double q0 = 1.0) {
  char b[200];
  std::snprintf(b, sizeof b, "%g, %g, 0, 0, 0, 0.1, 0, 0, 0, 0, 9.8\n", t, q0);
  return b;
}

std::vector<std::string> refuse(const std::string& text, tools::MotionCsvLimits lim = {}) {
  motion::MotionRecord r;
  std::vector<std::string> problems;
  EXPECT_FALSE(tools::parse_motion_csv(text, "m.csv", lim, r, problems)) << text;
  return problems;
}

bool has(const std::vector<std::string>& ps, const std::string& s) {
  for (const auto& p : ps) {
    if (p.find(s) != std::string::npos) return true;
  }
  return false;
}

TEST(MotionCsv, BadFilesAreRefusedWithTheirLine) {
  // Line 1 is the header; data from line 2.
  EXPECT_TRUE(has(refuse(kHeader + row(0) + row(0.01) + row(0.01) + row(0.02)),
                  "m.csv:4: time 0.01 s does not follow line 3's 0.01 s"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + row(0.02) + row(0.01) + row(0.03)), "m.csv:4: time 0.01 s"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + row(0.01) + row(0.5)), "m.csv:4: a gap of 0.49 s after line 3 exceeds max_gap_s = 0.1 s"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + "0.01, 1, 0, 0, 0, nan, 0, 0, 0, 0, 9.8\n" + row(0.02)), "m.csv:3: column wx: 'nan' is not finite"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + "0.01, 1, 0, 0, 0, inf, 0, 0, 0, 0, 9.8\n" + row(0.02)), "m.csv:3: column wx: 'inf' is not finite"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + "0.01, 1, 0, 0, 0, 0.1x, 0, 0, 0, 0, 9.8\n" + row(0.02)), "m.csv:3: column wx: '0.1x' is not a number"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + "0.01, 1, 0\n" + row(0.02)), "m.csv:3: 3 fields, the header has 11"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + row(0.01, 1.01) + row(0.02)), "m.csv:3: quaternion norm 1.01 differs from 1"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + row(0.01)), "m.csv: 2 rows: a record needs at least 3"));
  EXPECT_TRUE(has(refuse("# only a comment\n"), "m.csv: no header line"));
  // The header: missing, unknown, repeated columns and units.
  EXPECT_TRUE(has(refuse("t [s], q0, q1, q2, q3, wx [rad/s], wy [rad/s], fx [m/s^2], fy [m/s^2], fz [m/s^2]\n" + row(0)),
                  "m.csv:1: missing angular rate columns: wx, wy, wz"));
  EXPECT_TRUE(has(refuse("# a comment first\nt [s], q0, q1, q2, q3, wx [rad/s], wy [rad/s], wz [rad/s], fx [m/s^2], fy [m/s^2], fz [m/s^2], heave [m]\n"),
                  "m.csv:2: unknown column 'heave'"));
  EXPECT_TRUE(has(refuse("t [s], t [s], q0, q1, q2, q3\n"), "m.csv:1: column 't' appears twice"));
  EXPECT_TRUE(has(refuse("t, q0, q1, q2, q3, wx [rad/s], wy [rad/s], wz [rad/s], fx [m/s^2], fy [m/s^2], fz [m/s^2]\n"),
                  "m.csv:1: column 't' needs a unit: [s]"));
  EXPECT_TRUE(has(refuse("t [ms], q0, q1, q2, q3, wx [rad/s], wy [rad/s], wz [rad/s], fx [m/s^2], fy [m/s^2], fz [m/s^2]\n"),
                  "m.csv:1: column 't' has unit 'ms'; allowed: [s]"));
  EXPECT_TRUE(has(refuse("t [s], q0, q1, q2, q3, roll [deg], pitch [deg], yaw [deg], wx [rad/s], wy [rad/s], wz [rad/s], fx [g], fy [g], fz [g]\n"),
                  "m.csv:1: give the attitude once"));
}

TEST(MotionCsv, ValuesOutsideTheirColumnsRangeAreRefusedWithTheirLine) {
  EXPECT_TRUE(has(refuse(kHeader + row(0) + "0.01, 1, 0, 0, 0, 1e308, 0, 0, 0, 0, 9.8\n" + row(0.02)),
                  "m.csv:3: column wx: '1e308' is 1e+308 rad/s, outside ±100 rad/s"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + "0.01, 1, 0, 0, 0, 0, 0, -101, 0, 0, 9.8\n" + row(0.02)),
                  "m.csv:3: column wz: '-101' is -101 rad/s, outside ±100 rad/s"));
  EXPECT_TRUE(has(refuse(kHeader + row(0) + "0.01, 1, 0, 0, 0, 0, 0, 0, 0, 2000, 9.8\n" + row(0.02)),
                  "m.csv:3: column fy: '2000' is 2000 m/s^2, outside ±1000 m/s^2"));
  const std::vector<std::string> close =
      refuse(kHeader + row(0) + row(0.01) + "0.0100000005, 1, 0, 0, 0, 0.1, 0, 0, 0, 0, 9.8\n" + row(0.02));
  EXPECT_TRUE(has(close, "m.csv:4: time 0.0100000005 s is ")) << (close.empty() ? "" : close.front());
  EXPECT_TRUE(has(close, "s after line 3's: rows must be at least 1e-06 s apart")) << (close.empty() ? "" : close.front());
  EXPECT_TRUE(has(refuse(kHeader + row(0) + row(0.01) + row(2e7)), "m.csv:4: column t: '2e+07' is 20000000 s, outside ±10000000 s"));
}

// `check` and `run` read a record through one reader: a rate of 1e308 rad/s in the coning record, which the
// plant could not integrate (non-finite at tick 979), is refused by both with exit 2 and the line.
TEST(MotionFile, CheckAndRunRefuseTheSameRecordWithTheSameMessage) {
  const std::string dir = ::testing::TempDir() + "/recorded_motion_range";
  std::filesystem::create_directories(dir);
  {
    std::ifstream in(GYROSTAB_SOURCE_DIR "/sim/motion_records/coning-vibration.csv");
    std::ofstream out(dir + "/fast.csv");
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      if (n == 1000) {  // a data row: t, q0..q3, then wx
        std::size_t at = 0;
        for (int commas = 0; commas < 5; ++commas) at = line.find(',', at) + 1;
        line = line.substr(0, at) + "1e308" + line.substr(line.find(',', at));
      }
      out << line << "\n";
    }
  }
  std::ifstream scene(kScenes + "coning-recorded-motion.toml");
  std::stringstream text;
  text << scene.rdbuf();
  std::string t = text.str();
  const std::size_t at = t.find("../motion_records/coning-vibration.csv");
  ASSERT_NE(at, std::string::npos);
  t.replace(at, std::string("../motion_records/coning-vibration.csv").size(), "fast.csv");
  std::ofstream(dir + "/fast.toml") << t;
  for (const bool check_only : {true, false}) {
    tools::RunRequest req;
    req.scene_path = dir + "/fast.toml";
    req.check_only = check_only;
    req.write_outputs = false;
    req.progress = false;
    ::testing::internal::CaptureStderr();
    const int rc = tools::run_scene(req);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(rc, 2) << (check_only ? "check" : "run") << ": " << err;
    EXPECT_NE(err.find("fast.csv:1000: column wx: '1e308' is 1e+308 rad/s, outside ±100 rad/s"), std::string::npos)
        << err;
  }
}

TEST(MotionCsv, EulerAnglesDegreesAndGAreConverted) {
  const std::string text =
      "t [s], roll [deg], pitch [deg], yaw [deg], wx [deg/s], wy [deg/s], wz [deg/s], fx [g], fy [g], fz [g]\r\n"
      "0, 90, 0, 0, 180, 0, 0, 0, 0, 1\r\n0.01, 90, 0, 0, 180, 0, 0, 0, 0, 1\r\n0.02, 90, 0, 0, 180, 0, 0, 0, 0, 1\r\n";
  motion::MotionRecord r;
  std::vector<std::string> problems;
  ASSERT_TRUE(tools::parse_motion_csv(text, "e.csv", {}, r, problems)) << problems.front();
  EXPECT_NEAR(r.w_B[1].x(), M_PI, 1e-15);
  EXPECT_EQ(r.f_B[2].z(), motion::kStandardGravity);
  EXPECT_NEAR(r.q_WB[0].angularDistance(Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()))), 0.0, 1e-15);
}

TEST(MotionFile, PathsOutsideTheScenesDirectoryAndItsRecordsAreRefused) {
  const std::string root = GYROSTAB_SOURCE_DIR "/sim/scenes";
  std::vector<std::string> p;
  EXPECT_EQ(tools::load_motion_file("x.csv", "", {}, p), nullptr);
  EXPECT_TRUE(has(p, "cannot name a motion file"));
  p.clear();
  EXPECT_EQ(tools::load_motion_file("/etc/hosts.csv", root, {}, p), nullptr);
  EXPECT_TRUE(has(p, "relative to the scene file's directory"));
  p.clear();
  EXPECT_EQ(tools::load_motion_file("../../tests/unit/x.csv", root, {}, p), nullptr);
  EXPECT_TRUE(has(p, "leads outside"));
  p.clear();
  EXPECT_EQ(tools::load_motion_file("../motion_records/../../README.md", root, {}, p), nullptr);
  EXPECT_TRUE(has(p, "a motion record is a .csv file"));
  p.clear();
  EXPECT_EQ(tools::load_motion_file("../motion_records/none.csv", root, {}, p), nullptr);
  EXPECT_TRUE(has(p, "no such file"));
  p.clear();
  EXPECT_NE(tools::load_motion_file("../motion_records/ship-motion.csv", root, {}, p), nullptr) << (p.empty() ? "" : p[0]);
}

TEST(MotionFile, SceneTextWithoutAFileNamesNoMotionFile) {
  // check_scene_text is the fuzz target's entry: a scene given as text reads no file at all.
  std::ifstream f(kScenes + "power-stabilizer-recorded-motion.toml");
  std::stringstream text;
  text << f.rdbuf();
  std::vector<std::string> problems;
  EXPECT_EQ(tools::check_scene_text(text.str(), "t.toml", &problems), 2);
  EXPECT_TRUE(has(problems, "[motion] file: a scene given as text, not read from a file, cannot name a motion file"))
      << (problems.empty() ? "" : problems.front());
}

TEST(MotionFile, ARecordShorterThanTheSceneIsRefused) {
  const std::string dir = ::testing::TempDir() + "/recorded_motion_short";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/short.csv") << kHeader << row(0) << row(0.01) << row(0.02);
  std::ofstream(dir + "/s.toml") << "[scene]\ndevice = \"power_stabilizer\"\nduration_s = 1.0\n[gyro]\nCR = 0.1\nrpm = 19098.6\n"
                                    "AR = 0.5\n[controller]\nk1 = 200.0\nk2 = 200.0\n[motion]\nkind = \"recorded\"\nfile = \"short.csv\"\n";
  tools::SceneReader r;
  ASSERT_TRUE(r.open(dir + "/s.toml"));
  EXPECT_EQ(tools::read_device_scene(r), nullptr);
  EXPECT_TRUE(has(r.errors(), "short.csv: the record covers [0, 0.02] s; the scene runs over [0, 1] s"))
      << (r.errors().empty() ? "" : r.errors().front());
}

}  // namespace
}  // namespace gyrostab
