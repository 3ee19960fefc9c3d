#include "tools/scene/scene_reader.hpp"

#include "tools/scene/scene_hash.hpp"

#include "tools/scene/toml_limits.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "tools/scene/toml_parser.hpp"

namespace gyrostab::tools {

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  std::ostringstream s;
  const bool has_lo = lo > -1e307, has_hi = hi < 1e307;
  if (has_lo && has_hi) {
    s << "in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
  } else if (has_lo) {
    s << (lo_open ? "> " : ">= ") << lo;
  } else if (has_hi) {
    s << (hi_open ? "< " : "<= ") << hi;
  } else {
    s << "finite";
  }
  return s.str();
}

struct SceneReader::Impl {
  toml::table root;
  std::set<std::string> used;  // "section.key" and "section"
};

std::string scene_file_dir(const std::string& scene_path) {
  const std::filesystem::path dir = std::filesystem::path(scene_path).parent_path();
  return dir.empty() ? std::string(".") : dir.string();
}

SceneReader::SceneReader() : impl_(std::make_unique<Impl>()) {}
SceneReader::~SceneReader() = default;
SceneReader::SceneReader(SceneReader&&) noexcept = default;
SceneReader& SceneReader::operator=(SceneReader&&) noexcept = default;

bool SceneReader::open(const std::string& path) {
  name_ = path;
  // Read here, not by toml::parse_file: a missing or oversized file gets its own message, and the text passes
  // the nesting limit before the parser sees it.
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) {
    errors_.push_back(path + ": cannot read the scene file (" + ec.message() + ")");
    return false;
  }
  if (size > kMaxSceneBytes) {
    errors_.push_back(path + ": " + std::to_string(size) + " bytes, larger than a scene may be (" +
                      std::to_string(kMaxSceneBytes) + " bytes); not parsed");
    return false;
  }
  std::ifstream f(path, std::ios::binary);
  std::ostringstream text;
  text << f.rdbuf();
  if (!f) {
    errors_.push_back(path + ": cannot read the scene file");
    return false;
  }
  file_root_ = scene_file_dir(path);
  return parse(text.str(), path);
}

bool SceneReader::parse(std::string_view text, const std::string& name) {
  name_ = name;
  text_hash_ = scene_hash(text);
  if (const std::string why = toml_limits_problem(text, name); !why.empty()) {
    errors_.push_back(why);
    return false;
  }
  try {
    impl_->root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << name << ":" << e.source().begin.line << ":" << e.source().begin.column << ": not valid TOML: "
      << e.description();
    errors_.push_back(s.str());
    return false;
  }
  return true;
}

namespace {

const toml::node* lookup(const toml::table& root, std::string_view section, std::string_view key) {
  const toml::table* t = root.get_as<toml::table>(section);
  return t ? t->get(key) : nullptr;
}

std::string where(const std::string& file, const toml::node* n) {
  std::ostringstream s;
  s << file;
  if (n && n->source().begin.line > 0) s << ":" << n->source().begin.line;
  return s.str();
}

}  // namespace

bool SceneReader::has_section(std::string_view section) const {
  return impl_->root.get_as<toml::table>(section) != nullptr;
}

bool SceneReader::has(std::string_view section, std::string_view key) const {
  return lookup(impl_->root, section, key) != nullptr;
}

void SceneReader::fail(std::string_view section, std::string_view key, const std::string& message) {
  const toml::node* n = lookup(impl_->root, section, key);
  std::ostringstream s;
  s << where(name_, n) << ": [" << section << "] " << key << ": " << message;
  errors_.push_back(s.str());
}

double SceneReader::number(std::string_view section, std::string_view key, double fallback, const Range& range,
                           std::string_view what) {
  impl_->used.insert(std::string(section));
  impl_->used.insert(std::string(section) + "." + std::string(key));
  const toml::node* n = lookup(impl_->root, section, key);
  if (!n) return fallback;
  std::optional<double> v;
  if (n->is_floating_point()) v = n->as_floating_point()->get();
  if (n->is_integer()) v = static_cast<double>(n->as_integer()->get());
  std::ostringstream s;
  if (!v) {
    s << "must be a number (" << what << ")";
    fail(section, key, s.str());
    return fallback;
  }
  if (!range.contains(*v)) {
    s << "= " << *v << " is out of range: must be " << range.describe() << " (" << what << ")";
    fail(section, key, s.str());
    return fallback;
  }
  return *v;
}

