#include "tools/view/run_view.hpp"

#include <chrono>
#include <cstdio>
#include <thread>

#include "tools/log/stop_signal.hpp"
#include "tools/run/run_output.hpp"
#include "tools/signals/device_outputs.hpp"

namespace gyrostab::tools::view {

std::string view_options_problem(const RunRequest& req) {
  if (!req.view.enabled) return "";
  ViewOptions o;
  if (const std::string bad = parse_view_address(req.view.address, o); !bad.empty()) return "--view: " + bad;
  if (!(req.view.wait_s >= 0)) return "--view-wait must be >= 0 seconds";
  return "";
}

RunView::RunView(const RunRequest& req, std::size_t width, const ControllerPort* controller)
    : req_(req), ring_(width, kRingRows), feed_(ring_, controller) {}

RunView::~RunView() { server_.stop(); }

std::unique_ptr<RunView> RunView::start(const DeviceScene& scene, const RunRequest& req, const Recorder& rec,
                                        const ControllerPort* controller, std::int64_t ticks, std::string& error) {
  ViewOptions options;
  if (error = parse_view_address(req.view.address, options); !error.empty()) {
    error = "--view: " + error;
    return nullptr;
  }
  const LoopConfig& loop = scene.loop();
  std::unique_ptr<RunView> v(new RunView(req, rec.width(), controller));
  ViewRun run;
  run.scene = scene_summary(loop, req.scene_path);
  ViewChannel signals;
  signals.info = ChannelInfo{"/gyrostab/signals", "gyrostab.signals." + loop.device,
                             signals_of_columns(rec.columns(), find_device_outputs(loop.device))};
  signals.ring = &v->ring_;
  signals.status = controller != nullptr ? "fault" : "";
  run.channels.push_back(std::move(signals));
  run.limits = scene.limits();
  run.total_ticks = ticks;
  run.record_every = loop.record_every;
  run.tick_s = loop.tick_s();
  if (!v->server_.start(options, run, error)) return nullptr;
  std::fprintf(stderr, "gyrostab: live view of %s at %s\n", loop.name.c_str(), v->server_.url().c_str());
  std::fflush(stderr);
  if (req.view.wait_s > 0) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(req.view.wait_s);
    while (v->server_.pages() == 0 && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  return v;
}

void RunView::finish(const nlohmann::json& report) {
  server_.finish(final_report(report));
  StopSignalGuard guard;  // SIGINT/SIGTERM end the serving, not the process half way
  // Every open page gets the end message before anything else (a page keeps showing it once the server is
  // gone); a page that does not read for 2 s is not waited for.
  const auto delivered = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (server_.pages_ended() < server_.pages() && stop_signal_received() == 0 &&
         std::chrono::steady_clock::now() < delivered) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const double linger = req_.view.linger_s;
  if (linger < 0) {
    std::fprintf(stderr, "gyrostab: the run ended; its view stays at %s until Ctrl-C\n", server_.url().c_str());
    std::fflush(stderr);
  }
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(linger < 0 ? 1e9 : linger);
  while (stop_signal_received() == 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  server_.stop();
}

}  // namespace gyrostab::tools::view
