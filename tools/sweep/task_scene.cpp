#include <sstream>

#include "tools/scene/toml_parser.hpp"
#include "tools/sweep/task.hpp"

namespace gyrostab::tools::sweep {
namespace {

void set(toml::table& root, const std::string& section, const std::string& key, const SceneValue& value) {
  toml::node* n = root.get(section);
  if (n == nullptr) n = &root.insert_or_assign(section, toml::table{}).first->second;
  toml::table* t = n->as_table();
  if (t == nullptr) return;  // not a [section]: the reader refuses the scene with its own message
  std::visit([&](const auto& v) { t->insert_or_assign(key, v); }, value);
}

}  // namespace

std::string task_scene_text(const Study& s, const Task& t) {
  toml::table root;
  try {
    root = toml::parse(s.scene_text, s.scene_file);
  } catch (const toml::parse_error&) {
    return "";
  }
  const SeaStateCell& cell = s.cells[static_cast<std::size_t>(t.cell)];
  if (s.duration_s) set(root, "scene", "duration_s", *s.duration_s);
  if (s.settle_s) set(root, "report", "settle_s", *s.settle_s);
  set(root, "sea", "Hs", cell.Hs_m);
  set(root, "sea", "Tp", cell.Tp_s);
  if (!s.headings_deg.empty()) set(root, "course", "heading_deg", s.headings_deg[static_cast<std::size_t>(t.heading)]);
  set(root, "scene", "seed", static_cast<std::int64_t>(t.seed(s)));
  for (const SceneSetting& k : s.variants[static_cast<std::size_t>(t.variant)].set) set(root, k.section, k.key, k.value);
  std::ostringstream out;
  out << root << "\n";
  return out.str();
}

}  // namespace gyrostab::tools::sweep
