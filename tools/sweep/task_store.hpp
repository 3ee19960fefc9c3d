// A study directory's task files: DIR/tasks/<variant>/c<cell>-h<heading>-r<replicate>.json, each written
// through a temporary file in the same directory, fsync'ed, then renamed over its name, so a reader (another
// shard, a merge, a rerun after a crash) sees no file or a whole one. A rerun reuses a task only when its
// file is whole and belongs to the same task definition; a stale or damaged file is reported and rerun.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "tools/sweep/study.hpp"
#include "tools/sweep/task.hpp"

namespace gyrostab::tools::sweep {

std::string task_dir(const std::string& dir, const Study& s, const Task& t);
std::string task_path(const std::string& dir, const Study& s, const Task& t);

// Writes `record` (its "timing" without "write_s") to `path`; `write_s` is the time to serialise, write and
// fsync it, stored in the file as timing.write_s. false with `error` if it could not be written.
bool write_task_file(const std::string& path, nlohmann::json record, double& write_s, std::string& error);

enum class Stored { kMissing, kValid, kStale, kCorrupt };

struct StoredTask {
  Stored state{Stored::kMissing};
  std::string why;        // for stale and corrupt files
  nlohmann::json record;  // for valid ones
};

// The task file at `path` checked against the task's definition hash.
StoredTask read_task_file(const std::string& path, const std::string& expected_hash);

// Writes `text` to `path` atomically (temporary file in the same directory, fsync, rename).
bool write_text_atomic(const std::string& path, const std::string& text, std::string& error);

}  // namespace gyrostab::tools::sweep
