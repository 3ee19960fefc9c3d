// A scene's identity on a link and in a log: FNV-1a 64 of the scene file's bytes, exactly as parsed (and as a
// bus log's scene event records them). Both ends of a plant ⇄ controller link put it in every frame; a peer of
// another scene is refused with both hashes in the message (docs/protocol.md). Not a security property: the
// link key is; this keeps two hand-started pairs on one bus from pairing across scenes. `gyrostab check SCENE`
// prints it, so a controller written elsewhere can be told the hash of the scene it was built for.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace gyrostab::tools {

constexpr std::uint64_t scene_hash(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64: offset basis, then xor and multiply per byte
  for (const char c : text) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}
static_assert(scene_hash("") == 0xcbf29ce484222325ull && scene_hash("a") == 0xaf63dc4c8601ec8cull,
              "the FNV-1a 64 reference values");

// "0x" and 16 hexadecimal digits, as messages and report.json write a scene hash.
inline std::string format_scene_hash(std::uint64_t h) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace gyrostab::tools
