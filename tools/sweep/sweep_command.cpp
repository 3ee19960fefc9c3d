#include "tools/sweep/sweep_command.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <vector>

#include "tools/commands.hpp"
#include "tools/devices/device.hpp"
#include "tools/run/output_dir.hpp"
#include "tools/sweep/merge.hpp"
#include "tools/sweep/progress_bar.hpp"
#include "tools/sweep/study_file.hpp"
#include "tools/sweep/study_json.hpp"
#include "tools/sweep/task.hpp"
#include "tools/sweep/task_record.hpp"
#include "tools/sweep/task_runner.hpp"
#include "tools/sweep/task_store.hpp"
#include "tools/view/sweep_view.hpp"

namespace gyrostab::tools::sweep {
namespace {

using Clock = std::chrono::steady_clock;

// The base scene with the study's own keys and the first cell, no variant: a base scene the reader refuses
// would fail every task, so the study is refused instead.
bool base_scene_ok(const Study& s, std::vector<std::string>& problems) {
  Study base = s;
  base.variants = {Variant{"base", {}}};
  const std::string text = task_scene_text(base, Task{});
  SceneReader reader;
  if (reader.parse(text, s.scene_file + " (with the study's keys, first cell)") && read_device_scene(reader)) {
    return true;
  }
  problems = reader.errors();
  return false;
}

struct Timing {
  double setup_s{0.0}, run_s{0.0}, write_s{0.0};
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 == 1 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

bool parse_shard(const std::string& text, long& index, long& count) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == text.size()) return false;
  const std::string a = text.substr(0, slash), b = text.substr(slash + 1);
  const auto digits = [](const std::string& x) {
    return x.size() <= 9 && std::all_of(x.begin(), x.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (!digits(a) || !digits(b)) return false;
  const long i = std::stol(a), n = std::stol(b);
  if (n < 1 || i < 1 || i > n) return false;
  index = i - 1;
  count = n;
  return true;
}

int run_sweep(const SweepRequest& req) {
  long shard = 0, shards = 1;
  if (!req.shard.empty() && !parse_shard(req.shard, shard, shards)) {
    std::fprintf(stderr, "gyrostab sweep: --shard %s: must be I/N with 1 <= I <= N\n", req.shard.c_str());
    return kSweepRefused;
  }
  if (req.out_dir.empty()) {
    std::fprintf(stderr, "gyrostab sweep: --out DIR is required (the study directory)\n");
    return kSweepRefused;
  }
  Study s;
  std::vector<std::string> problems;
  if (!read_study_file(req.study_path, s, problems) || !base_scene_ok(s, problems)) {
    for (const std::string& p : problems) std::fprintf(stderr, "%s\n", p.c_str());
    std::fprintf(stderr, "%s: refused (%zu problem%s); nothing written\n", req.study_path.c_str(), problems.size(),
                 problems.size() == 1 ? "" : "s");
    return kSweepRefused;
  }
  std::string error;
  if (!check_output_dir(req.out_dir, error)) {
    std::fprintf(stderr, "gyrostab sweep: %s\n", error.c_str());
    return kSweepRefused;
  }
  for (const Variant& v : s.variants) {
    std::error_code ec;
    std::filesystem::create_directories(req.out_dir + "/tasks/" + v.name, ec);
    if (ec) {
      std::fprintf(stderr, "gyrostab sweep: cannot create %s/tasks/%s: %s\n", req.out_dir.c_str(), v.name.c_str(),
                   ec.message().c_str());
      return kSweepRefused;
    }
  }
  if (!write_text_atomic(req.out_dir + "/study.json", study_json(s).dump(2) + "\n", error)) {
    std::fprintf(stderr, "gyrostab sweep: %s\n", error.c_str());
    return kSweepRefused;
  }

  // The shard's tasks; those with a valid file are reused, stale or damaged ones reported and rerun.
  std::vector<Task> pending;
  std::int64_t in_shard = 0, reused = 0, reused_failed = 0;
  for (const Task& t : all_tasks(s)) {
    if (t.index % shards != shard) continue;
    ++in_shard;
    const std::string path = task_path(req.out_dir, s, t);
    const StoredTask st = read_task_file(path, definition_hash(s, t, task_scene_text(s, t)));
    if (st.state == Stored::kValid) {
      ++reused;
      if (st.record["outcome"] != kCompleted) ++reused_failed;
      continue;
    }
    if (st.state != Stored::kMissing) {
      std::fprintf(stderr, "gyrostab sweep: %s: %s: %s; running it again\n", path.c_str(),
                   st.state == Stored::kStale ? "stale" : "damaged", st.why.c_str());
    }
    pending.push_back(t);
  }

  // --view: the page shows every task of the shard, the reused ones from the start.
  std::unique_ptr<view::SweepView> live;
  if (req.view) {
    nlohmann::json variants = nlohmann::json::array(), cells = nlohmann::json::array();
    for (const Variant& v : s.variants) variants.push_back(v.name);
    for (const SeaStateCell& c : s.cells) cells.push_back({{"Hs", c.Hs_m}, {"Tp", c.Tp_s}});
    std::string why;
    live = view::SweepView::start({true, req.view_address, req.view_linger_s},
                                  {{"study", s.name}, {"variants", variants}, {"cells", cells},
                                   {"headings", s.heading_count()}, {"seeds", s.seeds_per_cell}, {"total", in_shard}},
                                  why);
    if (!live) {
      std::fprintf(stderr, "gyrostab sweep: %s\n", why.c_str());
      return kSweepRefused;
    }
    for (const Task& t : all_tasks(s)) {
      if (t.index % shards != shard) continue;
      const StoredTask st = read_task_file(task_path(req.out_dir, s, t), definition_hash(s, t, task_scene_text(s, t)));
      if (st.state == Stored::kValid) {
        live->add(t.variant, t.cell, st.record["outcome"] == kCompleted, st.record.value("figures", nlohmann::json()));
      }
    }
  }

  const int jobs = std::max(1, std::min<int>(req.jobs > 0 ? req.jobs : static_cast<int>(std::thread::hardware_concurrency()),
                                             static_cast<int>(std::max<std::size_t>(pending.size(), 1))));
  std::vector<Timing> timing(pending.size());
  std::vector<std::string> failures, write_errors;
  std::mutex messages;
  std::atomic<std::size_t> next{0};
  std::atomic<std::int64_t> done{0}, failed{0};
  const auto worker = [&] {
    for (std::size_t i = next.fetch_add(1); i < pending.size(); i = next.fetch_add(1)) {
      const Task& t = pending[i];
      nlohmann::json record = run_task(s, t);
      timing[i].setup_s = record["timing"]["setup_s"].get<double>();
      timing[i].run_s = record["timing"]["run_s"].get<double>();
      const bool ok = record["outcome"] == kCompleted;
      if (live) live->add(t.variant, t.cell, ok, record.value("figures", nlohmann::json()));
      std::string why;
      if (!ok) why = record["outcome"].get<std::string>() + ": " + (record["reasons"].empty() ? "" : record["reasons"][0].get<std::string>());
      std::string write_error;
      const bool written = write_task_file(task_path(req.out_dir, s, t), std::move(record), timing[i].write_s, write_error);
      if (!ok || !written) {
        const std::lock_guard<std::mutex> lock(messages);
        if (!ok) failures.push_back(t.label(s) + " " + why);
        if (!written) write_errors.push_back(write_error);
      }
      if (!ok) failed.fetch_add(1);
      done.fetch_add(1);
    }
  };
  const Clock::time_point start = Clock::now();
  ProgressBar bar(in_shard, req.quiet);
  {
    std::vector<std::jthread> threads;
    for (int j = 0; j < jobs && !pending.empty(); ++j) threads.emplace_back(worker);
    while (done.load() < static_cast<std::int64_t>(pending.size())) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      bar.update(reused + done.load(), reused_failed + failed.load());
      if (live) {
        live->publish(reused + done.load(), reused_failed + failed.load(),
                      std::chrono::duration<double>(Clock::now() - start).count(), false);
      }
    }
  }
  bar.finish(reused + done.load(), reused_failed + failed.load());
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();

  std::sort(failures.begin(), failures.end());  // threads finish in any order; the report does not
  const std::size_t shown = std::min<std::size_t>(failures.size(), 20);
  for (std::size_t i = 0; i < shown; ++i) std::fprintf(stderr, "  failed: %s\n", failures[i].c_str());
  if (failures.size() > shown) std::fprintf(stderr, "  ... and %zu more\n", failures.size() - shown);
  for (const std::string& e : write_errors) std::fprintf(stderr, "gyrostab sweep: %s\n", e.c_str());

  std::vector<double> overhead, setup, write, run;
  for (const Timing& t : timing) {
    setup.push_back(t.setup_s);
    write.push_back(t.write_s);
    if (t.run_s > 0.0) {
      run.push_back(t.run_s);
      overhead.push_back((t.setup_s + t.write_s) / t.run_s);
    }
  }
  const std::string which = req.shard.empty() ? "" : " (shard " + req.shard + ")";
  std::printf("sweep: %s%s: %lld tasks: %zu run on %d thread%s, %lld reused, %lld failed; %.1f s\n", s.name.c_str(),
              which.c_str(), static_cast<long long>(in_shard), pending.size(), jobs, jobs == 1 ? "" : "s",
              static_cast<long long>(reused), static_cast<long long>(reused_failed + failed.load()), wall_s);
  if (!run.empty()) {
    std::printf("sweep: per task: run %.3f s, setup %.2f ms, write %.2f ms (medians); overhead (setup + write) / run "
                "%.2f %% (median)\n",
                median(run), 1e3 * median(setup), 1e3 * median(write), 100.0 * median(overhead));
  }
  std::fflush(stdout);
  const int run_rc = !write_errors.empty() || reused_failed + failed.load() > 0 ? kSweepTasksFailed : kSweepOk;
  if (!req.shard.empty()) {
    if (live) live->finish(reused + done.load(), reused_failed + failed.load(), wall_s, nullptr);
    return run_rc;
  }
  const int merge_rc = merge_study_dir(req.out_dir, req.quiet);
  if (live) {
    nlohmann::json summary;
    std::ifstream f(req.out_dir + "/results/summary.csv");
    std::string line;
    nlohmann::json rows = nlohmann::json::array();
    while (std::getline(f, line)) rows.push_back(line);
    summary["summary_csv"] = rows;
    live->finish(reused + done.load(), reused_failed + failed.load(), wall_s, summary);
  }
  return merge_rc != kSweepOk ? merge_rc : run_rc;
}

}  // namespace gyrostab::tools::sweep
