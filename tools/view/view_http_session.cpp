#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include "tools/view/view_server_impl.hpp"

namespace gyrostab::tools::view {

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

}  // namespace

void serve_http(tcp::socket socket, ViewServer::Impl& server) {
  std::make_shared<HttpSession>(std::move(socket), server)->read();
}

}  // namespace gyrostab::tools::view
