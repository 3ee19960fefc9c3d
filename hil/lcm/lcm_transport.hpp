// The plant ⇄ controller byte transport over LCM's C API (the frame_transport.hpp concept).
//
// Why the C API: LCM's C++ publish<T>() allocates a buffer on every call, and its typed subscriptions decode
// into a fresh message per call. Here the caller encodes into its own buffer (hil/lcm/frame_codec.hpp) and
// lcm_publish() sends it; the receive handler copies the raw bytes into a buffer allocated at open(), and the
// caller decodes them into a preallocated frame.
//
// Threads: with udpm:// LCM runs its own receive thread (it reads the socket and queues datagrams; it may
// allocate: GLib, fragment buffers). That thread is never the loop's thread. The loop thread only calls
// ppoll() on lcm_get_fileno() (LCM's notify pipe), lcm_handle() (takes one queued message and calls our
// handler, which memcpy's it) and lcm_publish() (one sendmsg). After the first message of each channel LCM's
// dispatch path is allocation-free; tests/lcm/lcm_link_test.cpp checks this on the loop thread.
//
// Channels: one receive channel (subscribed, queue capacity set from the constructor: LCM's default of 30
// drops frames at 10 kHz and on fast replays) and one send channel. Channel names are plain identifiers
// (checked by valid_channel_suffix): lcm_subscribe() takes a regular expression.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "hil/link/frame_transport.hpp"

typedef struct _lcm_t lcm_t;
typedef struct _lcm_subscription_t lcm_subscription_t;
typedef struct _lcm_recv_buf_t lcm_recv_buf_t;

namespace gyrostab::hil {

inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";
inline constexpr const char* kSensorChannel = "GYROSTAB_SENSOR";
inline constexpr const char* kActuatorChannel = "GYROSTAB_ACTUATOR";
// Subscription queue: at 10 kHz this is 0.1 s of frames, far more than a lockstep link ever holds (one).
inline constexpr int kLcmQueueCapacity = 1000;

// True if `suffix` may be appended to a channel name: [A-Za-z0-9_-]*, at most 40 characters (LCM channel
// names are at most 63 bytes, and lcm_subscribe treats the name as a regular expression).
bool valid_channel_suffix(const std::string& suffix);

class LcmTransport {
 public:
  LcmTransport() = default;
  ~LcmTransport();
  LcmTransport(const LcmTransport&) = delete;
  LcmTransport& operator=(const LcmTransport&) = delete;

  // Creates the LCM instance for `url`, subscribes `rx_channel` with the given queue capacity and prepares
  // publishing on `tx_channel`. Allocates (start-up only). false with `error` set on failure.
  // `tx_url` non-empty and different from `url`: publish through a second, send-only LCM instance on that URL
  // (a bus per direction: no process receives its own datagrams, see docs/transport.md).
  bool open(const std::string& url, const std::string& tx_channel, const std::string& rx_channel,
            int queue_capacity, std::string& error, const std::string& tx_url = "");

  bool publish(const std::uint8_t* data, int size);
  RxStatus receive(std::int64_t deadline_ns, Message& out);

  const std::string& url() const { return url_; }

 private:
  void warm_up();
  bool open_blocked(const std::string& url, const std::string& rx_channel, int queue_capacity,
                    std::string& error);
  static void on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* self);

  lcm_t* lcm_{nullptr};
  lcm_t* tx_lcm_{nullptr};  // == lcm_ unless the send direction has its own URL
  lcm_subscription_t* sub_{nullptr};
  int fd_{-1};
  std::string url_, tx_channel_, rx_channel_;
  std::array<std::uint8_t, kMaxMessageBytes> buffer_{};
  int size_{0};
  bool oversize_{false};
  bool ready_{false};
};

}  // namespace gyrostab::hil
