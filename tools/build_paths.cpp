#include "tools/build_paths.hpp"

namespace gyrostab::tools {

const char* build_source_dir() { return GYROSTAB_SOURCE_DIR; }
const char* build_image_dir() { return GYROSTAB_IMAGE_DIR; }
const char* build_npm_dir() { return GYROSTAB_NPM_DIR; }

}  // namespace gyrostab::tools
