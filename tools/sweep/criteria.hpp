// The roll criteria a sweep's summary counts against: the probability of the sea states in which a variant's
// mean rms roll exceeds each limit, and the operability that leaves. One table, here; docs/sweep.md quotes it
// with its source and says which values were checked against it.
#pragma once

#include <array>
#include <numbers>
#include <string_view>

namespace gyrostab::tools::sweep {

struct RollCriterion {
  std::string_view name;     // the summary's key
  std::string_view applies;  // to whom, as the source words it
  double limit_deg;          // rms roll
  double limit_rad() const { return limit_deg * std::numbers::pi / 180.0; }
};

// NORDFORSK 1987 ("Assessment of ship performance in a seaway", Nordic cooperative project), the general
// operability limiting criteria for rms roll as the seakeeping literature reprints them. Only the three
// general criteria are taken: the task-related ones (light and heavy manual work, intellectual work,
// passengers) are quoted with differing values by secondary sources and were not checked (docs/sweep.md).
inline constexpr std::array<RollCriterion, 3> kRollCriteria{{
    {"nordforsk_merchant", "merchant ships", 6.0},
    {"nordforsk_naval", "naval vessels", 4.0},
    {"nordforsk_fast_small_craft", "fast small craft", 4.0},
}};

}  // namespace gyrostab::tools::sweep
