// The documentation of a scene schema, type-erased: the rows of docs/scenes.md (generated from the field
// tables by tools/scene/schema.hpp, written by `gyrostab scene-keys`; a test fails when the committed file
// differs). One source for the reader, its checks and the docs.
#pragma once

#include <string>
#include <vector>

namespace gyrostab::tools {

struct SceneDocRow {
  std::string key;      // "[ship] A"
  std::string meaning;  // description, with its condition ("regular: ...")
  std::string unit;     // "kg m²", "–"
  std::string fallback;  // "required", "0", "`jonswap`", "H (the rotor's momentum)"
  std::string range;    // "> 0", "integer 1 … 256", "`regular`, `jonswap`"
};

struct SceneDocTable {
  std::string title;  // "" for the device's main table
  std::string note;   // a paragraph under the title
  std::vector<SceneDocRow> rows;
};

struct SceneDoc {
  std::vector<SceneDocTable> tables;
  std::vector<std::string> rules;  // checks that relate several keys, in words
};

// Markdown of one table (header + rows) and of a rules list.
std::string markdown(const SceneDocTable& t);
std::string markdown_rules(const std::vector<std::string>& rules);

}  // namespace gyrostab::tools
