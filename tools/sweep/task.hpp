// One task of a study: a variant in one sea (cell, heading) with one replicate seed. Tasks are numbered in
// one fixed order — cell, then heading, then replicate, then variant innermost — so that --shard I/N (the
// tasks whose index mod N is I − 1) gives every shard a share of every variant and every sea.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/sweep/study.hpp"
#include "tools/sweep/task_seed.hpp"

namespace gyrostab::tools::sweep {

struct Task {
  int variant{0};
  int cell{0};
  int heading{0};
  int replicate{0};
  std::int64_t index{0};

  std::uint64_t seed(const Study& s) const {
    return task_seed(s.seed, static_cast<std::uint64_t>(cell), static_cast<std::uint64_t>(heading),
                     static_cast<std::uint64_t>(replicate));
  }
  // "c3-h0-r1": the task file's name without ".json", and the scene's name in the reader's messages.
  std::string stem() const {
    return "c" + std::to_string(cell) + "-h" + std::to_string(heading) + "-r" + std::to_string(replicate);
  }
  // "H-0.7e6/c3-h0-r1"
  std::string label(const Study& s) const { return s.variants[static_cast<std::size_t>(variant)].name + "/" + stem(); }
};

inline std::vector<Task> all_tasks(const Study& s) {
  std::vector<Task> tasks;
  const int variants = static_cast<int>(s.variants.size());
  std::int64_t index = 0;
  for (int c = 0; c < static_cast<int>(s.cells.size()); ++c) {
    for (int h = 0; h < s.heading_count(); ++h) {
      for (int r = 0; r < s.seeds_per_cell; ++r) {
        for (int v = 0; v < variants; ++v) tasks.push_back({v, c, h, r, index++});
      }
    }
  }
  return tasks;
}

// The base scene with the task's keys set, as TOML text: [scene] duration_s and [report] settle_s (if the
// study sets them), [sea] Hs and Tp of the cell, [course] heading_deg (only if the study lists headings),
// [scene] seed, then the variant's keys. Never throws: a base scene that no longer parses gives "" (the
// reader then refuses the task).
std::string task_scene_text(const Study& s, const Task& t);

}  // namespace gyrostab::tools::sweep
