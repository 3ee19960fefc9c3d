#include "tools/view/view_server.hpp"

#include <sys/random.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

#include "tools/build_paths.hpp"
#include "tools/view/view_meta.hpp"
#include "tools/view/view_server_impl.hpp"
#include "tools/view/view_store.hpp"

namespace gyrostab::tools::view {

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

void ViewServer::Impl::accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket s) {
    if (ec) return;  // closed
    serve_http(std::move(s), *this);
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
