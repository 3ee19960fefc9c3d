#include "tools/view/view_server.hpp"

#include <sys/random.h>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "tools/build_paths.hpp"
#include "tools/view/view_meta.hpp"
#include "tools/view/view_store.hpp"

namespace gyrostab::tools::view {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

std::string parse_view_address(const std::string& text, ViewOptions& out) {
  ViewOptions o;
  std::string host = text, port;
  if (!text.empty() && text.front() == '[') {  // [v6]:port
    const auto close = text.find(']');
    if (close == std::string::npos) return "expected ADDR:PORT, e.g. 127.0.0.1:8080";
    host = text.substr(1, close - 1);
    if (close + 1 < text.size()) {
      if (text[close + 1] != ':') return "expected [ADDR]:PORT";
      port = text.substr(close + 2);
    }
  } else if (const auto colon = text.rfind(':'); colon != std::string::npos) {
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
  }
  if (!host.empty()) {
    boost::system::error_code ec;
    asio::ip::make_address(host, ec);
    if (ec) return "\"" + host + "\" is not an IP address (the view binds an address, not a name)";
    o.address = host;
  }
  if (!port.empty()) {
    char* end = nullptr;
    const long p = std::strtol(port.c_str(), &end, 10);
    if (*end != '\0' || p < 0 || p > 65535) return "\"" + port + "\" is not a port (0-65535)";
    o.port = static_cast<unsigned short>(p);
  }
  out = o;
  return "";
}

std::string random_token() {
  unsigned char b[16];
  std::size_t got = 0;
  while (got < sizeof b) {
    const ssize_t n = ::getrandom(b + got, sizeof b - got, 0);
    if (n <= 0) return "";
    got += static_cast<std::size_t>(n);
  }
  static const char* hex = "0123456789abcdef";
  std::string t;
  for (unsigned char c : b) {
    t += hex[c >> 4];
    t += hex[c & 15];
  }
  return t;
}

std::string view_web_dir() { return std::string(build_source_dir()) + "/tools/view/web"; }
std::string view_uplot_dir() { return std::string(build_npm_dir()) + "/uplot/dist"; }

namespace {

bool same_token(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

std::string query_value(std::string_view target, std::string_view key) {
  const auto q = target.find('?');
  if (q == std::string_view::npos) return "";
  std::string_view rest = target.substr(q + 1);
  while (!rest.empty()) {
    const auto amp = rest.find('&');
    const std::string_view pair = rest.substr(0, amp);
    const auto eq = pair.find('=');
    if (eq != std::string_view::npos && pair.substr(0, eq) == key) return std::string(pair.substr(eq + 1));
    if (amp == std::string_view::npos) break;
    rest = rest.substr(amp + 1);
  }
  return "";
}

std::string read_file(const std::string& path, bool& ok) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  ok = static_cast<bool>(f);
  return s.str();
}

struct Asset {
  const char* path;
  const char* file;
  const char* type;
  bool uplot;
};
constexpr Asset kAssets[] = {
    {"/", "index.html", "text/html; charset=utf-8", false},  // or the snapshot view's page
    {"/view.js", "view.js", "text/javascript; charset=utf-8", false},
    {"/sweep.js", "sweep.js", "text/javascript; charset=utf-8", false},
    {"/view.css", "view.css", "text/css; charset=utf-8", false},
    {"/uPlot.iife.min.js", "uPlot.iife.min.js", "text/javascript; charset=utf-8", true},
    {"/uPlot.min.css", "uPlot.min.css", "text/css; charset=utf-8", true},
};

}  // namespace

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

  void accept(http::request<http::string_body> req) {
    ws.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(http::field::server, "gyrostab-view"); }));
    ws.read_message_max(4096);
    upgrade = std::move(req);
    ws.async_accept(upgrade, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->open = true;
      ++self->server.pages;
      self->next_bucket.assign(self->server.stores.size(), 0);
      self->send(self->server.meta);
      self->read();
    });
  }
  // The page may only close: a message from it is taken as a command, which the view does not accept.
  void read() {
    ws.async_read(in, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        self->closed();
        return;
      }
      self->ws.async_close(websocket::close_reason(websocket::close_code::policy_error, "the view accepts no command"),
                           [self](beast::error_code) { self->closed(); });
    });
  }
  void closed() {
    if (open) --server.pages;
    open = false;
  }
  bool idle() const { return open && !writing && out.empty(); }
  void send(std::string msg) {
    out.push_back(std::move(msg));
    if (!writing) write_next();
  }
  void write_next() {
    if (out.empty() || !open) {
      writing = false;
      return;
    }
    writing = true;
    ws.text(true);
    ws.async_write(asio::buffer(out.front()), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      self->out.pop_front();
      if (ec) {
        self->writing = false;
        self->closed();
        return;
      }
      self->write_next();
    });
  }
};

