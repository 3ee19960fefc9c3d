#include "tools/view/sweep_view.hpp"

#include <chrono>
#include <cstdio>
#include <thread>

#include "tools/log/stop_signal.hpp"

namespace gyrostab::tools::view {

std::unique_ptr<SweepView> SweepView::start(const SweepViewOptions& options, nlohmann::json meta, std::string& error) {
  ViewOptions vo;
  if (error = parse_view_address(options.address, vo); !error.empty()) {
    error = "--view: " + error;
    return nullptr;
  }
  std::unique_ptr<SweepView> v(new SweepView(options));
  meta["type"] = "meta";
  meta["kind"] = "sweep";
  v->meta_ = meta;
  if (!v->server_.start_snapshots(vo, "sweep.html", meta, error)) return nullptr;
  std::fprintf(stderr, "gyrostab sweep: live view at %s\n", v->server_.url().c_str());
  std::fflush(stderr);
  return v;
}

void SweepView::add(int variant, int cell, bool completed, const nlohmann::json& figures) {
  nlohmann::json t{{"variant", variant}, {"cell", cell}, {"ok", completed}};
  if (completed && figures.is_object()) {
    for (const char* k : {"roll_reduction", "stop_contacts", "roll_rms_rad"}) {
      if (figures.contains(k) && figures[k].is_number()) t[k] = figures[k];
    }
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  tasks_.push_back(std::move(t));
}

void SweepView::publish(std::int64_t done, std::int64_t failed, double elapsed_s, bool ended) {
  nlohmann::json state{{"type", "sweep"}, {"done", done}, {"failed", failed}, {"elapsed_s", elapsed_s},
                       {"ended", ended}};
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    state["tasks"] = tasks_;
    if (!summary_.is_null()) state["summary"] = summary_;
  }
  server_.publish(state);
}

void SweepView::finish(std::int64_t done, std::int64_t failed, double elapsed_s, const nlohmann::json& summary) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    summary_ = summary;
  }
  publish(done, failed, elapsed_s, true);
  StopSignalGuard guard;
  if (options_.linger_s < 0) {
    std::fprintf(stderr, "gyrostab sweep: done; the view stays at %s until Ctrl-C\n", server_.url().c_str());
    std::fflush(stderr);
  }
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration<double>(options_.linger_s < 0 ? 1e9 : options_.linger_s);
  while (stop_signal_received() == 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  server_.stop();
}

}  // namespace gyrostab::tools::view
