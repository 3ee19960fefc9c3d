// The sweep's progress on stderr. On a terminal: one line redrawn in place — a bar, tasks done of total,
// failures, elapsed and estimated time left — at most 4 times a second (the caller polls; the bar drops
// calls that come sooner). Off a terminal (CI, logs): one plain line each time another tenth of the tasks is
// done. Quiet: nothing.
#pragma once

#include <chrono>
#include <cstdint>

namespace gyrostab::tools::sweep {

class ProgressBar {
 public:
  ProgressBar(std::int64_t total, bool quiet);
  void update(std::int64_t done, std::int64_t failed);
  // The last state, and the line cleared on a terminal.
  void finish(std::int64_t done, std::int64_t failed);

 private:
  void draw(std::int64_t done, std::int64_t failed);

  std::int64_t total_;
  bool quiet_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_{};
  int last_tenth_{0};
};

}  // namespace gyrostab::tools::sweep
