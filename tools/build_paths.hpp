// Where this build found its sources and put its target images: the fallbacks when the installed layout
// (scripts next to the binary, GYROSTAB_IMAGE_DIR) is absent. Defined in one file, so that no other object
// depends on the checkout's path.
#pragma once

namespace gyrostab::tools {

const char* build_source_dir();  // the checkout the binary was built from
const char* build_image_dir();   // its target images, <build>/arm
const char* build_npm_dir();     // the npm packages tools/setup installed, <build>/npm/node_modules

}  // namespace gyrostab::tools
