// The live view's server: HTTP and WebSocket on Boost.Beast, on a thread of its own. It serves the page (static
// files of tools/view/web/ and uPlot from the build's npm tree) and one WebSocket per open page, over which it
// sends, never receives: a "meta" message on connect (view_meta.hpp), then twice a second the buckets
// that changed since that page's last message, the latest row, the status and the rates, and at the end the
// report. A page that is slow to read gets fewer, larger messages (its own bookmark into the store), never
// slows the loop: the loop only pushes into the ring (live_ring.hpp) that this thread drains every 10 ms.
//
// Who may connect: the server binds 127.0.0.1 unless told otherwise; every request must carry the random token
// printed at start (the page's URL has it, like Jupyter's); the Host header must name the server (a page of
// another site that resolves its name to 127.0.0.1 is refused); the WebSocket's Origin must be the page's own
// origin. Anything the page sends over the WebSocket closes it: no command is accepted. Docs: docs/view.md.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/log/signal_channel.hpp"
#include "tools/view/live_ring.hpp"

namespace gyrostab::tools::view {

struct ViewOptions {
  std::string address{"127.0.0.1"};
  unsigned short port{0};  // 0: a free port chosen by the OS
};

// "ADDR:PORT", "ADDR", ":PORT" or "" -> options; "" if well formed, else the problem.
std::string parse_view_address(const std::string& text, ViewOptions& out);

// 32 hex digits from getrandom(2); "" if the OS's random source failed.
std::string random_token();

// One channel the view charts: its signals ("t_s" first) and the ring its rows come through.
struct ViewChannel {
  ChannelInfo info;
  LiveRing* ring{nullptr};  // must outlive the server
  std::string status;       // "fault": the rows' status word is the controller's (msg::FaultBit) — in process,
                            // or an actuator frame's; "sensor": a sensor frame's (msg::SensorStatusBit); "": none
};

// What the server shows of a run: its scene, its channels, its limits and its length.
struct ViewRun {
  std::string source{"run"};     // "run": a loop in this process; "lcm": frames heard on a bus
  nlohmann::json scene;          // report.json "scene" (or what a listener knows of it)
  std::vector<ViewChannel> channels;
  nlohmann::json limits;         // report.json "limits"
  std::int64_t total_ticks{0};   // the run's length; a bus listener's grows with the frames (growable)
  int record_every{1};
  double tick_s{1e-3};
  bool growable{false};
  // Called on the server's thread twice a second: more for the page's "link" panel (a listener's counters).
  std::function<nlohmann::json()> link;
};

class ViewServer {
 public:
  ViewServer();
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  // Binds and starts the thread; false with `error` set.
  bool start(const ViewOptions& options, const ViewRun& run, std::string& error);
  // The other kind of view, for work that is not one loop (a sweep): the page `page` (a file of
  // tools/view/web/), `meta` sent on connect, then the latest publish()ed state whenever it changed.
  bool start_snapshots(const ViewOptions& options, const std::string& page, const nlohmann::json& meta,
                       std::string& error);
  // Any thread: the state every page gets next (10 times a second at most).
  void publish(const nlohmann::json& state);
  // http://ADDR:PORT/?token=...
  std::string url() const;
  // The run ended: the final rows are drained and every page gets {"type": "end", "report": report}.
  void finish(const nlohmann::json& report);
  // Pages connected now.
  int pages() const;
  // Pages that have received the end message.
  int pages_ended() const;
  void stop();

  struct Impl;  // the server's state, on its thread (view_server_impl.hpp)

 private:
  bool listen(const ViewOptions& options, std::string& error);
  std::unique_ptr<Impl> impl_;
};

// Where the page's files are: tools/view/web/ in the checkout, uPlot in the build's npm tree.
std::string view_web_dir();
std::string view_uplot_dir();

}  // namespace gyrostab::tools::view
