// `gyrostab run SCENE --view [ADDR:PORT]`: the live view of a run, for every run mode whose process has the
// plant (in process; the plant process of LCM, CAN and the emulated target). start() before tick 0: the ring is
// sized, the server binds and its URL with the token is printed; sink() is the loop's RowSink; finish() after
// the outputs are written sends the report to the pages and keeps serving as the request says.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/devices/device.hpp"
#include "tools/loop/closed_loop.hpp"
#include "tools/run/run_output.hpp"
#include "tools/view/live_feed.hpp"
#include "tools/view/view_server.hpp"

namespace gyrostab::tools::view {

// Rows the ring holds: it is drained every 10 ms, so 65 536 rows hold the rows of a loop that records up to
// 6.5 million rows a second (every tick at 6.5 MHz); beyond that the view drops rows, the run none.
inline constexpr std::size_t kRingRows = std::size_t{1} << 16;

class RunView {
 public:
  // nullptr and `error` set when the view cannot start (the run is then refused, before tick 0).
  static std::unique_ptr<RunView> start(const DeviceScene& scene, const RunRequest& req, const Recorder& rec,
                                        const ControllerPort* controller, std::int64_t ticks, std::string& error);
  ~RunView();
  RowSink* sink() { return &feed_; }
  // Sends the report to the pages, then serves until req.view.linger_s has passed or SIGINT/SIGTERM.
  void finish(const nlohmann::json& report);

 private:
  RunView(const RunRequest& req, std::size_t width, const ControllerPort* controller);
  const RunRequest& req_;
  LiveRing ring_;
  LiveFeed feed_;
  ViewServer server_;
};

// "" if the --view options are well formed, else the problem.
std::string view_options_problem(const RunRequest& req);

}  // namespace gyrostab::tools::view