struct HttpSession : std::enable_shared_from_this<HttpSession> {
  beast::tcp_stream stream;
  ViewServer::Impl& server;
  beast::flat_buffer buffer;
  http::request<http::string_body> req;

  HttpSession(tcp::socket&& s, ViewServer::Impl& srv) : stream(std::move(s)), server(srv) {}

  void read() {
    req = {};
    stream.expires_after(std::chrono::seconds(30));
    http::async_read(stream, buffer, req, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        beast::error_code ignored;
        self->stream.socket().shutdown(tcp::socket::shutdown_send, ignored);
        return;
      }
      self->handle();
    });
  }

  void reply(http::status status, std::string body, const char* type) {
    auto res = std::make_shared<http::response<http::string_body>>(status, req.version());
    res->set(http::field::server, "gyrostab-view");
    res->set(http::field::content_type, type);
    res->set(http::field::cache_control, "no-store");
    res->set("X-Content-Type-Options", "nosniff");
    res->set("Referrer-Policy", "no-referrer");  // the token stays out of any Referer
    res->set("X-Frame-Options", "DENY");
    res->set("Content-Security-Policy",
             "default-src 'self'; connect-src 'self'; img-src 'self' data:; style-src 'self' 'unsafe-inline'");
    res->keep_alive(req.keep_alive());
    res->body() = std::move(body);
    res->prepare_payload();
    http::async_write(stream, *res, [self = shared_from_this(), res](beast::error_code ec, std::size_t) {
      if (ec || !res->keep_alive()) {
        beast::error_code ignored;
        self->stream.socket().shutdown(tcp::socket::shutdown_send, ignored);
        return;
      }
      self->read();
    });
  }

  void handle() {
    const std::string target(req.target());
    const std::string path = target.substr(0, target.find('?'));
    if (!server.host_ok(std::string(req[http::field::host]))) {
      reply(http::status::forbidden, "forbidden: unknown Host\n", "text/plain");
      return;
    }
    const bool token_ok = same_token(query_value(target, "token"), server.token);
    if (websocket::is_upgrade(req)) {
      const std::string origin(req[http::field::origin]);
      const std::string own = "http://" + std::string(req[http::field::host]);
      if (path != "/ws" || !token_ok || origin != own) {
        reply(http::status::forbidden, "forbidden: wrong token or origin\n", "text/plain");
        return;
      }
      // Registered on the server's own thread (this one), read by tick().
      server.sessions.erase(std::remove_if(server.sessions.begin(), server.sessions.end(),
                                           [](const std::weak_ptr<WsSession>& w) { return w.expired(); }),
                            server.sessions.end());
      auto ws = std::make_shared<WsSession>(stream.release_socket(), server);
      server.sessions.push_back(ws);
      ws->accept(std::move(req));
      return;
    }
    if (req.method() != http::verb::get) {
      reply(http::status::method_not_allowed, "only GET\n", "text/plain");
      return;
    }
    for (const Asset& a : kAssets) {
      if (path != a.path) continue;
      if (path == "/" && !token_ok) {
        reply(http::status::forbidden, "forbidden: open the URL gyrostab printed, with its token\n", "text/plain");
        return;
      }
      bool ok = false;
      const std::string file = path == "/" ? server.page : a.file;
      std::string body = read_file((a.uplot ? view_uplot_dir() : view_web_dir()) + "/" + file, ok);
      if (!ok) {
        reply(http::status::not_found,
              std::string(a.file) + " not found" + (a.uplot ? " (uPlot: run tools/setup, which installs it)" : "") + "\n",
              "text/plain");
        return;
      }
      reply(http::status::ok, std::move(body), a.type);
      return;
    }
    reply(http::status::not_found, "not found\n", "text/plain");
  }
};

void ViewServer::Impl::accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket s) {
    if (ec) return;  // closed
    auto h = std::make_shared<HttpSession>(std::move(s), *this);
    h->read();
    accept();
  });
}

