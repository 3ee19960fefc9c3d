// `gyrostab view --lcm-url URL`: a passive listener on a running plant ⇄ controller bus. It never sends: not
// through LCM's library either, whose udpm receiver publishes a self-test message on the bus when it subscribes
// (lcm_udpm.c, udpm_self_test) — so the listener reads the bus with a socket of its own: bound to the URL's
// multicast group and port, joined to the group (the kernel answers the group's membership queries, IGMP, as for
// any receiver), and only ever read (recvmmsg). It parses LCM's datagram format (the "LC02" short message: magic,
// sequence number, channel name, payload; fragmented "LC03" messages are counted, not read: no gyrostab frame is
// that long) and decodes the frames on GYROSTAB_SENSOR<suffix> and GYROSTAB_ACTUATOR<suffix> with the codec of
// the device's signal table (hil/lcm/frame_codec.hpp).
//
// Which frames are shown: those of one session (the first heard; a new one replaces it once the current one has
// been silent for 2 s — a new run on the bus, marked kNewRun so the view starts again) and, per direction, of the
// first sender heard in it. With a key (--key-file), a frame is shown only when its MAC verifies (SipHash-2-4
// over the frame, firmware/link/secoc.hpp, with the direction's data id) and its freshness value is newer than
// the last shown one; the rest are counted as refused (bad MAC, replayed) and never reach the page. Without a
// key every frame of the session is shown, marked as not authenticated (the page says so).
//
// Threads: the listener's own thread reads the socket in batches (recvmmsg, then a pause of kBatchPause so that
// one wake-up takes many datagrams: the listener's CPU competes with the loop's on a small machine) and pushes
// each frame as a row — t_s (the frame's time_ns), then frame_values() — into the direction's ring
// (tools/view/live_ring.hpp), which the view's server drains.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "firmware/link/secoc.hpp"
#include "firmware/msg/signal_spec.hpp"
#include "tools/view/live_ring.hpp"

namespace gyrostab::tools::view {

struct UdpmAddress {
  std::string group;     // dotted IPv4 multicast address
  unsigned short port{0};
};
// "udpm://GROUP:PORT[?options]" (LCM's form; the options — ttl, recv_buf_size — concern senders and LCM's own
// receiver and are ignored here). "" if well formed, else the problem.
std::string parse_udpm_url(const std::string& url, UdpmAddress& out);

struct ListenerOptions {
  std::string url;
  std::optional<firmware::link::Key128> key;
  std::string channel_suffix;          // with suffix_given: exactly GYROSTAB_SENSOR<suffix>, ...
  bool suffix_given{false};            // else: the suffix of the first frame heard
  const msg::DeviceSignals* device{nullptr};  // known from --scene; nullptr: learnt from the first frame's type
};

// One direction's counts (written by the listener's thread, read by any).
struct DirectionCounts {
  std::atomic<std::uint64_t> received{0};        // decoded frames on the direction's channel
  std::atomic<std::uint64_t> shown{0};           // pushed to the view
  std::atomic<std::uint64_t> bad_mac{0};         // with a key: the MAC does not verify
  std::atomic<std::uint64_t> replayed{0};        // with a key: freshness not newer than the last shown
  std::atomic<std::uint64_t> other_session{0};   // another session, or another sender in this one
  std::atomic<std::uint64_t> undecodable{0};     // wrong size or type fingerprint (another device or version)
  std::atomic<std::uint64_t> ring_full{0};       // shown frames the view's ring had no room for
  std::atomic<std::uint64_t> end_of_run{0};      // the run's end-of-run frame and its answer (and their copies):
                                                 // verified like the others, not charted (their values are not
                                                 // the loop's: docs/protocol.md)
};

class LcmListener {
 public:
  static constexpr int kBatchPauseMs = 5;

  LcmListener() = default;
  ~LcmListener();
  LcmListener(const LcmListener&) = delete;
  LcmListener& operator=(const LcmListener&) = delete;

  // Opens the socket (bind, join); false with `error` set.
  bool open(const ListenerOptions& options, std::string& error);
  // Before start(): reads until a frame tells the device (unless known) and the tick length (a frame with
  // tick > 0: time_ns / tick), or `should_stop()` returns true (polled every 100 ms). The frames read meanwhile are
  // kept and shown first. nullptr when stopped.
  const msg::DeviceSignals* learn(bool (*should_stop)(), std::int64_t& tick_ns);
  // Starts the thread: frames go to the two rings (width 1 + frame_width(device, direction) each).
  void start(LiveRing& sensor, LiveRing& actuator);
  void stop();

  // The page's "link" panel (any thread).
  nlohmann::json link_json() const;
  // Every count, for the summary printed at exit (any thread).
  nlohmann::json summary_json() const;
  const DirectionCounts& sensor_counts() const { return sensor_; }
  const DirectionCounts& actuator_counts() const { return actuator_; }

 private:
  struct Datagram {
    std::vector<std::uint8_t> bytes;
  };
  void run();
  // One datagram: parse, match the channel, decode, judge, push.
  void take(const std::uint8_t* data, std::size_t size);
  bool channel_of(const char* name, int& direction);  // 0 sensor, 1 actuator; false: not a frame channel of ours

  ListenerOptions o_;
  int fd_{-1};
  std::thread thread_;
  std::atomic<bool> stopping_{false};
  LiveRing* rings_[2]{nullptr, nullptr};
  const msg::DeviceSignals* device_{nullptr};
  std::vector<Datagram> pending_;  // read by learn(), taken first by the thread
  std::vector<double> row_;
  // Which frames are shown: the session and each direction's sender (the listener's thread only).
  bool bound_{false};
  std::uint64_t session_{0};
  std::uint64_t sender_[2]{0, 0};
  std::uint64_t freshness_[2]{0, 0};
  std::int64_t last_heard_ns_{0};
  bool new_run_[2]{true, true};
  // Counts.
  DirectionCounts sensor_, actuator_;
  std::atomic<std::uint64_t> datagrams_{0}, other_channels_{0}, fragmented_{0}, not_lcm_{0};
  std::atomic<std::uint64_t> kernel_drops_{0};
  std::atomic<std::uint64_t> sessions_{0};
  std::atomic<std::uint64_t> session_now_{0};
  mutable std::mutex text_mutex_;
  std::string suffix_;  // the channel suffix listened to
};

}  // namespace gyrostab::tools::view