double SceneReader::required(std::string_view section, std::string_view key, const Range& range,
                             std::string_view what) {
  if (!lookup(impl_->root, section, key)) {
    impl_->used.insert(std::string(section));
    std::ostringstream s;
    s << name_ << ": [" << section << "] " << key << " is missing (" << what << ")";
    errors_.push_back(s.str());
    return std::nan("");
  }
  return number(section, key, std::nan(""), range, what);
}

std::int64_t SceneReader::integer(std::string_view section, std::string_view key, std::int64_t fallback,
                                  std::int64_t lo, std::int64_t hi, std::string_view what) {
  impl_->used.insert(std::string(section));
  impl_->used.insert(std::string(section) + "." + std::string(key));
  const toml::node* n = lookup(impl_->root, section, key);
  if (!n) return fallback;
  std::ostringstream s;
  if (!n->is_integer()) {
    s << "must be an integer (" << what << ")";
    fail(section, key, s.str());
    return fallback;
  }
  const std::int64_t v = n->as_integer()->get();
  if (v < lo || v > hi) {
    s << "= " << v << " is out of range: must be in [" << lo << ", " << hi << "] (" << what << ")";
    fail(section, key, s.str());
    return fallback;
  }
  return v;
}

bool SceneReader::flag(std::string_view section, std::string_view key, bool fallback, std::string_view what) {
  impl_->used.insert(std::string(section));
  impl_->used.insert(std::string(section) + "." + std::string(key));
  const toml::node* n = lookup(impl_->root, section, key);
  if (!n) return fallback;
  if (!n->is_boolean()) {
    fail(section, key, "must be true or false (" + std::string(what) + ")");
    return fallback;
  }
  return n->as_boolean()->get();
}

std::string SceneReader::text(std::string_view section, std::string_view key, std::string_view fallback,
                              std::string_view what) {
  impl_->used.insert(std::string(section));
  impl_->used.insert(std::string(section) + "." + std::string(key));
  const toml::node* n = lookup(impl_->root, section, key);
  if (!n) return std::string(fallback);
  if (!n->is_string()) {
    fail(section, key, "must be a string (" + std::string(what) + ")");
    return std::string(fallback);
  }
  return n->as_string()->get();
}

std::vector<std::string> SceneReader::strings(std::string_view section, std::string_view key, std::string_view what) {
  impl_->used.insert(std::string(section));
  impl_->used.insert(std::string(section) + "." + std::string(key));
  std::vector<std::string> out;
  const toml::node* n = lookup(impl_->root, section, key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (a == nullptr) {
    fail(section, key, "must be an array of strings (" + std::string(what) + ")");
    return out;
  }
  for (const toml::node& e : *a) {
    if (!e.is_string()) {
      fail(section, key, "must be an array of strings (" + std::string(what) + ")");
      return {};
    }
    out.push_back(e.as_string()->get());
  }
  return out;
}

std::string SceneReader::choice(std::string_view section, std::string_view key, std::string_view fallback,
                                std::initializer_list<std::string_view> allowed, std::string_view what) {
  return choice_of(section, key, fallback, std::span<const std::string_view>(allowed.begin(), allowed.size()), what);
}

std::string SceneReader::choice_of(std::string_view section, std::string_view key, std::string_view fallback,
                                   std::span<const std::string_view> allowed, std::string_view what) {
  const std::string v = text(section, key, fallback, what);
  for (std::string_view a : allowed) {
    if (v == a) return v;
  }
  std::ostringstream s;
  s << "= \"" << v << "\" is not one of";
  for (std::string_view a : allowed) s << " \"" << a << "\"";
  s << " (" << what << ")";
  fail(section, key, s.str());
  return std::string(fallback);
}

void SceneReader::finish() {
  for (auto&& [sk, node] : impl_->root) {
    const std::string section(sk.str());
    if (!impl_->used.count(section)) {
      errors_.push_back(where(name_, &node) + ": unknown section [" + section + "]");
      continue;
    }
    if (const toml::table* t = node.as_table()) {
      for (auto&& [kk, kn] : *t) {
        const std::string key(kk.str());
        if (!impl_->used.count(section + "." + key)) {
          std::string known;
          for (const std::string& u : impl_->used) {
            if (u.rfind(section + ".", 0) == 0) known += (known.empty() ? "" : ", ") + u.substr(section.size() + 1);
          }
          errors_.push_back(where(name_, &kn) + ": unknown key [" + section + "] " + key + " (known: " + known + ")");
        }
      }
    } else {
      errors_.push_back(where(name_, &node) + ": '" + section + "' must be a [section]");
    }
  }
}

}  // namespace gyrostab::tools
