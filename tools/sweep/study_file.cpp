#include "tools/sweep/study_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "tools/scene/toml_limits.hpp"
#include "tools/scene/toml_parser.hpp"

namespace gyrostab::tools::sweep {
namespace {

constexpr int kMaxSeedsPerCell = 10000;
constexpr std::size_t kMaxCells = 100000;
constexpr std::size_t kMaxVariants = 1000;
// The study's task count, cells × headings × seeds × variants: each factor within its own limit can still
// multiply to a list the machine cannot hold (1e9 tasks); a study is refused before anything is written.
constexpr std::int64_t kMaxTasks = 1'000'000;

// Collects problems with the file and line of the node they concern.
class Problems {
 public:
  Problems(std::string file, std::vector<std::string>& out) : file_(std::move(file)), out_(out) {}
  void add(const toml::node* n, const std::string& where, const std::string& why) {
    std::ostringstream s;
    s << file_;
    if (n != nullptr && n->source().begin.line > 0) s << ":" << n->source().begin.line;
    s << ": " << where << ": " << why;
    out_.push_back(s.str());
    ++count_;
  }
  int count() const { return count_; }

 private:
  std::string file_;
  std::vector<std::string>& out_;
  int count_{0};
};

std::string describe(const toml::node& n) {
  std::ostringstream s;
  if (n.is_string()) {
    s << '"' << n.value_or(std::string_view{}) << '"';
  } else if (n.is_table()) {
    s << "a table";
  } else if (n.is_array()) {
    s << "an array";
  } else {
    n.visit([&s](const auto& v) { s << v; });
  }
  return s.str();
}

// A finite number (TOML integer or float) in [lo, hi] (lo open if lo_open); nullopt with the problem added.
std::optional<double> number(const toml::node* n, const std::string& where, Problems& p, double lo, bool lo_open,
                             double hi, const std::string& range) {
  std::optional<double> v;
  if (n->is_floating_point()) v = n->as_floating_point()->get();
  if (n->is_integer()) v = static_cast<double>(n->as_integer()->get());
  if (!v) {
    p.add(n, where, "= " + describe(*n) + " must be a number");
    return std::nullopt;
  }
  if (!std::isfinite(*v) || (lo_open ? !(*v > lo) : !(*v >= lo)) || !(*v <= hi)) {
    p.add(n, where, "= " + describe(*n) + " is out of range: must be " + range);
    return std::nullopt;
  }
  return v;
}

std::optional<std::int64_t> integer(const toml::node* n, const std::string& where, Problems& p, std::int64_t lo,
                                    std::int64_t hi) {
  if (!n->is_integer()) {
    p.add(n, where, "= " + describe(*n) + " must be an integer");
    return std::nullopt;
  }
  const std::int64_t v = n->as_integer()->get();
  if (v < lo || v > hi) {
    p.add(n, where, "= " + std::to_string(v) + " is out of range: must be in [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
    return std::nullopt;
  }
  return v;
}

std::optional<std::string> text(const toml::node* n, const std::string& where, Problems& p) {
  if (!n->is_string()) {
    p.add(n, where, "= " + describe(*n) + " must be a string");
    return std::nullopt;
  }
  return std::string(n->as_string()->get());
}

// Keys of `t` that are not in `known`: each a problem.
void refuse_unknown(const toml::table& t, const std::string& table, std::initializer_list<std::string_view> known,
                    Problems& p) {
  for (auto&& [k, node] : t) {
    bool ok = false;
    for (std::string_view name : known) ok = ok || k.str() == name;
    if (ok) continue;
    std::string list;
    for (std::string_view name : known) list += (list.empty() ? "" : ", ") + std::string(name);
    p.add(&node, table + " " + std::string(k.str()), "unknown key (known: " + list + ")");
  }
}

const toml::node* required(const toml::table& t, std::string_view key, const std::string& where, Problems& p) {
  const toml::node* n = t.get(key);
  if (n == nullptr) p.add(&t, where, "is missing (required)");
  return n;
}

std::vector<double> numbers(const toml::node* n, const std::string& where, Problems& p, double lo, double hi,
                            const std::string& range) {
  std::vector<double> out;
  const toml::array* a = n->as_array();
  if (a == nullptr) {
    p.add(n, where, "= " + describe(*n) + " must be an array of numbers");
    return out;
  }
  if (a->empty()) p.add(n, where, "is empty (leave the key out for the scene's own value)");
  for (std::size_t i = 0; i < a->size(); ++i) {
    if (auto v = number(a->get(i), where + "[" + std::to_string(i) + "]", p, lo, false, hi, range)) out.push_back(*v);
  }
  return out;
}

void read_study_table(const toml::table& t, Study& s, Problems& p, std::string& scene) {
  const std::string w = "[study] ";
  refuse_unknown(t, "[study]",
                 {"name", "scene", "seed", "seeds_per_cell", "duration_s", "settle_s", "headings_deg",
                  "heading_probability"},
                 p);
  if (const toml::node* n = required(t, "name", w + "name", p)) {
    if (auto v = text(n, w + "name", p)) s.name = *v;
  }
  if (const toml::node* n = required(t, "scene", w + "scene", p)) {
    if (auto v = text(n, w + "scene", p)) scene = *v;
  }
  if (const toml::node* n = required(t, "seed", w + "seed", p)) {
    if (auto v = integer(n, w + "seed", p, 0, INT64_MAX)) s.seed = static_cast<std::uint64_t>(*v);
  }
  if (const toml::node* n = t.get("seeds_per_cell")) {
    if (auto v = integer(n, w + "seeds_per_cell", p, 1, kMaxSeedsPerCell)) s.seeds_per_cell = static_cast<int>(*v);
  }
  if (const toml::node* n = t.get("duration_s")) s.duration_s = number(n, w + "duration_s", p, 0.0, true, 1e7, "> 0 [s]");
  if (const toml::node* n = t.get("settle_s")) s.settle_s = number(n, w + "settle_s", p, 0.0, false, 1e7, ">= 0 [s]");
  if (s.duration_s && s.settle_s && *s.settle_s > *s.duration_s) {
    p.add(t.get("settle_s"), w + "settle_s", "is longer than duration_s (no statistics would remain)");
  }
  if (const toml::node* n = t.get("headings_deg")) {
    s.headings_deg = numbers(n, w + "headings_deg", p, -360.0, 360.0, "in [-360, 360] [deg]");
    std::set<double> seen(s.headings_deg.begin(), s.headings_deg.end());
    if (seen.size() != s.headings_deg.size()) p.add(n, w + "headings_deg", "holds a heading twice");
  }
  if (const toml::node* n = t.get("heading_probability")) {
    s.heading_probability = numbers(n, w + "heading_probability", p, 0.0, 1e300, ">= 0");
    if (s.headings_deg.empty()) {
      p.add(n, w + "heading_probability", "needs headings_deg");
    } else if (s.heading_probability.size() != s.headings_deg.size()) {
      p.add(n, w + "heading_probability",
            "has " + std::to_string(s.heading_probability.size()) + " values for " +
                std::to_string(s.headings_deg.size()) + " headings");
    } else {
      double sum = 0.0;
      for (double q : s.heading_probability) sum += q;
      if (!(sum > 0.0)) p.add(n, w + "heading_probability", "sums to 0");
    }
  } else if (!s.headings_deg.empty()) {
    s.heading_probability.assign(s.headings_deg.size(), 1.0);
  }
}

void read_sea_states(const toml::node* node, Study& s, Problems& p, const toml::table& root) {
  const toml::array* a = node ? node->as_array() : nullptr;
  if (node == nullptr) {
    p.add(&root, "[[sea_state]]", "is missing: the study needs at least one sea state");
    return;
  }
  if (a == nullptr || !a->is_array_of_tables()) {
    p.add(node, "sea_state", "must be [[sea_state]] tables");
    return;
  }
  if (a->empty()) p.add(node, "[[sea_state]]", "is empty");
  if (a->size() > kMaxCells) {
    p.add(node, "[[sea_state]]", "has more than " + std::to_string(kMaxCells) + " rows");
    return;
  }
  std::set<std::pair<double, double>> seen;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table& t = *a->get(i)->as_table();
    const std::string w = "[[sea_state]] #" + std::to_string(i + 1) + " ";
    refuse_unknown(t, "[[sea_state]] #" + std::to_string(i + 1), {"Hs", "Tp", "probability"}, p);
    SeaStateCell c;
    bool ok = true;
    const auto get = [&](std::string_view key, double lo, bool lo_open, const std::string& range, double& out) {
      const toml::node* n = required(t, key, w + std::string(key), p);
      std::optional<double> v = n ? number(n, w + std::string(key), p, lo, lo_open, 1e300, range) : std::nullopt;
      if (v) {
        out = *v;
      } else {
        ok = false;
      }
    };
    get("Hs", 0.0, true, "> 0 [m]", c.Hs_m);
    get("Tp", 0.0, true, "> 0 [s]", c.Tp_s);
    get("probability", 0.0, false, ">= 0", c.probability);
    if (ok && !seen.insert({c.Hs_m, c.Tp_s}).second) {
      p.add(&t, w + "Hs, Tp", "the same cell as an earlier row (Hs " + describe(*t.get("Hs")) + ", Tp " +
                                  describe(*t.get("Tp")) + ")");
    }
    s.cells.push_back(c);
  }
  if (p.count() == 0 && !(s.probability_sum() > 0.0)) {
    p.add(node, "[[sea_state]] probability", "sums to 0: no cell has weight");
  }
}

bool read_setting(const std::string& section, const std::string& key, const toml::node& v, const std::string& w,
                  Variant& out, Problems& p) {
  const std::string full = section + "." + key;
  if (section.empty() || key.empty() || key.find('.') != std::string::npos) {
    p.add(&v, w + "set", "\"" + full + "\" is not a scene key \"table.key\"");
    return false;
  }
  if (study_owns_key(section, key)) {
    p.add(&v, w + "set", "\"" + full + "\" is set by the study itself (docs/sweep.md), not by a variant");
    return false;
  }
  SceneValue value;
  if (v.is_boolean()) {
    value = v.as_boolean()->get();
  } else if (v.is_integer()) {
    value = v.as_integer()->get();
  } else if (v.is_floating_point()) {
    value = v.as_floating_point()->get();
  } else if (v.is_string()) {
    value = std::string(v.as_string()->get());
  } else {
    p.add(&v, w + "set", "\"" + full + "\" = " + describe(v) + ": a variant sets numbers, booleans or strings");
    return false;
  }
  for (const SceneSetting& s : out.set) {
    if (s.section == section && s.key == key) {
      p.add(&v, w + "set", "\"" + full + "\" is set twice");
      return false;
    }
  }
  out.set.push_back({section, key, value});
  return true;
}

void read_variants(const toml::node* node, Study& s, Problems& p, const toml::table& root) {
  const toml::array* a = node ? node->as_array() : nullptr;
  if (node == nullptr) {
    p.add(&root, "[[variant]]", "is missing: the study needs at least one variant");
    return;
  }
  if (a == nullptr || !a->is_array_of_tables()) {
    p.add(node, "variant", "must be [[variant]] tables");
    return;
  }
  if (a->empty()) p.add(node, "[[variant]]", "is empty");
  if (a->size() > kMaxVariants) {
    p.add(node, "[[variant]]", "has more than " + std::to_string(kMaxVariants) + " rows");
    return;
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table& t = *a->get(i)->as_table();
    const std::string w = "[[variant]] #" + std::to_string(i + 1) + " ";
    refuse_unknown(t, "[[variant]] #" + std::to_string(i + 1), {"name", "set"}, p);
    Variant v;
    if (const toml::node* n = required(t, "name", w + "name", p)) {
      if (auto name = text(n, w + "name", p)) {
        v.name = *name;
        if (const std::string why = variant_name_problem(v.name); !why.empty()) {
          p.add(n, w + "name", "\"" + v.name + "\" " + why);
        } else if (!names.insert(v.name).second) {
          p.add(n, w + "name", "\"" + v.name + "\" names an earlier variant too");
        }
      }
    }
    if (const toml::node* n = t.get("set")) {
      const toml::table* set = n->as_table();
      if (set == nullptr) {
        p.add(n, w + "set", "= " + describe(*n) + " must be a table { \"table.key\" = value, ... }");
      } else {
        for (auto&& [k, value] : *set) {
          const std::string key(k.str());
          if (const toml::table* inner = value.as_table()) {  // set = { gyro.H = 1 }: a dotted key
            for (auto&& [k2, v2] : *inner) read_setting(key, std::string(k2.str()), v2, w, v, p);
            continue;
          }
          const std::size_t dot = key.find('.');
          read_setting(dot == std::string::npos ? "" : key.substr(0, dot),
                       dot == std::string::npos ? key : key.substr(dot + 1), value, w, v, p);
        }
      }
    }
    s.variants.push_back(std::move(v));
  }
}

// The base scene: it exists, parses, and is a ship roll damper in an irregular sea.
void read_base_scene(const std::string& study_path, const std::string& scene, const toml::table& study_table,
                     Study& s, Problems& p) {
  const toml::node* n = study_table.get("scene");
  const std::filesystem::path base = std::filesystem::path(study_path).parent_path();
  const std::filesystem::path path =
      std::filesystem::path(scene).is_absolute() ? std::filesystem::path(scene) : base / scene;
  s.scene_file = scene;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) {
    p.add(n, "[study] scene", "\"" + scene + "\": cannot read " + path.string() + " (" + ec.message() + ")");
    return;
  }
  if (size > kMaxSceneBytes) {
    p.add(n, "[study] scene", path.string() + " is larger than a scene may be");
    return;
  }
  std::ifstream f(path, std::ios::binary);
  std::ostringstream text;
  text << f.rdbuf();
  s.scene_text = text.str();
  if (const std::string why = toml_limits_problem(s.scene_text, path.string()); !why.empty()) {
    p.add(n, "[study] scene", why);
    return;
  }
  toml::table root;
  try {
    root = toml::parse(s.scene_text, path.string());
  } catch (const toml::parse_error& e) {
    p.add(n, "[study] scene", path.string() + ":" + std::to_string(e.source().begin.line) +
                                  ": not valid TOML: " + std::string(e.description()));
    return;
  }
  const std::string device(root["scene"]["device"].value_or(std::string_view{}));
  const std::string kind(root["sea"]["kind"].value_or(std::string_view{"jonswap"}));
  if (device != "ship_roll_damper") {
    p.add(n, "[study] scene",
          path.string() + " is a \"" + device + "\" scene; a sweep runs a ship_roll_damper scene in an irregular sea");
  } else if (kind != "jonswap" && kind != "pierson_moskowitz") {
    p.add(n, "[study] scene",
          path.string() + " has [sea] kind = \"" + kind +
              "\"; a sweep sets Hs and Tp of an irregular sea (jonswap or pierson_moskowitz)");
  }
}

}  // namespace

