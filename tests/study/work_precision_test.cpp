// The work-precision analysis on hand-made points: the front drops dominated points, T(e) interpolates
// log(time) against log(error), holds the cheapest time above the cheapest run's error and refuses to
// extrapolate below the most accurate run; the speed-up compares the best of each family at equal error.
#include <gtest/gtest.h>

#include <cmath>

#include "tools/accuracy/work_precision.hpp"

namespace gyrostab::tools::accuracy {
namespace work_precision_test {

RunResult run(const char* method, Family f, double wall_s, double error) {
  RunResult r;
  r.spec.method = method;
  r.spec.family = f;
  r.spec.substeps = 1;
  r.outcome.ok = true;
  r.cpu_s = {wall_s};
  r.wall_s = {wall_s};
  r.errors = {error};
  r.below_floor = {false};
  r.comparison_error = {error};
  return r;
}

TEST(WorkPrecision, FrontDropsDominatedPointsAndSortsByTime) {
  const auto f = work_front({{4.0, 1e-6, 0}, {1.0, 1e-3, 1}, {2.0, 1e-2, 2}, {3.0, 1e-5, 3}, {5.0, 1e-5, 4}});
  ASSERT_EQ(f.size(), 3u);  // (2, 1e-2) is slower than (1, 1e-3) and worse; (5, 1e-5) is slower than (3, 1e-5)
  EXPECT_EQ(f[0].run, 1u);
  EXPECT_EQ(f[1].run, 3u);
  EXPECT_EQ(f[2].run, 0u);
}

TEST(WorkPrecision, TimeForErrorInterpolatesInLogLogAndNeverExtrapolates) {
  const std::vector<WorkPoint> f{{1.0, 1e-2, 0}, {16.0, 1e-6, 1}};  // error ∝ time^-... : 4 decades per 16×
  EXPECT_DOUBLE_EQ(time_for_error(f, 1e-2), 1.0);
  EXPECT_DOUBLE_EQ(time_for_error(f, 1.0), 1.0);           // the cheapest run already meets it
  EXPECT_NEAR(time_for_error(f, 1e-4), 4.0, 1e-12);        // halfway in log error: halfway in log time
  EXPECT_NEAR(time_for_error(f, 1e-3), 2.0, 1e-12);
  EXPECT_TRUE(std::isnan(time_for_error(f, 1e-7)));        // beyond the most accurate run
}

TEST(WorkPrecision, SpeedUpComparesTheBestOfEachFamilyAtEqualError) {
  StudyResult s;
  s.window_s = 2.0;  // times per simulated second are wall / 2
  s.repeats = 1;
  s.runs = {run("fast", Family::kOurs, 2.0, 1e-4), run("fast", Family::kOurs, 8.0, 1e-8),
            run("slow", Family::kOurs, 20.0, 1e-4), run("peerA", Family::kPeer, 10.0, 1e-4),
            run("peerA", Family::kPeer, 40.0, 1e-6), run("peerB", Family::kPeer, 6.0, 1e-2),
            run("peerB", Family::kPeer, 600.0, 1e-6)};
  // At 1e-4: ours "fast" 1 s/s, peers: A 5 s/s, B interpolated 3·(100)^(1/2)... = 30 s/s: best peer A.
  const SpeedUp a = speed_up_at(s, 0, 1e-4);
  EXPECT_EQ(a.ours_method, "fast");
  EXPECT_EQ(a.peer_method, "peerA");
  EXPECT_NEAR(a.ours_time, 1.0, 1e-12);
  EXPECT_NEAR(a.peer_time, 5.0, 1e-12);
  EXPECT_NEAR(a.ratio, 5.0, 1e-12);
  // At 1e-6: ours fast: 1·4^(1/2) = 2 s/s; peer A 20 s/s.
  const SpeedUp b = speed_up_at(s, 0, 1e-6);
  EXPECT_NEAR(b.ratio, 10.0, 1e-12);
  // At 1e-7 no peer reaches: undefined as a ratio, bounded below by the peers' most accurate run (peerA at
  // 1e-6, 20 s/s; peerB's 1e-6 costs 300) against ours at 1e-7 (fast: 1·4^(3/4) = 2.83 s/s).
  const SpeedUp c = speed_up_at(s, 0, 1e-7);
  EXPECT_TRUE(std::isnan(c.ratio));
  EXPECT_EQ(c.peer_best_method, "peerA");
  EXPECT_NEAR(c.peer_best_error, 1e-6, 1e-20);
  EXPECT_NEAR(c.peer_best_time, 20.0, 1e-12);
  EXPECT_NEAR(c.ratio_at_least, 20.0 / std::pow(4.0, 0.75), 1e-12);
  EXPECT_TRUE(std::isnan(b.ratio_at_least)) << "a peer reaches 1e-6: a ratio, no bound";
  // Decade levels both families reach: 1e-6 … 1e-2.
  const std::vector<double> levels = comparison_levels(s, 0);
  ASSERT_EQ(levels.size(), 5u);
  EXPECT_NEAR(levels.front(), 1e-6, 1e-20);
  EXPECT_NEAR(levels.back(), 1e-2, 1e-16);
  // A point below an unconverged reference's floor is not used (comparison error NaN): without ours' 1e-8
  // point, 1e-6 is beyond ours.
  s.runs[1].below_floor[0] = true;
  s.runs[1].comparison_error[0] = NAN;
  EXPECT_TRUE(std::isnan(speed_up_at(s, 0, 1e-6).ours_time));
  // Ranks by error × time: peerA 1e-6·40 = 4e-5 is best among the rest, then fast 2e-4 …
  const std::vector<int> rank = error_time_ranks(s, 0);
  EXPECT_EQ(rank[1], 0);  // not usable
  EXPECT_EQ(rank[4], 1);
}

}  // namespace work_precision_test
}  // namespace gyrostab::tools::accuracy
