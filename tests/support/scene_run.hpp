// Runs a scene in memory for a test — the shipped file, or a variant's text — and keeps what it reports: the
// exit code, report.json's content and signals.csv's. Nothing is written.
#pragma once

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tools/commands.hpp"

namespace gyrostab::testing {

struct SceneRunResult {
  int rc{-1};
  nlohmann::json report;
  std::string csv;
};

// `text` empty: the file at `path`; else the text, `path` naming it and `file_root` the directory its data
// files resolve against.
inline SceneRunResult run_scene_in_memory(const std::string& path, const std::string& text = "",
                                          const std::string& file_root = "") {
  tools::RunRequest req;
  req.scene_path = path;
  req.scene_text = text;
  req.scene_file_root = file_root;
  req.write_outputs = false;
  req.progress = false;
  SceneRunResult r;
  req.report_out = &r.report;
  req.csv_out = &r.csv;
  r.rc = tools::run_scene(req);
  return r;
}

// The report's "figures" of a run that must succeed.
inline nlohmann::json figures_of(const std::string& path, const std::string& text = "",
                                 const std::string& file_root = "") {
  const SceneRunResult r = run_scene_in_memory(path, text, file_root);
  EXPECT_EQ(r.rc, 0) << path;
  return r.report["figures"];
}

// One figure `<key>` of a report: measured, `<key>_predicted_sampled` and `<key>_predicted` (0 when the run
// measured none, which the test is told of).
struct Predicted {
  double measured{0}, sampled{0}, continuous{0};
  static Predicted of(const nlohmann::json& f, const std::string& key) {
    EXPECT_TRUE(f[key].is_number()) << key << ": " << f.dump();
    if (!f[key].is_number()) return {};
    return {f[key].get<double>(), f[key + "_predicted_sampled"].get<double>(), f[key + "_predicted"].get<double>()};
  }
};

// A report's figures of one mode (`<mode>_decay_rate_per_s`, `<mode>_frequency_rad_s`): measured, the sampled
// loop's and the continuous loop's (docs/sampled-data.md), with their relative differences.
struct ModeFigures {
  double decay{0}, freq{0}, decay_sampled{0}, freq_sampled{0}, decay_continuous{0}, freq_continuous{0};

  static ModeFigures of(const nlohmann::json& f, const std::string& mode = "nutation") {
    const Predicted d = Predicted::of(f, mode + "_decay_rate_per_s"), w = Predicted::of(f, mode + "_frequency_rad_s");
    return {d.measured, w.measured, d.sampled, w.sampled, d.continuous, w.continuous};
  }
  double decay_vs_sampled() const { return decay / decay_sampled - 1.0; }
  double freq_vs_sampled() const { return freq / freq_sampled - 1.0; }
  double decay_vs_continuous() const { return decay / decay_continuous - 1.0; }
  double freq_vs_continuous() const { return freq / freq_continuous - 1.0; }
  void print(const char* name) const {
    std::printf("  %s: decay %.7f (sampled %.7f %+.2e, continuous %.7f %+.2e), freq %.6f (sampled %.6f %+.2e, "
                "continuous %.6f %+.2e)\n", name, decay, decay_sampled, decay_vs_sampled(), decay_continuous,
                decay_vs_continuous(), freq, freq_sampled, freq_vs_sampled(), freq_continuous, freq_vs_continuous());
  }
};

// A report's pair near a double root as `<pair>_natural_frequency_rad_s` and `<pair>_damping_ratio`
// (analysis::pair_shape): measured, the sampled loop's and the continuous design's.
struct PairFigures {
  double wn{0}, zeta{0}, wn_s{0}, zeta_s{0}, wn_c{0}, zeta_c{0};

  static PairFigures of(const nlohmann::json& f, const std::string& pair) {
    const Predicted w = Predicted::of(f, pair + "_natural_frequency_rad_s"), z = Predicted::of(f, pair + "_damping_ratio");
    return {w.measured, z.measured, w.sampled, z.sampled, w.continuous, z.continuous};
  }
  void print(const char* what) const {
    std::printf("  %s: w_n %.9g (sampled %+.2e, continuous %+.2e), zeta %.9g (sampled %+.2e, continuous %+.2e)\n",
                what, wn, wn / wn_s - 1.0, wn / wn_c - 1.0, zeta, zeta / zeta_s - 1.0, zeta / zeta_c - 1.0);
  }
};

}  // namespace gyrostab::testing
