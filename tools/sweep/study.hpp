// A sizing study as the sweep runs it: the base scene (its text, so that a study directory stands alone), the
// sea-state table, the headings, the seeds and the design variants. Read from the study file
// (study_file.hpp) or from a study directory's study.json (the same struct as JSON, study_json.hpp).
// Keys and meanings: docs/sweep.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace gyrostab::tools::sweep {

// One cell of the scatter table. `probability` as given: the table is normalised when merged.
struct SeaStateCell {
  double Hs_m{0.0};
  double Tp_s{0.0};
  double probability{0.0};
};

// A scene value a variant sets: TOML's scalar kinds.
using SceneValue = std::variant<bool, std::int64_t, double, std::string>;

struct SceneSetting {
  std::string section;  // "gyro" of "gyro.H"
  std::string key;      // "H"
  SceneValue value;
};

struct Variant {
  std::string name;  // [A-Za-z0-9._-]+, not starting with '.': it names a directory
  std::vector<SceneSetting> set;
};

struct Study {
  std::string name;
  std::string scene_file;  // the base scene as the study named it (messages)
  std::string scene_text;  // the base scene's text
  std::uint64_t seed{0};
  int seeds_per_cell{1};
  std::optional<double> duration_s;
  std::optional<double> settle_s;
  std::vector<double> headings_deg;         // empty: the scene's own course, one heading
  std::vector<double> heading_probability;  // as given (or all 1), one per heading
  std::vector<SeaStateCell> cells;
  std::vector<Variant> variants;

  int heading_count() const { return headings_deg.empty() ? 1 : static_cast<int>(headings_deg.size()); }
  // Probability of cell c at heading h, as a fraction of the whole table (the table normalised to 1).
  double probability(int cell, int heading) const;
  double probability_sum() const;
};

// A name fit for a directory: [A-Za-z0-9._-]{1,64}, not starting with '.' (so never "." or ".."). "" if fit,
// else why not.
std::string variant_name_problem(const std::string& name);

}  // namespace gyrostab::tools::sweep
