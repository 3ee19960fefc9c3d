// libFuzzer target for the bus log reader (tools/log/bus_log_reader.hpp): arbitrary bytes as a log file,
// opened (its scene parsed and checked, as `gyrostab replay` does) and read tick by tick to its end, before
// anything reaches a controller.
// Refusing an input is the normal outcome; a crash, a sanitizer report, an uncaught exception, a hang or
// unbounded memory is a finding. Invariants checked beyond "no crash": reading stops with exactly one of
// kEnd / kTruncated / kCorrupt; a refusal names a byte offset inside the file; kEnd means the end event's
// tick count equals the ticks read and the file ended there; a status, once final, stays final.
// Built only with -DGYROSTAB_FUZZ=ON and clang; run it with tools/fuzz/run-bus-log-fuzz.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "tools/commands.hpp"
#include "tools/log/bus_log_reader.hpp"

namespace {

using gyrostab::tools::buslog::BusLogReader;
using gyrostab::tools::buslog::ReadStatus;

// The input as a file LCM's log API can open by path, without touching the disk.
int g_fd = -1;

bool refused(ReadStatus s) {
  return s == ReadStatus::kTruncated || s == ReadStatus::kCorrupt;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (g_fd < 0) g_fd = memfd_create("bus_log_fuzz", 0);
  if (g_fd < 0) __builtin_trap();
  if (ftruncate(g_fd, 0) != 0 || pwrite(g_fd, data, size, 0) != static_cast<ssize_t>(size)) __builtin_trap();
  const std::string path = "/proc/self/fd/" + std::to_string(g_fd);

  BusLogReader r;
  ReadStatus s = r.open(path);
  if (s == ReadStatus::kOk) {
    // The scene the log carries goes where `gyrostab replay` sends it: through the size and nesting limits,
    // the TOML parser and every device's checks. A refusal must say why.
    std::vector<std::string> problems;
    if (gyrostab::tools::check_scene_text(r.scene().toml, "fuzzed-log", &problems) != 0 && problems.empty()) {
      __builtin_trap();
    }
  }
  if (s != ReadStatus::kOk) {
    if (!refused(s)) __builtin_trap();  // kUnreadable: the memfd is always readable
  } else {
    gyrostab::tools::buslog::TickRecord t;
    std::int64_t ticks = 0;
    while ((s = r.next(t)) == ReadStatus::kOk) {
      if (t.tick != ticks) __builtin_trap();
      ++ticks;
    }
    if (s == ReadStatus::kEnd) {
      if (r.end_event().ticks != ticks) __builtin_trap();
    } else if (!refused(s)) {
      __builtin_trap();
    }
    if (r.next(t) != s) __builtin_trap();  // final stays final
  }
  if (refused(s)) {
    if (r.problem().empty()) __builtin_trap();
    if (r.problem_offset() < 0 || r.problem_offset() > static_cast<std::int64_t>(size)) __builtin_trap();
  }
  return 0;
}
