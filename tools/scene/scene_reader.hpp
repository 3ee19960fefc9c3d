// Reads a scene file (TOML, toml++) with typed, range-checked getters that collect every problem as a
// message naming the file, line, section and key — a scene is refused before running if any getter
// failed or any key was never asked for (a typo), so nothing is silently accepted.
//
//   SceneReader r;  if (!r.open(path)) { print r.errors(); }
//   double A = r.required("ship", "A", Range::positive(), "roll inertia [kg m²]");
//   ...; r.finish();  // reports unknown sections and keys
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gyrostab::tools {

struct Range {
  double lo{-1e308}, hi{1e308};
  bool lo_open{false}, hi_open{false};
  static constexpr Range any() { return {}; }
  static constexpr Range positive() { return {0.0, 1e308, true, false}; }
  static constexpr Range non_negative() { return {0.0, 1e308, false, false}; }
  static constexpr Range closed(double a, double b) { return {a, b, false, false}; }
  static constexpr Range open_closed(double a, double b) { return {a, b, true, false}; }
  bool contains(double v) const;
  std::string describe() const;
};

// The directory of a scene file ("." for a bare file name): its data files are resolved against it.
std::string scene_file_dir(const std::string& scene_path);

class SceneReader {
 public:
  SceneReader();
  ~SceneReader();
  SceneReader(SceneReader&&) noexcept;
  SceneReader& operator=(SceneReader&&) noexcept;

  // Parse a file; false (with the parser's message, line and column in errors()) if it is not valid TOML.
  bool open(const std::string& path);
  // Parse text (tests, fuzzing); `name` stands for the file name in messages.
  bool parse(std::string_view text, const std::string& name);

  bool has_section(std::string_view section) const;
  bool has(std::string_view section, std::string_view key) const;

  double required(std::string_view section, std::string_view key, const Range& range, std::string_view what);
  double number(std::string_view section, std::string_view key, double fallback, const Range& range,
                std::string_view what);
  std::int64_t integer(std::string_view section, std::string_view key, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi, std::string_view what);
  bool flag(std::string_view section, std::string_view key, bool fallback, std::string_view what);
  std::string choice(std::string_view section, std::string_view key, std::string_view fallback,
                     std::initializer_list<std::string_view> allowed, std::string_view what);
  std::string choice_of(std::string_view section, std::string_view key, std::string_view fallback,
                        std::span<const std::string_view> allowed, std::string_view what);
  std::string text(std::string_view section, std::string_view key, std::string_view fallback, std::string_view what);
  // An array of strings; empty when the key is absent (a non-array or a non-string element is a problem).
  std::vector<std::string> strings(std::string_view section, std::string_view key, std::string_view what);

  // A problem found by the caller (e.g. a relation between keys); `key` is used for the line number.
  void fail(std::string_view section, std::string_view key, const std::string& message);

  // Report sections and keys present in the file but never read.
  void finish();

  // The directory a scene's data files (a [motion] file) are resolved against and confined to; empty: the
  // scene names no file it may read (text from memory, the fuzz target). open() sets the file's directory.
  void set_file_root(std::string dir) { file_root_ = std::move(dir); }
  const std::string& file_root() const { return file_root_; }

  bool ok() const { return errors_.empty(); }
  const std::vector<std::string>& errors() const { return errors_; }
  const std::string& name() const { return name_; }
  // The scene's identity: scene_hash() of the bytes parsed (tools/scene/scene_hash.hpp).
  std::uint64_t text_hash() const { return text_hash_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string name_;
  std::string file_root_;
  std::uint64_t text_hash_{0};
  std::vector<std::string> errors_;
};

}  // namespace gyrostab::tools
