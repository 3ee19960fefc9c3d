// `gyrostab sweep STUDY.toml --out DIR [--jobs N] [--shard I/N] [--quiet]`: runs a sizing study's tasks in
// this process on N threads, one task file each (task_store.hpp), reusing the valid ones already in DIR, then
// merges (merge.hpp) unless it ran one shard. Exit codes: merge.hpp. Docs: docs/sweep.md.
#pragma once

#include <string>

namespace gyrostab::tools::sweep {

struct SweepRequest {
  std::string study_path;
  std::string out_dir;
  int jobs{0};        // 0: the number of cores
  std::string shard;  // "I/N", empty: the whole study
  bool quiet{false};
  // --view [ADDR:PORT]: the sweep's live view (tools/view/sweep_view.hpp)
  bool view{false};
  std::string view_address;
  double view_linger_s{-1};
};

int run_sweep(const SweepRequest& request);

// "I/N" with 1 <= I <= N: true with index = I − 1 and count = N.
bool parse_shard(const std::string& text, long& index, long& count);

}  // namespace gyrostab::tools::sweep
