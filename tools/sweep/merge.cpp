#include "tools/build_paths.hpp"
#include "tools/sweep/merge.hpp"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "tools/run/output_dir.hpp"
#include "tools/sweep/criteria.hpp"
#include "tools/sweep/study_json.hpp"
#include "tools/sweep/task.hpp"
#include "tools/sweep/task_record.hpp"
#include "tools/sweep/task_store.hpp"

namespace gyrostab::tools::sweep {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The figures the summary weights over the cells (roll_rms_ratio and roll_max are per-cell only).
constexpr std::string_view kSummaryFigures[] = {
    "roll_rms_rad",       "roll_rms_unstabilized_rad", "roll_reduction",         "stop_contacts",
    "precession_max_rad", "precession_torque_max_Nm",  "roll_moment_max_Nm",     "yaw_moment_max_Nm",
    "yaw_moment_unit_max_Nm", "pitch_moment_max_Nm"};

std::string number_text(const json& v) {
  if (v.is_null()) return "";
  if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v.get<double>());
  return std::string(buf, r.ptr);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One row of a variant's table: a cell at a heading, over its replicates.
struct Row {
  int cell{0}, heading{0};
  double probability{0.0};
  int completed{0}, failed{0}, missing{0};
  std::vector<std::string> failures;  // "r1: diverged: ..."
  json means = json::object();
  bool included(int replicates) const { return completed == replicates; }
};

struct VariantTable {
  std::vector<Row> rows;
  int completed{0}, failed{0}, missing{0};
};

VariantTable tabulate(const Study& s, int variant, const std::vector<Task>& tasks, const std::vector<json>& records,
                      const std::vector<bool>& present) {
  VariantTable out;
  const int H = s.heading_count();
  out.rows.resize(s.cells.size() * static_cast<std::size_t>(H));
  for (int c = 0; c < static_cast<int>(s.cells.size()); ++c) {
    for (int h = 0; h < H; ++h) {
      Row& r = out.rows[static_cast<std::size_t>(c * H + h)];
      r.cell = c;
      r.heading = h;
      r.probability = s.probability(c, h);
    }
  }
  std::map<std::size_t, std::vector<const json*>> completed_figures;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const Task& t = tasks[i];
    if (t.variant != variant) continue;
    const std::size_t row = static_cast<std::size_t>(t.cell * H + t.heading);
    Row& r = out.rows[row];
    if (!present[i]) {
      ++r.missing;
      ++out.missing;
      continue;
    }
    const json& rec = records[i];
    if (rec["outcome"] == kCompleted) {
      ++r.completed;
      ++out.completed;
      completed_figures[row].push_back(&rec["figures"]);
    } else {
      ++r.failed;
      ++out.failed;
      std::string why = rec["reasons"].empty() ? "" : rec["reasons"][0].get<std::string>();
      r.failures.push_back("r" + std::to_string(t.replicate) + ": " + rec["outcome"].get<std::string>() + ": " + why);
    }
  }
  for (std::size_t row = 0; row < out.rows.size(); ++row) {
    Row& r = out.rows[row];
    const auto& figs = completed_figures[row];
    for (std::string_view name : kTaskFigures) {
      const std::string key(name);
      json mean;
      if (!figs.empty()) {
        double sum = 0.0;
        bool all = true;
        for (const json* f : figs) {
          const json& v = (*f)[key];
          if (!v.is_number()) {
            all = false;
            break;
          }
          sum += v.get<double>();
        }
        if (all) mean = sum / static_cast<double>(figs.size());
      }
      r.means[key] = mean;
    }
  }
  return out;
}

json heading_of(const Study& s, int h) {
  return s.headings_deg.empty() ? json() : json(s.headings_deg[static_cast<std::size_t>(h)]);
}

std::string cells_csv(const Study& s, const VariantTable& t) {
  std::string out = "cell,heading,Hs_m,Tp_s,heading_deg,probability,replicates,failures,missing,included";
  for (std::string_view name : kTaskFigures) out += "," + std::string(name);
  out += "\n";
  for (const Row& r : t.rows) {
    const SeaStateCell& c = s.cells[static_cast<std::size_t>(r.cell)];
    out += std::to_string(r.cell) + "," + std::to_string(r.heading) + "," + number_text(c.Hs_m) + "," +
           number_text(c.Tp_s) + "," + number_text(heading_of(s, r.heading)) + "," + number_text(r.probability) + "," +
           std::to_string(r.completed) + "," + std::to_string(r.failed) + "," + std::to_string(r.missing) + "," +
           (r.included(s.seeds_per_cell) ? "1" : "0");
    for (std::string_view name : kTaskFigures) out += "," + number_text(r.means[std::string(name)]);
    out += "\n";
  }
  return out;
}

