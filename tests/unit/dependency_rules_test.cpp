// The dependency rules of docs/architecture.md, checked on the source tree: firmware/ includes none of sim/,
// hil/, tools/; sim/ includes neither tools/ nor hil/ nor a JSON library; the accuracy study's framework
// (tools/accuracy/) includes no device; and the project stands alone — no file cites the private library it
// was written from, and no comment cites an issue number.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace gyrostab {
namespace {

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

// file:line of every line of the files that matches.
std::vector<std::string> matches(const std::vector<fs::path>& files, const std::regex& re) {
  std::vector<std::string> out;
  for (const fs::path& p : files) {
    std::istringstream in(read(p));
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      if (std::regex_search(line, re)) out.push_back(fs::relative(p, kRoot).string() + ":" + std::to_string(n));
    }
  }
  return out;
}

const std::vector<std::string> kCode = {".hpp", ".cpp", ".h"};

TEST(DependencyRules, FirmwareIncludesOnlyFirmware) {
  const auto bad = matches(files_under("firmware", kCode), std::regex(R"(^\s*#\s*include\s*[<"](sim|hil|tools)/)"));
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, SimIncludesNeitherToolsNorHilNorJson) {
  const auto bad =
      matches(files_under("sim", kCode), std::regex(R"(^\s*#\s*include\s*[<"]((tools|hil)/|nlohmann/))"));
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, TheAccuracyFrameworkIncludesNoDevice) {
  const auto bad = matches(files_under("tools/accuracy", kCode), std::regex(R"(^\s*#\s*include\s*"tools/devices/[a-z_]+/)"));
  EXPECT_TRUE(bad.empty()) << bad.front();
}

TEST(DependencyRules, TheProjectStandsAlone) {
  std::vector<fs::path> files;
  for (const char* dir : {"firmware", "sim", "hil", "tools", "tests", "docs", ".ci"}) {
    for (const fs::path& p : files_under(dir, {".hpp", ".cpp", ".h", ".md", ".py", ".toml", ".txt", ".lcm", ""})) {
      // The fuzz corpora keep their inputs as found; this file names what it looks for.
      if (p.string().find("/corpus") == std::string::npos && p.filename() != "dependency_rules_test.cpp") {
        files.push_back(p);
      }
    }
  }
  files.push_back(kRoot / "README.md");
  files.push_back(kRoot / "CMakeLists.txt");
  const auto shared = matches(files, std::regex(R"(\.\./shared|\bdigest\b|DESIGN §|DESIGN\.md)", std::regex::icase));
  EXPECT_TRUE(shared.empty()) << shared.size() << " places cite the private library, first " << shared.front();
  const auto issues = matches(files, std::regex(R"(\bissue [0-9]+)", std::regex::icase));
  EXPECT_TRUE(issues.empty()) << issues.size() << " places cite an issue number, first " << issues.front();
}

}  // namespace
}  // namespace gyrostab
