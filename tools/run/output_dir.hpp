// Where a run writes, and how: the output directory is checked before the run starts (it must be, or become,
// a writable directory outside /proc, /sys and /dev), every output file is first written under a staging
// directory inside it and moved into place only when the whole set is complete, and the helpers that draw the
// figures run with an argument vector (posix_spawn), never through a shell. So a run whose output path holds
// shell syntax or an apostrophe writes exactly there; a failed or interrupted run never leaves its new report
// beside an older run's CSV or figure; nothing is written outside the directory asked for.
#pragma once

#include <string>
#include <vector>

namespace gyrostab::tools {

// Creates `dir` (and its parents) if needed and checks that it is a directory this process can write, and not
// inside /proc, /sys or /dev. false with `error` set (what is wrong, with the path) otherwise.
bool check_output_dir(const std::string& dir, std::string& error);

// One run's output files, staged in `dir`/.staging-<pid> and moved into `dir` together by commit(). Files of
// this kind of output (`kind`, e.g. report.json, signals.csv, signals.png) that the run did not produce are
// removed from `dir` at commit, so the directory never mixes two runs. The staging directory is removed
// when the set is dropped uncommitted.
class OutputSet {
 public:
  OutputSet(std::string dir, std::vector<std::string> kind);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  bool open(std::string& error);
  // The staging path of an output file (write it there; commit() moves it).
  std::string staged(const std::string& name) const { return staging_ + "/" + name; }
  const std::string& staging_dir() const { return staging_; }
  bool write(const std::string& name, const std::string& text, std::string& error);
  // Moves every staged file of `kind` into the directory and removes the ones not staged; `written` lists
  // the files now in place, in `kind` order.
  bool commit(std::vector<std::string>& written, std::string& error);

 private:
  std::string dir_;
  std::vector<std::string> kind_;
  std::string staging_;
  bool open_{false};
};

// Writes `text` to `path` through a temporary file beside it and a rename: readers see the old file or the
// whole new one, never a part.
bool write_file_atomic(const std::string& path, const std::string& text, std::string& error);

// Runs `argv` (argv[0] an absolute path) with posix_spawn and waits for it. Its exit code; -1 if it could not
// be started or was killed (`error` says which).
int run_program(const std::vector<std::string>& argv, std::string& error);

// "report.json, signals.csv and signals.png" style list for messages.
std::string list_names(const std::vector<std::string>& names);

}  // namespace gyrostab::tools
