#include "tools/sweep/study_json.hpp"

namespace gyrostab::tools::sweep {

nlohmann::json scene_value_json(const SceneValue& v) {
  return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}

nlohmann::json study_json(const Study& s) {
  nlohmann::json cells = nlohmann::json::array();
  for (std::size_t i = 0; i < s.cells.size(); ++i) {
    const SeaStateCell& c = s.cells[i];
    cells.push_back({{"cell", i}, {"Hs_m", c.Hs_m}, {"Tp_s", c.Tp_s}, {"probability", c.probability}});
  }
  nlohmann::json variants = nlohmann::json::array();
  for (const Variant& v : s.variants) {
    nlohmann::json set = nlohmann::json::array();
    for (const SceneSetting& k : v.set) set.push_back({{"key", k.section + "." + k.key}, {"value", scene_value_json(k.value)}});
    variants.push_back({{"name", v.name}, {"set", set}});
  }
  return {{"format", kStudyFormat},
          {"name", s.name},
          {"scene_file", s.scene_file},
          {"scene_text", s.scene_text},
          {"seed", s.seed},
          {"seeds_per_cell", s.seeds_per_cell},
          {"duration_s", s.duration_s ? nlohmann::json(*s.duration_s) : nlohmann::json()},
          {"settle_s", s.settle_s ? nlohmann::json(*s.settle_s) : nlohmann::json()},
          {"headings_deg", s.headings_deg},
          {"heading_probability", s.heading_probability},
          {"probability_sum", s.probability_sum()},
          {"cells", cells},
          {"variants", variants}};
}

bool study_from_json(const nlohmann::json& j, Study& out, std::string& error) {
  try {
    if (!j.is_object() || j.value("format", "") != kStudyFormat) {
      error = std::string("not a study of format ") + kStudyFormat;
      return false;
    }
    Study s;
    s.name = j.at("name").get<std::string>();
    s.scene_file = j.at("scene_file").get<std::string>();
    s.scene_text = j.at("scene_text").get<std::string>();
    s.seed = j.at("seed").get<std::uint64_t>();
    s.seeds_per_cell = j.at("seeds_per_cell").get<int>();
    if (!j.at("duration_s").is_null()) s.duration_s = j.at("duration_s").get<double>();
    if (!j.at("settle_s").is_null()) s.settle_s = j.at("settle_s").get<double>();
    s.headings_deg = j.at("headings_deg").get<std::vector<double>>();
    s.heading_probability = j.at("heading_probability").get<std::vector<double>>();
    for (const auto& c : j.at("cells")) {
      s.cells.push_back({c.at("Hs_m").get<double>(), c.at("Tp_s").get<double>(), c.at("probability").get<double>()});
    }
    for (const auto& v : j.at("variants")) {
      Variant variant;
      variant.name = v.at("name").get<std::string>();
      if (!variant_name_problem(variant.name).empty()) {
        error = "variant name \"" + variant.name + "\" " + variant_name_problem(variant.name);
        return false;
      }
      for (const auto& k : v.at("set")) {
        const std::string key = k.at("key").get<std::string>();
        const std::size_t dot = key.find('.');
        const nlohmann::json& value = k.at("value");
        SceneValue sv;
        if (value.is_boolean()) {
          sv = value.get<bool>();
        } else if (value.is_number_integer()) {
          sv = value.get<std::int64_t>();
        } else if (value.is_number_float()) {
          sv = value.get<double>();
        } else {
          sv = value.get<std::string>();
        }
        variant.set.push_back({key.substr(0, dot), dot == std::string::npos ? "" : key.substr(dot + 1), sv});
      }
      s.variants.push_back(std::move(variant));
    }
    if (s.cells.empty() || s.variants.empty() || s.seeds_per_cell < 1 ||
        (!s.headings_deg.empty() && s.heading_probability.size() != s.headings_deg.size())) {
      error = "the study has no cells, no variants, no seeds, or headings without their probabilities";
      return false;
    }
    out = std::move(s);
    return true;
  } catch (const nlohmann::json::exception& e) {
    error = std::string("malformed study: ") + e.what();
    return false;
  }
}

}  // namespace gyrostab::tools::sweep
