// The live view's server inside: its state and a page's WebSocket session, shared by the three files that
// implement it — view_server.cpp (the server's tick, the public API), view_http_session.cpp (requests, assets,
// the checks before an upgrade) and view_ws_session.cpp (a page's WebSocket). Three files because optimising
// Beast's asynchronous operations is most of their compile time: in one file they took 19-21 s (docs/build.md).
#pragma once

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tools/view/view_server.hpp"
#include "tools/view/view_store.hpp"

namespace gyrostab::tools::view {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

struct WsSession;

struct ViewServer::Impl {
  asio::io_context io;
  tcp::acceptor acceptor{io};
  asio::steady_timer timer{io};
  std::thread thread;
  std::string token;
  std::string host_port;           // as the URL names it
  std::set<std::string> hosts;     // Host header values accepted
  bool any_host{false};            // bound to a wildcard address: any Host, the token decides
  bool rows_mode{false};           // a run's (or a bus's) rows, not snapshots
  std::vector<std::unique_ptr<ViewStore>> stores;  // one per channel
  ViewRun run;
  std::string meta;                // the meta message, serialised when the channels' spans change
  std::string page{"index.html"};  // what "/" serves
  // Snapshot mode (no ring): the latest state and its version, set by publish() from any thread.
  std::mutex snap_mutex;
  std::string snapshot;
  std::uint64_t snap_version{0};
  std::vector<std::weak_ptr<WsSession>> sessions;
  std::string end_message;         // set when the run ended
  int frame{0};
  // Rates: ticks per wall second over the last half second or more.
  std::chrono::steady_clock::time_point rate_t0{};
  std::int64_t rate_tick0{0};
  double ticks_per_s{0};
  std::atomic<int> pages{0}, pages_ended{0};

  void accept();
  void tick();
  bool drain();  // true when a store's span changed (a new meta message is due)
  void make_meta();
  std::int64_t last_tick() const;
  nlohmann::json data_message(const std::vector<std::int64_t>& from) const;
  bool host_ok(const std::string& host) const {
    return any_host || hosts.count(host) != 0;
  }
};

// Serves HTTP on an accepted connection until it closes or becomes a page's WebSocket (view_http_session.cpp).
void serve_http(tcp::socket socket, ViewServer::Impl& server);

struct WsSession : std::enable_shared_from_this<WsSession> {
  websocket::stream<beast::tcp_stream> ws;
  ViewServer::Impl& server;
  beast::flat_buffer in;
  std::deque<std::string> out;  // at most a meta, a data and an end message wait
  bool writing{false};
  bool open{false};
  bool got_end{false};
  std::vector<std::int64_t> next_bucket;  // per channel
  std::uint64_t snap_seen{0};
  http::request<http::string_body> upgrade;  // kept until the handshake completes

  WsSession(tcp::socket&& s, ViewServer::Impl& srv) : ws(std::move(s)), server(srv) {}

  void accept(http::request<http::string_body> req);
  // The page may only close: a message from it is taken as a command, which the view does not accept.
  void read();
  void closed();
  bool idle() const { return open && !writing && out.empty(); }
  void send(std::string msg);
  void write_next();
};

}  // namespace gyrostab::tools::view
