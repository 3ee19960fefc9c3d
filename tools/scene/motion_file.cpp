#include "tools/scene/motion_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace gyrostab::tools {
namespace {

namespace fs = std::filesystem;

// `p` lies in `root` (both canonical): a component-wise prefix, so /a/bc is not inside /a/b.
bool inside(const fs::path& p, const fs::path& root) {
  auto r = root.begin();
  for (auto it = p.begin(); r != root.end(); ++it, ++r) {
    if (it == p.end() || *it != *r) return false;
  }
  return true;
}

}  // namespace

std::shared_ptr<const motion::MotionRecord> load_motion_file(const std::string& file, const std::string& file_root,
                                                             const MotionCsvLimits& limits,
                                                             std::vector<std::string>& problems) {
  if (file_root.empty()) {
    problems.push_back("a scene given as text, not read from a file, cannot name a motion file");
    return nullptr;
  }
  const fs::path rel(file);
  if (rel.empty() || rel.is_absolute() || rel.has_root_name()) {
    problems.push_back("'" + file + "': give a path relative to the scene file's directory");
    return nullptr;
  }
  if (rel.extension() != ".csv") {
    problems.push_back("'" + file + "': a motion record is a .csv file");
    return nullptr;
  }
  // Canonical forms (symbolic links and .. resolved) before the check, so neither can lead out of the roots.
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(fs::path(file_root), ec);
  const fs::path records = fs::weakly_canonical(fs::path(file_root) / ".." / "motion_records", ec);
  const fs::path path = fs::weakly_canonical(fs::path(file_root) / rel, ec);
  if (ec || !(inside(path, root) || inside(path, records))) {
    problems.push_back("'" + file + "' leads outside the scene's directory and the motion_records/ directory beside it");
    return nullptr;
  }
  if (!fs::is_regular_file(path, ec)) {
    problems.push_back("'" + file + "': no such file (looked for " + path.string() + ")");
    return nullptr;
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size > kMaxMotionFileBytes) {
    problems.push_back("'" + file + "': " + std::to_string(size) + " bytes, more than a motion record may be (" +
                       std::to_string(kMaxMotionFileBytes) + ")");
    return nullptr;
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) {
    problems.push_back("'" + file + "': cannot read " + path.string());
    return nullptr;
  }
  auto record = std::make_shared<motion::MotionRecord>();
  if (!parse_motion_csv(text.str(), file, limits, *record, problems)) return nullptr;
  return record;
}

}  // namespace gyrostab::tools
