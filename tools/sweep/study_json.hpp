// A study as DIR/study.json: everything the merge needs (the base scene's text included), so that a study
// directory stands alone — a merge on another machine, or after the study file changed, reads this, not the
// study file.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "tools/sweep/study.hpp"

namespace gyrostab::tools::sweep {

inline constexpr const char* kStudyFormat = "gyrostab-sweep-study/1";

nlohmann::json study_json(const Study& s);
// false with `error` when the JSON is not a study of this format.
bool study_from_json(const nlohmann::json& j, Study& s, std::string& error);

nlohmann::json scene_value_json(const SceneValue& v);

}  // namespace gyrostab::tools::sweep
