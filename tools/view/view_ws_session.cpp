#include <cstddef>
#include <string>
#include <utility>

#include "tools/view/view_server_impl.hpp"

namespace gyrostab::tools::view {

void WsSession::accept(http::request<http::string_body> req) {
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
void WsSession::read() {
  ws.async_read(in, [self = shared_from_this()](beast::error_code ec, std::size_t) {
    if (ec) {
      self->closed();
      return;
    }
    self->ws.async_close(websocket::close_reason(websocket::close_code::policy_error, "the view accepts no command"),
                         [self](beast::error_code) { self->closed(); });
  });
}

void WsSession::closed() {
  if (open) --server.pages;
  open = false;
}

void WsSession::send(std::string msg) {
  out.push_back(std::move(msg));
  if (!writing) write_next();
}

void WsSession::write_next() {
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

}  // namespace gyrostab::tools::view
