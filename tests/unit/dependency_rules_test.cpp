// The dependency rules of docs/architecture.md, checked on the source tree: firmware/ includes none of sim/,
// hil/, tools/; sim/ includes neither tools/ nor hil/ nor a JSON library, and of firmware/ only the messages
// (firmware/msg/: the contract, not a law); inside tools/, the loop and the device interface (tools/loop/,
// tools/devices/*.hpp) lie below both the devices and the run modes: no device includes a run mode
// (tools/run/), the loop includes neither, and a run mode reaches a device only through its interface (never a
// device's folder); the accuracy study's framework
// (tools/accuracy/) includes no device; and the project stands alone — no file cites the private library it
// was written from, and no comment cites an issue number.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <cctype>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace gyrostab {
namespace dependency_rules_test {

namespace fs = std::filesystem;
const fs::path kRoot = GYROSTAB_SOURCE_DIR;

std::vector<fs::path> files_under(const std::string& dir, const std::vector<std::string>& exts) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(kRoot / dir)) {
    if (!e.is_regular_file()) continue;
    const std::string ext = e.path().extension().string();
    for (const std::string& x : exts) {
      if (ext == x) out.push_back(e.path());
    }
  }
  return out;
}

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Plain string matching, not std::regex: <regex> trips GCC 12's -Wmaybe-uninitialized under the sanitizers.
using LineRule = std::function<bool(const std::string&)>;

// file:line of every line of the files that the rule matches.
std::vector<std::string> matches(const std::vector<fs::path>& files, const LineRule& rule) {
  std::vector<std::string> out;
  for (const fs::path& p : files) {
    std::istringstream in(read(p));
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (rule(line)) out.push_back(fs::relative(p, kRoot).string() + ":" + std::to_string(n));
    }
  }
  return out;
}

// The path of a line `#include <...>` or `#include "..."` (spaces allowed around '#'), or "" for any other line.
std::string included_path(const std::string& line) {
  std::size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line[i] != '#') return "";
  i = line.find_first_not_of(" \t", i + 1);
  if (i == std::string::npos || line.compare(i, 7, "include") != 0) return "";
  i = line.find_first_not_of(" \t", i + 7);
  if (i == std::string::npos || (line[i] != '<' && line[i] != '"')) return "";
  return line.substr(i + 1);
}

LineRule includes_any_of(std::vector<std::string> prefixes) {
  return [prefixes = std::move(prefixes)](const std::string& line) {
    const std::string path = included_path(line);
    return std::any_of(prefixes.begin(), prefixes.end(),
                       [&](const std::string& pre) { return !path.empty() && path.rfind(pre, 0) == 0; });
  };
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Case-insensitive: `word` stands in the line with no letter, digit or '_' right before it (and, when
// `digit_after`, a digit right after it; otherwise no word character after it).
bool has_word(const std::string& line, const std::string& word, bool digit_after = false) {
  const std::string l = lower(line);
  for (std::size_t i = l.find(word); i != std::string::npos; i = l.find(word, i + 1)) {
    if (i > 0 && word_char(l[i - 1])) continue;
    const std::size_t end = i + word.size();
    const bool at_end = end >= l.size();
    if (digit_after ? (!at_end && std::isdigit(static_cast<unsigned char>(l[end]))) : (at_end || !word_char(l[end]))) {
      return true;
    }
  }
  return false;
}

const std::vector<std::string> kCode = {".hpp", ".cpp", ".h"};

TEST(DependencyRules, FirmwareIncludesOnlyFirmware) {
  const auto bad = matches(files_under("firmware", kCode), includes_any_of({"sim/", "hil/", "tools/"}));
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, SimIncludesNeitherToolsNorHilNorJson) {
  const auto bad =
      matches(files_under("sim", kCode), includes_any_of({"tools/", "hil/", "nlohmann/"}));
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, SimTakesOnlyTheMessagesFromFirmware) {
  const auto bad = matches(files_under("sim", kCode), [](const std::string& line) {
    const std::string path = included_path(line);
    return path.rfind("firmware/", 0) == 0 && path.rfind("firmware/msg/", 0) != 0;
  });
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, NoDeviceIncludesARunMode) {
  const auto bad = matches(files_under("tools/devices", kCode), includes_any_of({"tools/run/"}));
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, TheLoopIncludesNeitherRunModesNorDevices) {
  const auto bad = matches(files_under("tools/loop", kCode), includes_any_of({"tools/run/", "tools/devices/"}));
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, RunModesReachDevicesOnlyThroughTheirInterface) {
  // tools/devices/device.hpp, registry.hpp, device_scene_of.hpp: yes; tools/devices/<device>/...: no.
  const auto bad = matches(files_under("tools/run", kCode), [](const std::string& line) {
    const std::string path = included_path(line);
    return path.rfind("tools/devices/", 0) == 0 && path.find('/', 14) != std::string::npos &&
           path.find('/', 14) < path.find_first_of("\">");
  });
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, TheAccuracyFrameworkIncludesNoDevice) {
  const auto bad = matches(files_under("tools/accuracy", kCode), [](const std::string& line) {
    const std::string path = included_path(line);
    return path.rfind("tools/devices/", 0) == 0 && path.find('/', 14) != std::string::npos;
  });
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, TheProjectStandsAlone) {
  std::vector<fs::path> files;
  for (const char* dir : {"firmware", "sim", "hil", "tools", "tests", "docs", ".ci"}) {
    for (const fs::path& p : files_under(dir, {".hpp", ".cpp", ".h", ".md", ".py", ".toml", ".txt", ".lcm", ""})) {
      // The binary fuzz corpora keep their inputs as found; the scene corpus (tests/fuzz/corpus/*.toml) is text
      // a reader opens, so it stands alone like every other file. This file names what it looks for.
      const bool binary_corpus =
          p.string().find("_corpus") != std::string::npos ||
          (p.string().find("/corpus") != std::string::npos && p.extension() != ".toml");
      if (!binary_corpus && p.filename() != "dependency_rules_test.cpp") {
        files.push_back(p);
      }
    }
  }
  files.push_back(kRoot / "README.md");
  files.push_back(kRoot / "CMakeLists.txt");
  const auto shared = matches(files, [](const std::string& line) {
    const std::string l = lower(line);
    return l.find("../shared") != std::string::npos || has_word(line, "digest") ||
           l.find("design §") != std::string::npos || l.find("design.md") != std::string::npos;
  });
  EXPECT_TRUE(shared.empty()) << shared.size() << " places cite the private library, first " << shared.front();
  const auto issues = matches(files, [](const std::string& line) { return has_word(line, "issue ", true); });
  EXPECT_TRUE(issues.empty()) << issues.size() << " places cite an issue number, first " << issues.front();
}

}  // namespace dependency_rules_test
}  // namespace gyrostab