bool ViewServer::Impl::drain() {
  bool span_changed = false;
  for (std::size_t c = 0; c < stores.size(); ++c) {
    ViewStore& store = *stores[c];
    run.channels[c].ring->drain([&](const RowHeader& h, const double* v) {
      if ((h.flags & kNewRun) != 0 && store.rows() > 0) {
        store.clear();
        span_changed = true;
      }
      span_changed = store.add(h, v) || span_changed;
    });
  }
  return span_changed;
}

void ViewServer::Impl::make_meta() {
  std::vector<ChannelMeta> ch;
  for (std::size_t c = 0; c < stores.size(); ++c) {
    ch.push_back({&run.channels[c].info, run.channels[c].status, stores[c]->buckets(), stores[c]->span_ticks()});
  }
  meta = meta_message(run.source, run.scene, ch, run.limits, run.tick_s)
             .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::int64_t ViewServer::Impl::last_tick() const {
  std::int64_t t = 0;
  for (const auto& s : stores)
    if (s->rows() > 0) t = std::max(t, s->last_header().tick);
  return t;
}

nlohmann::json ViewServer::Impl::data_message(const std::vector<std::int64_t>& from) const {
  nlohmann::json channels = nlohmann::json::array();
  for (std::size_t c = 0; c < stores.size(); ++c) {
    const ViewStore& store = *stores[c];
    const RowHeader& h = store.last_header();
    nlohmann::json latest = nlohmann::json(nullptr);
    if (store.rows() > 0) {
      nlohmann::json values = nlohmann::json::array();
      for (double v : store.last_values()) values.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
      latest = {{"tick", h.tick}, {"values", values}, {"flags", h.flags}};
      if (!run.channels[c].status.empty()) {
        latest["status"] = h.status;
        latest["safe"] = (h.flags & kSafe) != 0;
      }
    }
    channels.push_back({{"buckets", store.buckets_json(c < from.size() ? from[c] : 0)},
                        {"latest", latest},
                        {"rows", store.rows()},
                        {"status_seen", store.status_seen()},
                        {"safe_rows", store.safe_rows()},
                        {"dropped", run.channels[c].ring->dropped()}});
  }
  const std::int64_t t = last_tick();
  nlohmann::json progress = nlohmann::json(nullptr);
  if (!run.growable && run.total_ticks > 0) progress = static_cast<double>(t) / static_cast<double>(run.total_ticks);
  return {{"type", "data"},
          {"channels", channels},
          {"ticks_per_s", ticks_per_s},
          {"real_time_factor", ticks_per_s * run.tick_s},
          {"progress", progress},
          {"link", run.link ? run.link() : nlohmann::json(nullptr)},
          {"ended", !end_message.empty()}};
}

void ViewServer::Impl::tick() {
  if (!rows_mode) {  // snapshot mode
    if (++frame % 10 == 0) {
      std::string snap;
      std::uint64_t version = 0;
      {
        const std::lock_guard<std::mutex> lock(snap_mutex);
        version = snap_version;
        if (version != 0) snap = snapshot;
      }
      for (auto& w : sessions) {
        auto s = w.lock();
        if (!s || !s->idle() || s->snap_seen == version || version == 0) continue;
        s->send(snap);
        s->snap_seen = version;
      }
    }
    timer.expires_after(std::chrono::milliseconds(10));
    timer.async_wait([this](beast::error_code ec) {
      if (!ec) tick();
    });
    return;
  }
  if (drain()) {
    // A span grew or a new run began: every page starts again from the new meta message.
    make_meta();
    for (auto& w : sessions) {
      auto s = w.lock();
      if (!s || !s->open || s->got_end) continue;
      s->send(meta);
      s->next_bucket.assign(stores.size(), 0);
    }
  }
  const auto now = std::chrono::steady_clock::now();
  // Every 500 ms: 2 page updates a second (a page redraws at most once a second while a run goes on; more
  // messages would only cost the server's and the browser's CPU, which the loop shares on a small machine).
  if (++frame % 50 == 0) {
    const std::int64_t t = last_tick();
    const double dt = std::chrono::duration<double>(now - rate_t0).count();
    if (dt >= 0.5) {
      if (end_message.empty()) ticks_per_s = t >= rate_tick0 ? static_cast<double>(t - rate_tick0) / dt : 0.0;
      rate_t0 = now;
      rate_tick0 = t;
    }
    for (auto& w : sessions) {
      auto s = w.lock();
      if (!s || !s->idle()) continue;  // a page still reading its last message skips this frame
      if (s->got_end) continue;
      s->send(data_message(s->next_bucket).dump());
      for (std::size_t c = 0; c < stores.size() && c < s->next_bucket.size(); ++c) {
        s->next_bucket[c] = std::max<std::int64_t>(stores[c]->last_bucket(), 0);
      }
      if (!end_message.empty()) {
        s->send(end_message);
        s->got_end = true;
        ++pages_ended;
      }
    }
  }
  timer.expires_after(std::chrono::milliseconds(10));
  timer.async_wait([this](beast::error_code ec) {
    if (!ec) tick();
  });
}

ViewServer::ViewServer() : impl_(std::make_unique<Impl>()) {}
ViewServer::~ViewServer() { stop(); }

bool ViewServer::start(const ViewOptions& options, const ViewRun& run, std::string& error) {
  Impl& s = *impl_;
  s.rows_mode = true;
  s.run = run;
  for (const ViewChannel& c : run.channels) {
    s.stores.push_back(std::make_unique<ViewStore>(run.total_ticks, run.record_every, c.ring->width(), run.growable));
  }
  s.make_meta();
  return listen(options, error);
}

bool ViewServer::start_snapshots(const ViewOptions& options, const std::string& page, const nlohmann::json& meta,
                                 std::string& error) {
  Impl& s = *impl_;
  s.page = page;
  s.meta = meta.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return listen(options, error);
}

void ViewServer::publish(const nlohmann::json& state) {
  Impl& s = *impl_;
  std::string text = state.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  const std::lock_guard<std::mutex> lock(s.snap_mutex);
  s.snapshot = std::move(text);
  ++s.snap_version;
}

bool ViewServer::listen(const ViewOptions& options, std::string& error) {
  Impl& s = *impl_;
  s.token = random_token();
  if (s.token.empty()) {
    error = "the OS's random source (getrandom) failed: no token for the view";
    return false;
  }
  boost::system::error_code ec;
  const auto addr = asio::ip::make_address(options.address, ec);
  if (ec) {
    error = "view address " + options.address + ": " + ec.message();
    return false;
  }
  const tcp::endpoint ep(addr, options.port);
  s.acceptor.open(ep.protocol(), ec);
  if (!ec) s.acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) s.acceptor.bind(ep, ec);
  if (!ec) s.acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    error = "cannot serve the view on " + options.address + ":" + std::to_string(options.port) + ": " + ec.message();
    return false;
  }
  const unsigned short port = s.acceptor.local_endpoint().port();
  const std::string p = std::to_string(port);
  const std::string a = addr.is_v6() ? "[" + addr.to_string() + "]" : addr.to_string();
  s.host_port = a + ":" + p;
  s.hosts.insert(s.host_port);
  if (addr.is_loopback()) {
    s.hosts.insert("localhost:" + p);
    s.hosts.insert("127.0.0.1:" + p);
    s.hosts.insert("[::1]:" + p);
  }
  s.any_host = addr.is_unspecified();
  s.rate_t0 = std::chrono::steady_clock::now();
  s.accept();
  s.tick();
  s.thread = std::thread([&s] { s.io.run(); });
  return true;
}

std::string ViewServer::url() const {
  const std::string host = impl_->any_host ? "127.0.0.1:" + std::to_string(impl_->acceptor.local_endpoint().port())
                                           : impl_->host_port;
  return "http://" + host + "/?token=" + impl_->token;
}

void ViewServer::finish(const nlohmann::json& report) {
  Impl& s = *impl_;
  nlohmann::json msg{{"type", "end"}, {"report", report}};
  std::string text = msg.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  asio::post(s.io, [&s, text = std::move(text)] {
    s.drain();
    s.end_message = text;
  });
}

int ViewServer::pages() const { return impl_->pages.load(); }
int ViewServer::pages_ended() const { return impl_->pages_ended.load(); }

void ViewServer::stop() {
  Impl& s = *impl_;
  if (!s.thread.joinable()) return;
  asio::post(s.io, [&s] {
    beast::error_code ec;
    s.acceptor.close(ec);
    s.timer.cancel();
    s.io.stop();
  });
  s.thread.join();
}

}  // namespace gyrostab::tools::view
