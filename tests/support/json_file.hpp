// report.json and other JSON files the tests read, parsed by one compiled function (nlohmann's parser is one
// of the most expensive templates to compile; every test that reads a report would instantiate it again).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace gyrostab::testing {

// The file's JSON; a discarded value (is_discarded()) when it is not JSON, null when it cannot be read.
nlohmann::json read_json(const std::string& path);

}  // namespace gyrostab::testing
