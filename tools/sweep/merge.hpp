// `gyrostab sweep merge DIR`: reads every task file a study directory should hold (DIR/study.json says
// which), checks each against its task's definition, and writes per variant DIR/results/<variant>/cells.csv,
// cells.json (one row per cell × heading: the mean over replicates of each figure), summary.json
// (probability-weighted means, the exceedance of each roll criterion and the operability it leaves, the
// probability left out because its tasks failed or are missing) and two heat maps over (Hs, Tp); and
// DIR/results/summary.csv (a row per variant). The results depend only on the task files' results, in the
// study's fixed order, printed at round-trip precision: any split into shards, any order, any --jobs gives the
// same bytes. The timings go to DIR/timing.json, apart. results/ is replaced as a whole.
#pragma once

#include <string>

namespace gyrostab::tools::sweep {

// Exit codes of `gyrostab sweep` and `gyrostab sweep merge`.
inline constexpr int kSweepOk = 0;
inline constexpr int kSweepRefused = 2;        // bad study file, options or directory: nothing written
inline constexpr int kSweepTasksFailed = 3;    // some tasks refused or diverged (the rest merged)
inline constexpr int kSweepIncomplete = 4;     // merge: tasks missing or unusable; results for what is there

int merge_study_dir(const std::string& dir, bool quiet);

}  // namespace gyrostab::tools::sweep
