// Limits on a TOML text, checked before the TOML parser sees it. toml++ descends recursively into dotted
// table headers, dotted keys, inline tables and arrays, so a hostile file (a header 200 000 levels deep is
// 400 KB) overflows the stack; and it builds the whole document in memory before the scene reader can refuse
// an unknown section, so a 50 MB array costs gigabytes. A scene is a few kilobytes with at most three levels
// (section, key, an array of numbers), so the limits leave room by orders of magnitude and are never a
// scene author's concern: every scene file and every scene embedded in a bus log passes through them.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace gyrostab::tools {

inline constexpr std::size_t kMaxSceneBytes = 1u << 20;  // 1 MiB
inline constexpr int kMaxTomlNesting = 32;               // header components + key components + brackets

// "" if `text` is within the limits, else the problem as "name:line: ..." (the first line that goes deeper
// than kMaxTomlNesting, or the size).
std::string toml_limits_problem(std::string_view text, const std::string& name);

// The deepest nesting of `text` as counted for kMaxTomlNesting (tests, and the message).
int toml_nesting_depth(std::string_view text, int* line_of_max = nullptr);

}  // namespace gyrostab::tools
