// Scene files as text, for tests that run a variant of a shipped scene: the whole file, and the file with one
// key's text replaced (a replacement that finds nothing fails the calling test).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace gyrostab::testing {

inline std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

inline std::string replaced(std::string t, const std::string& from, const std::string& to) {
  const auto at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) t.replace(at, from.size(), to);
  return t;
}

}  // namespace gyrostab::testing
