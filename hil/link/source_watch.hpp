// A second source on a link without a key: a process that reads the bus can copy the session and sender ids
// (link_guard.hpp: nothing else authenticates a frame then) and send frames the guard cannot tell from the
// peer's. It cannot, however, stop the peer: the genuine frames keep coming. So a receiver that sees, from its
// bound peer,
//   - two frames for one tick with different contents (a resend repeats the frame byte for byte; a second
//     source's frame for that tick differs), or
//   - in lockstep, on kStaleTicks ticks in a row, a refused stale frame for one of the last kRecentTicks ticks
//     whose contents differ from the frame accepted for that tick (a peer in lockstep sends each tick once and
//     resends only what it already sent: when a faster impostor's frames are accepted, the genuine ones arrive
//     a tick late with other contents),
// concludes that two sources speak as one sender. The run then cannot stand: both ends end it with exit 7
// naming what they saw (docs/protocol.md). With a key this never happens: a copier has no MAC.
// Stale frames that are copies of what was accepted, or that are older than kRecentTicks, are counted by the
// order checks but are no evidence: on a loaded machine a process that replays the bus late (or the peer's own
// resends) delivers them in bursts, several on consecutive ticks, without any race being lost.
// O(1) per frame, no heap. Tests: tests/unit/source_watch_test.cpp, tests/lcm/lcm_bad_messages_test.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "firmware/msg/any_frame.hpp"

namespace gyrostab::hil {

// FNV-1a 64 of a frame's header and first `signals` values: the content a resend repeats exactly.
template <class AnyFrame>
std::uint64_t frame_content_hash(const AnyFrame& f, std::size_t signals) {
  const auto* p = reinterpret_cast<const unsigned char*>(&f);
  const std::size_t n = msg::kFrameHeaderBytes + signals * sizeof(double);
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

class SourceWatch {
 public:
  static constexpr int kStaleTicks = 8;
  // A genuine frame that lost the race trails the accepted one by a tick; older stale frames are late copies.
  static constexpr std::size_t kRecentTicks = 16;

  // A frame of the bound peer was accepted for `tick`.
  void accepted(std::uint64_t tick, std::uint64_t content) {
    have_ = true;
    tick_ = tick;
    content_ = content;
    recent_[tick % kRecentTicks] = Recent{tick, content, true};
  }
  // A frame of the bound peer was refused by the order checks; `stale`: it was for an earlier tick.
  void refused(std::uint64_t tick, std::uint64_t content, bool stale) {
    if (have_ && tick == tick_ && content != content_ && conflict_tick_ < 0) {
      conflict_tick_ = static_cast<std::int64_t>(tick);
    }
    if (stale && differs_from_accepted(tick, content)) stale_this_tick_ = true;
  }
  // The receiver's tick ends; `lockstep`: the stale-streak rule applies.
  void end_tick(std::int64_t tick, bool lockstep) {
    stale_streak_ = lockstep && stale_this_tick_ ? stale_streak_ + 1 : 0;
    stale_this_tick_ = false;
    if (stale_streak_ >= kStaleTicks && streak_tick_ < 0) streak_tick_ = tick;
  }

  bool hijacked() const { return conflict_tick_ >= 0 || streak_tick_ >= 0; }
  // The tick of the first evidence, and which: two contents for one tick, or a run of stale ticks.
  std::int64_t conflict_tick() const { return conflict_tick_; }
  std::int64_t stale_streak_tick() const { return streak_tick_; }

 private:
  struct Recent {
    std::uint64_t tick{0};
    std::uint64_t content{0};
    bool valid{false};
  };
  bool differs_from_accepted(std::uint64_t tick, std::uint64_t content) const {
    const Recent& r = recent_[tick % kRecentTicks];
    return r.valid && r.tick == tick && r.content != content;
  }

  Recent recent_[kRecentTicks]{};
  bool have_{false};
  std::uint64_t tick_{0};
  std::uint64_t content_{0};
  bool stale_this_tick_{false};
  int stale_streak_{0};
  std::int64_t conflict_tick_{-1};
  std::int64_t streak_tick_{-1};
};

}  // namespace gyrostab::hil