json cells_json(const Study& s, const VariantTable& t) {
  json rows = json::array();
  for (const Row& r : t.rows) {
    const SeaStateCell& c = s.cells[static_cast<std::size_t>(r.cell)];
    rows.push_back({{"cell", r.cell},
                    {"heading", r.heading},
                    {"Hs_m", c.Hs_m},
                    {"Tp_s", c.Tp_s},
                    {"heading_deg", heading_of(s, r.heading)},
                    {"probability", r.probability},
                    {"replicates", r.completed},
                    {"failures", r.failed},
                    {"missing", r.missing},
                    {"included", r.included(s.seeds_per_cell)},
                    {"failure_reasons", r.failures},
                    {"mean", r.means}});
  }
  return rows;
}

json summary_json(const Study& s, const Variant& v, const VariantTable& t) {
  double included = 0.0, failed_p = 0.0, missing_p = 0.0;
  for (const Row& r : t.rows) {
    if (r.included(s.seeds_per_cell)) {
      included += r.probability;
    } else if (r.failed > 0) {
      failed_p += r.probability;
    } else {
      missing_p += r.probability;
    }
  }
  json means = json::object();
  for (std::string_view name : kSummaryFigures) {
    const std::string key(name);
    double sum = 0.0;
    bool all = included > 0.0;
    for (const Row& r : t.rows) {
      if (!r.included(s.seeds_per_cell) || r.probability == 0.0) continue;
      if (!r.means[key].is_number()) {
        all = false;
        break;
      }
      sum += r.probability * r.means[key].get<double>();
    }
    means[key] = all ? json(sum / included) : json();
  }
  json criteria = json::array();
  for (const RollCriterion& c : kRollCriteria) {
    double exceed = 0.0, exceed_unstab = 0.0;
    for (const Row& r : t.rows) {
      if (!r.included(s.seeds_per_cell)) continue;
      const json& roll = r.means["roll_rms_rad"];
      const json& roll0 = r.means["roll_rms_unstabilized_rad"];
      if (roll.is_number() && roll.get<double>() > c.limit_rad()) exceed += r.probability;
      if (roll0.is_number() && roll0.get<double>() > c.limit_rad()) exceed_unstab += r.probability;
    }
    criteria.push_back({{"name", c.name},
                        {"applies_to", c.applies},
                        {"roll_rms_limit_deg", c.limit_deg},
                        {"roll_rms_limit_rad", c.limit_rad()},
                        {"exceedance_probability", exceed},
                        {"operability", included - exceed},
                        {"exceedance_probability_unstabilized", exceed_unstab},
                        {"operability_unstabilized", included - exceed_unstab}});
  }
  json set = json::object();
  for (const SceneSetting& k : v.set) set[k.section + "." + k.key] = scene_value_json(k.value);
  return {{"study", s.name},
          {"variant", v.name},
          {"set", set},
          {"tasks", {{"total", t.completed + t.failed + t.missing},
                     {"completed", t.completed},
                     {"failed", t.failed},
                     {"missing", t.missing}}},
          {"complete", t.missing == 0},
          {"probability_sum_of_table", s.probability_sum()},
          {"included_probability", included},
          {"excluded_probability_failed", failed_p},
          {"excluded_probability_missing", missing_p},
          {"weighted_mean", means},
          {"roll_criteria", criteria}};
}

std::string summary_csv_header() {
  std::string h = "variant,tasks,completed,failed,missing,included_probability,excluded_probability_failed,"
                  "excluded_probability_missing";
  for (std::string_view name : kSummaryFigures) h += "," + std::string(name);
  for (const RollCriterion& c : kRollCriteria) h += ",operability_" + std::string(c.name);
  for (const RollCriterion& c : kRollCriteria) h += ",operability_unstabilized_" + std::string(c.name);
  return h + "\n";
}

std::string summary_csv_row(const json& sum) {
  std::string row = sum["variant"].get<std::string>();
  for (const char* k : {"total", "completed", "failed", "missing"}) row += "," + number_text(sum["tasks"][k]);
  for (const char* k : {"included_probability", "excluded_probability_failed", "excluded_probability_missing"}) {
    row += "," + number_text(sum[k]);
  }
  for (std::string_view name : kSummaryFigures) row += "," + number_text(sum["weighted_mean"][std::string(name)]);
  for (const json& c : sum["roll_criteria"]) row += "," + number_text(c["operability"]);
  for (const json& c : sum["roll_criteria"]) row += "," + number_text(c["operability_unstabilized"]);
  return row + "\n";
}

