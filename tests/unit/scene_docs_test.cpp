// docs/scenes.md is generated from the scene schemas (`gyrostab scene-keys`, tools/scene/scene_keys.cpp): the
// committed file must be exactly what the field tables say, so a key's unit, default, range or description
// cannot drift from the reader.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tools/devices/registry.hpp"
#include "tools/scene/scene_keys.hpp"

namespace gyrostab {
namespace scene_docs_test {

TEST(SceneDocs, CommittedScenesMdIsWhatTheSchemasGenerate) {
  std::ifstream f(GYROSTAB_SOURCE_DIR "/docs/scenes.md", std::ios::binary);
  ASSERT_TRUE(f) << "docs/scenes.md is missing";
  std::ostringstream committed;
  committed << f.rdbuf();
  const std::string generated = tools::scenes_markdown();
  if (committed.str() != generated) {
    std::size_t at = 0;
    while (at < generated.size() && at < committed.str().size() && generated[at] == committed.str()[at]) ++at;
    const std::size_t line = static_cast<std::size_t>(std::count(generated.begin(), generated.begin() +
                                                                 static_cast<std::ptrdiff_t>(at), '\n')) + 1;
    FAIL() << "docs/scenes.md differs from the schemas from line " << line
           << ": run `build/bin/gyrostab scene-keys > docs/scenes.md`";
  }
}

TEST(SceneDocs, EveryRegisteredDeviceHasASectionWithItsKeys) {
  const std::string md = tools::scenes_markdown();
  for (const tools::DeviceDescriptor* d : tools::devices()) {
    EXPECT_NE(md.find("\n## " + std::string(d->name) + "\n"), std::string::npos) << d->name;
    const tools::SceneDoc doc = d->doc();
    ASSERT_FALSE(doc.tables.empty()) << d->name;
    for (const tools::SceneDocTable& t : doc.tables) {
      for (const tools::SceneDocRow& r : t.rows) {
        EXPECT_FALSE(r.meaning.empty()) << d->name << " " << r.key;
        EXPECT_FALSE(r.fallback.empty()) << d->name << " " << r.key;
        EXPECT_FALSE(r.range.empty()) << d->name << " " << r.key;
      }
    }
  }
}

}  // namespace scene_docs_test
}  // namespace gyrostab
