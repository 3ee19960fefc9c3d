// The scene seed of one sweep task, from the study seed and the task's sea (cell, heading, replicate) only.
// Not from the variant: every variant meets the same seas (common random numbers), so the difference between
// two variants is not masked by sea noise. Not from the shard, the order or the thread either: a task's seed
// is the same however the study is split. Each index goes through a SplitMix64 step (the generator that seeds
// xoshiro256**, sim/random/seeded_rng.hpp), so neighbouring cells get unrelated seeds.
// Test: tests/sweep/sweep_cli_test.py (SeedsFollowTheSeaNotTheVariant).
#pragma once

#include <cstdint>

#include "sim/random/seeded_rng.hpp"

namespace gyrostab::tools::sweep {

constexpr std::uint64_t task_seed(std::uint64_t study_seed, std::uint64_t cell, std::uint64_t heading,
                                  std::uint64_t replicate) {
  std::uint64_t x = study_seed;
  std::uint64_t h = random::splitmix64_next(x);
  for (const std::uint64_t index : {cell, heading, replicate}) {
    std::uint64_t y = h ^ index;
    h = random::splitmix64_next(y);
  }
  return h >> 1;  // [scene] seed is a TOML integer: 0 … INT64_MAX
}

}  // namespace gyrostab::tools::sweep