// The numbers a reader compares first, as a Markdown table (docs/sweep.md quotes the sample study's), rounded
// for reading; the CSV and JSON files keep every digit.
std::string summary_markdown_header() {
  std::string h = "| variant | roll rms [deg] | unstabilized [deg] | roll reduction | precession max [deg] | "
                  "torque peak [kN m] | stop contacts |";
  std::string rule = "|---|---:|---:|---:|---:|---:|---:|";
  for (const RollCriterion& c : kRollCriteria) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " operability %s %.1f° |", std::string(c.applies).c_str(), c.limit_deg);
    h += buf;
    rule += "---:|";
  }
  return h + "\n" + rule + "\n";
}

std::string summary_markdown_row(const json& sum) {
  const json& m = sum["weighted_mean"];
  const auto fixed = [](const json& v, double scale, const char* format) {
    if (!v.is_number()) return std::string("n/a");
    char buf[64];
    std::snprintf(buf, sizeof buf, format, scale * v.get<double>());
    return std::string(buf);
  };
  constexpr double kDeg = 180.0 / 3.14159265358979323846;
  std::string row = "| " + sum["variant"].get<std::string>() + " | " + fixed(m["roll_rms_rad"], kDeg, "%.2f") + " | " +
                    fixed(m["roll_rms_unstabilized_rad"], kDeg, "%.2f") + " | " + fixed(m["roll_reduction"], 1.0, "%.3f") +
                    " | " + fixed(m["precession_max_rad"], kDeg, "%.1f") + " | " +
                    fixed(m["precession_torque_max_Nm"], 1e-3, "%.1f") + " | " + fixed(m["stop_contacts"], 1.0, "%.2f") +
                    " |";
  for (const json& c : sum["roll_criteria"]) {
    row += " " + fixed(c["operability"], 1.0, "%.3f") + " (" + fixed(c["operability_unstabilized"], 1.0, "%.3f") + ") |";
  }
  return row + "\n";
}

bool write_file(const fs::path& path, const std::string& text, std::string& error) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  f.close();
  if (!f) {
    error = "cannot write " + path.string();
    return false;
  }
  return true;
}

json timing_json(const std::vector<json>& records, const std::vector<bool>& present) {
  std::vector<double> setup, run, write, overhead;
  double total_run = 0.0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (!present[i]) continue;
    const json& t = records[i]["timing"];
    const double s = t.value("setup_s", 0.0), r = t.value("run_s", 0.0), w = t.value("write_s", 0.0);
    setup.push_back(s);
    write.push_back(w);
    if (r > 0.0) {
      run.push_back(r);
      overhead.push_back((s + w) / r);
      total_run += r;
    }
  }
  return {{"tasks_timed", setup.size()},
          {"median_setup_s", median(setup)},
          {"median_run_s", median(run)},
          {"median_write_s", median(write)},
          {"median_overhead_fraction", median(overhead)},
          {"max_overhead_fraction", overhead.empty() ? 0.0 : *std::max_element(overhead.begin(), overhead.end())},
          {"total_run_s", total_run},
          {"about", "per task, from the task files: setup (scene text, reader, checks, plant and controller), run "
                    "(the closed loop), write (serialise, write, fsync); overhead = (setup + write) / run. Wall "
                    "times: they differ run to run and are not part of results/."}};
}

// The heat maps, drawn by tools/plot/plot_sweep.py into the staged results; false with the reason.
bool draw_heat_maps(const fs::path& staged, const Study& s, std::string& why) {
  const char* here = std::getenv("GYROSTAB_SWEEP_PLOT_SCRIPT");  // set and empty: no heat maps (tests)
  if (here != nullptr && *here == '\0') return true;
  const std::string script = here ? here : std::string(build_source_dir()) + "/tools/plot/plot_sweep.py";
  std::vector<std::string> argv{"/usr/bin/python3", script, staged.string()};
  for (const Variant& v : s.variants) argv.push_back(v.name);
  const int rc = run_program(argv, why);
  if (rc != 0 && why.empty()) why = script + " exited with " + std::to_string(rc);
  return rc == 0;
}

}  // namespace

