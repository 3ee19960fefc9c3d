#include "tools/sweep/task_record.hpp"

namespace gyrostab::tools::sweep {

std::string fnv1a64_hex(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  char buf[17];
  static constexpr char kHex[] = "0123456789abcdef";
  for (int i = 15; i >= 0; --i, h >>= 4) buf[i] = kHex[h & 0xF];
  buf[16] = '\0';
  return buf;
}

std::string definition_hash(const Study& s, const Task& t, const std::string& scene_text) {
  std::string text = kTaskFormat;
  text.append("\n").append(t.label(s)).append("\n").append(scene_text);
  return fnv1a64_hex(text);
}

std::string result_check(const nlohmann::json& record) {
  const nlohmann::json part{{"outcome", record.value("outcome", nlohmann::json())},
                            {"reasons", record.value("reasons", nlohmann::json())},
                            {"figures", record.value("figures", nlohmann::json())}};
  return fnv1a64_hex(part.dump());
}

nlohmann::json task_block(const Study& s, const Task& t) {
  const SeaStateCell& c = s.cells[static_cast<std::size_t>(t.cell)];
  return {{"variant", s.variants[static_cast<std::size_t>(t.variant)].name},
          {"cell", t.cell},
          {"heading", t.heading},
          {"replicate", t.replicate},
          {"index", t.index},
          {"seed", t.seed(s)},
          {"Hs_m", c.Hs_m},
          {"Tp_s", c.Tp_s},
          {"heading_deg", s.headings_deg.empty() ? nlohmann::json() : nlohmann::json(s.headings_deg[static_cast<std::size_t>(t.heading)])}};
}

}  // namespace gyrostab::tools::sweep
