// `gyrostab sweep STUDY --view [ADDR:PORT]`: the sweep's live view. The page (tools/view/web/sweep.html) shows
// the tasks' progress (done, failed, of how many, elapsed) and, per variant, a heat map over the study's (Hs, Tp)
// table that fills as tasks finish: each cell's mean roll reduction over its finished tasks (headings and
// replicates), with how many of them are in. The workers add() each finished task; the sweep's polling loop
// publishes the state (view_server.hpp's snapshot mode). Same security model as the run's view.
#pragma once

#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/view/view_server.hpp"

namespace gyrostab::tools::view {

struct SweepViewOptions {
  bool enabled{false};
  std::string address;
  double linger_s{-1};  // after the merge: serve this long (< 0: until SIGINT/SIGTERM)
};

class SweepView {
 public:
  // `meta`: {"study", "variants": [names], "cells": [{"Hs", "Tp"}], "headings", "seeds", "total"}.
  static std::unique_ptr<SweepView> start(const SweepViewOptions& options, nlohmann::json meta, std::string& error);
  // A finished task (any thread): variant, cell, its outcome and figures.
  void add(int variant, int cell, bool completed, const nlohmann::json& figures);
  // Publishes {"type": "sweep", done, failed, total, elapsed_s, reused, "tasks": [...]}.
  void publish(std::int64_t done, std::int64_t failed, double elapsed_s, bool ended);
  // After the merge: the final state, then serve as the options say.
  void finish(std::int64_t done, std::int64_t failed, double elapsed_s, const nlohmann::json& summary);

 private:
  explicit SweepView(const SweepViewOptions& o) : options_(o) {}
  SweepViewOptions options_;
  ViewServer server_;
  nlohmann::json meta_;
  std::mutex mutex_;
  nlohmann::json tasks_ = nlohmann::json::array();
  nlohmann::json summary_;
};

}  // namespace gyrostab::tools::view