int merge_study_dir(const std::string& dir, bool quiet) {
  const fs::path root(dir);
  std::ifstream f(root / "study.json", std::ios::binary);
  std::ostringstream text;
  text << f.rdbuf();
  Study s;
  std::string error;
  const json sj = json::parse(text.str(), nullptr, false);
  if (!f || sj.is_discarded() || !study_from_json(sj, s, error)) {
    std::fprintf(stderr, "gyrostab sweep merge: %s: not a study directory (study.json %s)\n", dir.c_str(),
                 !f ? "cannot be read" : (sj.is_discarded() ? "is not valid JSON" : error.c_str()));
    return kSweepRefused;
  }
  const std::vector<Task> tasks = all_tasks(s);
  std::vector<json> records(tasks.size());
  std::vector<bool> present(tasks.size(), false);
  std::vector<std::string> missing;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const Task& t = tasks[i];
    const std::string path = task_path(dir, s, t);
    StoredTask st = read_task_file(path, definition_hash(s, t, task_scene_text(s, t)));
    if (st.state == Stored::kValid) {
      records[i] = std::move(st.record);
      present[i] = true;
      continue;
    }
    if (st.state != Stored::kMissing) {
      std::fprintf(stderr, "gyrostab sweep merge: %s: %s: %s; left out\n", path.c_str(),
                   st.state == Stored::kStale ? "stale" : "damaged", st.why.c_str());
    }
    missing.push_back(t.label(s) + (st.state == Stored::kMissing ? "" : " (unusable file)"));
  }

  const fs::path staged = root / (".results-staging-" + std::to_string(getpid()));
  std::error_code ec;
  fs::remove_all(staged, ec);
  fs::create_directories(staged, ec);
  if (ec) {
    std::fprintf(stderr, "gyrostab sweep merge: cannot create %s: %s\n", staged.c_str(), ec.message().c_str());
    return kSweepRefused;
  }
  std::string summary = summary_csv_header();
  std::string markdown = summary_markdown_header();
  int failed = 0;
  bool ok = true;
  for (int v = 0; v < static_cast<int>(s.variants.size()) && ok; ++v) {
    const Variant& variant = s.variants[static_cast<std::size_t>(v)];
    const VariantTable table = tabulate(s, v, tasks, records, present);
    failed += table.failed;
    const fs::path vdir = staged / variant.name;
    fs::create_directories(vdir, ec);
    const json sum = summary_json(s, variant, table);
    ok = !ec && write_file(vdir / "cells.csv", cells_csv(s, table), error) &&
         write_file(vdir / "cells.json", cells_json(s, table).dump(2) + "\n", error) &&
         write_file(vdir / "summary.json", sum.dump(2) + "\n", error);
    summary += summary_csv_row(sum);
    markdown += summary_markdown_row(sum);
  }
  ok = ok && write_file(staged / "summary.csv", summary, error) &&
       write_file(staged / "summary.md", markdown, error);
  if (!ok) {
    std::fprintf(stderr, "gyrostab sweep merge: %s\n", error.empty() ? ec.message().c_str() : error.c_str());
    fs::remove_all(staged, ec);
    return kSweepTasksFailed;
  }
  std::string why;
  const bool maps = draw_heat_maps(staged, s, why);
  if (!maps) {
    std::fprintf(stderr, "gyrostab sweep merge: heat maps not written (needs /usr/bin/python3 with "
                         "python3-matplotlib; %s); the tables are complete\n", why.c_str());
  }
  const fs::path results = root / "results";
  const fs::path old = root / (".results-old-" + std::to_string(getpid()));
  if (fs::exists(results)) fs::rename(results, old, ec);
  if (!ec) fs::rename(staged, results, ec);
  if (ec) {
    std::fprintf(stderr, "gyrostab sweep merge: cannot move the results into %s: %s\n", results.c_str(),
                 ec.message().c_str());
    return kSweepTasksFailed;
  }
  fs::remove_all(old, ec);
  if (!write_text_atomic((root / "timing.json").string(), timing_json(records, present).dump(2) + "\n", error)) {
    std::fprintf(stderr, "gyrostab sweep merge: %s\n", error.c_str());
  }

  const std::size_t have = tasks.size() - missing.size();
  if (!quiet || !missing.empty() || failed > 0) {
    std::printf("sweep merge: %s: %zu of %zu tasks (%d failed, %zu missing); wrote %s/results: summary.csv, summary.md and, per "
                "variant, cells.csv, cells.json, summary.json%s\n",
                s.name.c_str(), have, tasks.size(), failed, missing.size(), dir.c_str(),
                maps ? ", heatmap_roll_reduction.png, heatmap_stop_contacts.png" : "");
  }
  if (!missing.empty()) {
    const std::size_t shown = std::min<std::size_t>(missing.size(), 20);
    for (std::size_t i = 0; i < shown; ++i) std::fprintf(stderr, "  missing: %s\n", missing[i].c_str());
    if (missing.size() > shown) std::fprintf(stderr, "  ... and %zu more\n", missing.size() - shown);
    std::fprintf(stderr, "gyrostab sweep merge: incomplete: the results leave out the cells of the %zu missing "
                         "tasks (summary.json \"complete\": false); run the study again to finish it\n",
                 missing.size());
    return kSweepIncomplete;
  }
  return failed > 0 ? kSweepTasksFailed : kSweepOk;
}

}  // namespace gyrostab::tools::sweep
