// The study's outputs: the work-precision table (stdout), accuracy.csv (one row per run), report.json (set-up,
// reference convergence, every run, the speed-ups with their spread over repeats) and work_precision.png
// (tools/plot/plot_work_precision.py through Debian's /usr/bin/python3 with matplotlib).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/accuracy/study_result.hpp"

namespace gyrostab::tools::accuracy {

std::string format_table(const StudyResult& s);
std::string format_csv(const StudyResult& s);
nlohmann::json study_json(const StudyResult& s);

// Writes accuracy.csv, report.json and work_precision.png into out_dir; false with `error` set if a file
// could not be written (a missing plotting interpreter is reported on stderr, not an error).
bool write_study_outputs(const StudyResult& s, const std::string& out_dir, bool plot, std::vector<std::string>& written,
                         std::string& error);

}  // namespace gyrostab::tools::accuracy