bool study_owns_key(const std::string& section, const std::string& key) {
  static constexpr std::pair<std::string_view, std::string_view> kOwned[] = {
      {"scene", "seed"}, {"scene", "duration_s"}, {"scene", "device"},        {"report", "settle_s"},
      {"sea", "Hs"},     {"sea", "Tp"},           {"sea", "kind"},            {"course", "heading_deg"}};
  for (const auto& [s, k] : kOwned) {
    if (s == section && k == key) return true;
  }
  return false;
}

bool read_study_file(const std::string& path, Study& study, std::vector<std::string>& problems) {
  Problems p(path, problems);
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || !std::filesystem::is_regular_file(path)) {
    problems.push_back(path + ": cannot read the study file" + (ec ? " (" + ec.message() + ")" : ""));
    return false;
  }
  if (size > kMaxSceneBytes) {
    problems.push_back(path + ": " + std::to_string(size) + " bytes, larger than a study file may be (" +
                       std::to_string(kMaxSceneBytes) + ")");
    return false;
  }
  std::ifstream f(path, std::ios::binary);
  std::ostringstream buffer;
  buffer << f.rdbuf();
  const std::string text = buffer.str();
  if (const std::string why = toml_limits_problem(text, path); !why.empty()) {
    problems.push_back(why);
    return false;
  }
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    problems.push_back(path + ":" + std::to_string(e.source().begin.line) + ":" +
                       std::to_string(e.source().begin.column) + ": not valid TOML: " + std::string(e.description()));
    return false;
  }
  Study s;
  for (auto&& [k, node] : root) {
    const std::string_view key = k.str();
    if (key != "study" && key != "sea_state" && key != "variant") {
      p.add(&node, std::string(key), "unknown table (known: [study], [[sea_state]], [[variant]])");
    }
  }
  const toml::table* study_table = root.get_as<toml::table>("study");
  std::string scene;
  if (study_table == nullptr) {
    p.add(root.get("study"), "[study]", "is missing or not a table");
  } else {
    read_study_table(*study_table, s, p, scene);
  }
  read_sea_states(root.get("sea_state"), s, p, root);
  read_variants(root.get("variant"), s, p, root);
  if (study_table != nullptr && !scene.empty()) read_base_scene(path, scene, *study_table, s, p);
  // Each factor is bounded (cells 1e5, seeds 1e4, variants 1e3, headings by the file's size), so the product
  // fits an int64 without overflow.
  const std::int64_t cells = static_cast<std::int64_t>(s.cells.size()), headings = s.heading_count(),
                     seeds = s.seeds_per_cell, variants = static_cast<std::int64_t>(s.variants.size());
  const std::int64_t tasks = cells * headings * seeds * variants;
  if (tasks > kMaxTasks) {
    p.add(study_table, "[study]",
          "cells × headings × seeds_per_cell × variants = " + std::to_string(cells) + " × " +
              std::to_string(headings) + " × " + std::to_string(seeds) + " × " + std::to_string(variants) + " = " +
              std::to_string(tasks) + " tasks, more than " + std::to_string(kMaxTasks) +
              ": split the study into several");
  }
  if (p.count() > 0) return false;
  study = std::move(s);
  return true;
}

}  // namespace gyrostab::tools::sweep
