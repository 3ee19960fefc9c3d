// libFuzzer target for the scene parser: arbitrary bytes as a scene text through the path of
// `gyrostab check` (SceneReader::parse, the [scene] device's scene validation and the controller's start-up
// check; nothing is built or run). Refusing an input is a normal outcome; a crash, a sanitizer report, an
// uncaught exception, a timeout or unbounded memory is a finding.
// Invariants checked beyond "no crash": the exit code is 0 (valid) or 2 (refused), and a scene is refused
// exactly when at least one problem was reported (no silent refusal, no accepted scene with problems).
// Built only with -DGYROSTAB_FUZZ=ON and clang; run it with tools/fuzz/run-scene-fuzz.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tools/commands.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> problems;
  const int rc = gyrostab::tools::check_scene_text(text, "fuzz.toml", &problems);
  if (rc != 0 && rc != 2) __builtin_trap();
  if ((rc == 0) != problems.empty()) __builtin_trap();
  return 0;
}
