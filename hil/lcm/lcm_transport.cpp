#include "hil/lcm/lcm_transport.hpp"

#include <lcm/lcm.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace gyrostab::hil {

bool valid_channel_suffix(const std::string& suffix) {
  if (suffix.size() > 40) return false;
  for (const char c : suffix) {
    const bool ok =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

LcmTransport::~LcmTransport() {
  if (tx_lcm_ != nullptr && tx_lcm_ != lcm_) lcm_destroy(tx_lcm_);
  if (lcm_ != nullptr) {
    if (sub_ != nullptr) lcm_unsubscribe(lcm_, sub_);
    lcm_destroy(lcm_);
  }
}

bool LcmTransport::open(const std::string& url, const std::string& tx_channel, const std::string& rx_channel,
                        int queue_capacity, std::string& error, const std::string& tx_url) {
  url_ = url;
  tx_channel_ = tx_channel;
  rx_channel_ = rx_channel;
  // LCM's receive thread starts inside lcm_create/lcm_subscribe/lcm_get_fileno and inherits this thread's
  // signal mask: with SIGINT/SIGTERM blocked there, a stop request always reaches the loop's thread (and
  // interrupts its ppoll) instead of being taken by LCM's thread.
  sigset_t stop_signals, previous;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, &previous);
  const bool ok = open_blocked(url, rx_channel, queue_capacity, error);
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (!ok) return false;
  tx_lcm_ = lcm_;
  if (!tx_url.empty() && tx_url != url) {
    // Send-only: LCM starts no receive thread for an instance that never subscribes.
    tx_lcm_ = lcm_create(tx_url.c_str());
    if (tx_lcm_ == nullptr) {
      error = "cannot open LCM at " + tx_url;
      return false;
    }
  }
  warm_up();
  return true;
}

namespace {
extern "C" void ignore_message(const lcm_recv_buf_t*, const char*, void*) {}
}  // namespace

void LcmTransport::warm_up() {
  // LCM 1.3.1 initialises a GLib mutex inside the first lcm_handle() of an lcm_t (an allocation, seen with
  // gdb): take that first call here, at start-up, on one message to ourselves on a channel of our own. If it
  // does not come back within 0.5 s (no multicast loop-back), the first real message pays instead.
  char channel[64];
  std::snprintf(channel, sizeof channel, "GYROSTAB_WARMUP_%d_%p", static_cast<int>(getpid()),
                static_cast<void*>(this));
  lcm_subscription_t* w = lcm_subscribe(lcm_, channel, &ignore_message, nullptr);
  if (w == nullptr) return;
  const std::uint8_t byte = 0;
  if (lcm_publish(lcm_, channel, &byte, 1) == 0) {
    pollfd p{fd_, POLLIN, 0};
    const timespec half_second{0, 500'000'000};
    if (ppoll(&p, 1, &half_second, nullptr) > 0) lcm_handle(lcm_);
  }
  lcm_unsubscribe(lcm_, w);
}

bool LcmTransport::open_blocked(const std::string& url, const std::string& rx_channel, int queue_capacity,
                                std::string& error) {
  lcm_ = lcm_create(url.c_str());
  if (lcm_ == nullptr) {
    error = "cannot open LCM at " + url +
            " (no multicast route? inside a private network namespace run: ip link set lo up; ip link set lo "
            "multicast on; ip route add 224.0.0.0/4 dev lo)";
    return false;
  }
  sub_ = lcm_subscribe(lcm_, rx_channel.c_str(), &LcmTransport::on_message, this);
  if (sub_ == nullptr) {
    error = "cannot subscribe to LCM channel " + rx_channel;
    return false;
  }
  if (lcm_subscription_set_queue_capacity(sub_, queue_capacity) != 0) {
    error = "cannot set the LCM queue capacity of " + rx_channel;
    return false;
  }
  fd_ = lcm_get_fileno(lcm_);
  if (fd_ < 0) {
    error = "LCM provider of " + url + " has no file descriptor to wait on";
    return false;
  }
  return true;
}

bool LcmTransport::publish(const std::uint8_t* data, int size) {
  return lcm_publish(tx_lcm_, tx_channel_.c_str(), data, static_cast<unsigned int>(size)) == 0;
}

void LcmTransport::on_message(const lcm_recv_buf_t* rbuf, const char*, void* self) {
  auto* t = static_cast<LcmTransport*>(self);
  t->ready_ = true;
  // LCM's largest message is far below 2^31 bytes (LCM_MAX_MESSAGE_SIZE).
  t->size_ = static_cast<int>(rbuf->data_size);
  t->oversize_ = rbuf->data_size > t->buffer_.size();
  if (!t->oversize_) std::memcpy(t->buffer_.data(), rbuf->data, rbuf->data_size);
}

RxStatus LcmTransport::receive(std::int64_t deadline_ns, Message& out) {
  for (;;) {
    if (ready_) {  // handled earlier (by warm_up's lcm_handle, or the loop below)
      ready_ = false;
      out.data = oversize_ ? nullptr : buffer_.data();
      out.size = size_;
      return RxStatus::kMessage;
    }
    pollfd p{fd_, POLLIN, 0};
    int n = 0;
    if (deadline_ns == kNoDeadline) {
      n = ppoll(&p, 1, nullptr, nullptr);
    } else {
      const std::int64_t left = deadline_ns - monotonic_ns();
      const timespec ts = to_timespec(left > 0 ? left : 0);
      n = ppoll(&p, 1, &ts, nullptr);
    }
    if (n < 0) {
      // A signal (a stop request): return so that the loop can look at it; the caller's wait goes on if not.
      if (errno == EINTR) return RxStatus::kInterrupted;
      return RxStatus::kError;
    }
    if (n == 0) return RxStatus::kTimeout;
    if (lcm_handle(lcm_) != 0) return RxStatus::kError;
    // Not ready: the message was for no current subscription (the warm-up channel); wait on.
  }
}

}  // namespace gyrostab::hil
