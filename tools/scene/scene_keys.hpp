// docs/scenes.md, generated from the field tables of the common keys and of every registered device
// (`gyrostab scene-keys`; tests/unit/scene_docs_test.cpp fails when the committed file differs).
#pragma once

#include <string>

namespace gyrostab::tools {

std::string scenes_markdown();

}  // namespace gyrostab::tools
