#include "tests/support/json_file.hpp"

#include <fstream>

namespace gyrostab::testing {

nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  if (!f) return nlohmann::json();
  return nlohmann::json::parse(f, nullptr, false);
}

}  // namespace gyrostab::testing
