// The second-source rules of hil/link/source_watch.hpp: two contents for one tick, and a run of ticks with a
// stale frame that contradicts a recently accepted one. Copies and late replays of old frames — which a loaded
// machine delivers in bursts over consecutive ticks — must never look like a second source.
#include <gtest/gtest.h>

#include "hil/link/source_watch.hpp"

namespace gyrostab::hil {
namespace {

std::uint64_t content(std::uint64_t tick) { return 1000 + tick; }

TEST(SourceWatch, CopiesOfAcceptedFramesOnEveryTickAreNotASecondSource) {
  SourceWatch w;
  for (std::uint64_t k = 0; k < 100; ++k) {
    w.accepted(k, content(k));
    // The peer's copy of the previous tick's frame (it answered our resend) arrives after we moved on.
    if (k > 0) w.refused(k - 1, content(k - 1), /*stale=*/true);
    if (k > 2) w.refused(k - 3, content(k - 3), /*stale=*/true);
    w.end_tick(static_cast<std::int64_t>(k), /*lockstep=*/true);
  }
  EXPECT_FALSE(w.hijacked());
}

TEST(SourceWatch, StaleFramesOfOtherContentOnEightTicksInARowAreASecondSource) {
  SourceWatch w;
  for (std::uint64_t k = 0; k < 20; ++k) {
    w.accepted(k, content(k));  // the impostor's frame, first
    if (k > 0) w.refused(k - 1, content(k - 1) + 7, /*stale=*/true);  // the genuine one, late
    w.end_tick(static_cast<std::int64_t>(k), /*lockstep=*/true);
  }
  ASSERT_TRUE(w.hijacked());
  EXPECT_LT(w.conflict_tick(), 0);
  EXPECT_EQ(w.stale_streak_tick(), SourceWatch::kStaleTicks);  // ticks 1 .. 8
}

TEST(SourceWatch, ALateReplayOfOldFramesInABurstIsNoEvidence) {
  SourceWatch w;
  for (std::uint64_t k = 0; k < 60; ++k) {
    w.accepted(k, content(k));
    // A process replaying the bus with a backlog: frames of ticks long gone, other contents among them.
    if (k >= 20) {
      w.refused(k - 20, content(k - 20), true);
      w.refused(k - SourceWatch::kRecentTicks, content(k) + 9, true);
    }
    w.end_tick(static_cast<std::int64_t>(k), true);
  }
  EXPECT_FALSE(w.hijacked());
}

TEST(SourceWatch, OtherContentsForARecentTickOnSevenTicksInARowAreNotYetEvidenceEnough) {
  SourceWatch w;
  for (std::uint64_t k = 0; k < 100; ++k) {
    w.accepted(k, content(k));
    // Seven of every eight ticks: one short of the streak, again and again.
    if (k % SourceWatch::kStaleTicks != 0 && k > 2) w.refused(k - 2, content(k), true);
    w.end_tick(static_cast<std::int64_t>(k), true);
  }
  EXPECT_FALSE(w.hijacked());
}

TEST(SourceWatch, StaleResendsOutsideLockstepAreNeverAStreak) {
  SourceWatch w;
  for (std::uint64_t k = 1; k < 50; ++k) {
    w.accepted(k, content(k));
    w.refused(k - 1, content(k - 1) + 1, true);
    w.end_tick(static_cast<std::int64_t>(k), /*lockstep=*/false);
  }
  EXPECT_FALSE(w.hijacked());
}

TEST(SourceWatch, TwoContentsForTheLastAcceptedTickAreASecondSource) {
  SourceWatch w;
  w.accepted(5, content(5));
  w.refused(5, content(5), false);  // a resend: the same bytes
  EXPECT_FALSE(w.hijacked());
  w.refused(5, content(5) + 1, false);
  ASSERT_TRUE(w.hijacked());
  EXPECT_EQ(w.conflict_tick(), 5);
}

}  // namespace
}  // namespace gyrostab::hil
