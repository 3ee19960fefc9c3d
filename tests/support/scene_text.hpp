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

// The text without its comments (from '#' to the end of a line) and the spaces they leave at line ends.
inline std::string without_comments(const std::string& t) {
  std::string out;
  std::istringstream in(t);
  for (std::string line; std::getline(in, line);) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.pop_back();
    out += line;
    out += '\n';
  }
  return out;
}

// The text without the table [name]: its header and every line up to the next table (comments first removed,
// so that a unit in brackets does not end it); a table that is not there fails the calling test.
inline std::string without_table(const std::string& t, const std::string& name) {
  std::string out;
  std::istringstream in(without_comments(t));
  bool skipping = false, found = false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.front() == '[') {
      skipping = line == "[" + name + "]";
      found = found || skipping;
    }
    if (!skipping) {
      out += line;
      out += '\n';
    }
  }
  EXPECT_TRUE(found) << "[" << name << "]";
  return out;
}

}  // namespace gyrostab::testing
