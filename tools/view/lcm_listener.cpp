#include "tools/view/lcm_listener.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <span>

#include "firmware/msg/any_frame.hpp"
#include "firmware/msg/fault_bits.hpp"
#include "gyrostab_signals/all_devices.hpp"
#include "hil/lcm/frame_codec.hpp"
#include "hil/lcm/lcm_transport.hpp"
#include "hil/link/link_guard.hpp"
#include "tools/log/frame_channel.hpp"
#include "tools/run/link_identity.hpp"

namespace gyrostab::tools::view {

namespace {

constexpr std::uint32_t kMagicShort = 0x4c433032;  // "LC02": one datagram, one message
constexpr std::uint32_t kMagicLong = 0x4c433033;   // "LC03": a fragment of a long message
constexpr int kBatch = 64;
constexpr std::size_t kDatagramBytes = 2048;       // every gyrostab frame is far shorter (hil::kMaxEncodedSize)
constexpr std::int64_t kSessionSilenceNs = 2'000'000'000;
constexpr std::size_t kMaxPending = 4096;

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
std::uint64_t be64(const std::uint8_t* p) {
  return (std::uint64_t{be32(p)} << 32) | be32(p + 4);
}

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The channel name and payload of an LCM short message; false for anything else.
bool parse_short(const std::uint8_t* data, std::size_t size, const char*& channel, const std::uint8_t*& payload,
                 std::size_t& payload_size) {
  if (size < 9 || be32(data) != kMagicShort) return false;
  const auto* name = data + 8;
  const void* nul = std::memchr(name, 0, size - 8);
  if (nul == nullptr) return false;
  channel = reinterpret_cast<const char*>(name);
  payload = static_cast<const std::uint8_t*>(nul) + 1;
  payload_size = size - static_cast<std::size_t>(payload - data);
  return true;
}

}  // namespace

std::string parse_udpm_url(const std::string& url, UdpmAddress& out) {
  const std::string scheme = "udpm://";
  if (url.rfind(scheme, 0) != 0) {
    return "--lcm-url " + url + ": the view listens on LCM's UDP multicast provider only (udpm://GROUP:PORT)";
  }
  std::string rest = url.substr(scheme.size());
  rest = rest.substr(0, rest.find('?'));
  const auto colon = rest.rfind(':');
  UdpmAddress a;
  a.group = colon == std::string::npos ? rest : rest.substr(0, colon);
  a.port = 7667;  // LCM's default
  if (colon != std::string::npos) {
    char* end = nullptr;
    const long p = std::strtol(rest.c_str() + colon + 1, &end, 10);
    if (*end != '\0' || p <= 0 || p > 65535) return "--lcm-url " + url + ": not a port after the group";
    a.port = static_cast<unsigned short>(p);
  }
  if (a.group.empty()) a.group = "239.255.76.67";
  in_addr addr{};
  if (inet_pton(AF_INET, a.group.c_str(), &addr) != 1 || !IN_MULTICAST(ntohl(addr.s_addr))) {
    return "--lcm-url " + url + ": " + a.group + " is not an IPv4 multicast group";
  }
  out = a;
  return "";
}

LcmListener::~LcmListener() {
  stop();
  if (fd_ >= 0) ::close(fd_);
}

bool LcmListener::open(const ListenerOptions& options, std::string& error) {
  o_ = options;
  device_ = options.device;
  if (o_.suffix_given) {
    if (!hil::valid_channel_suffix(o_.channel_suffix)) {
      error = "--channel-suffix " + o_.channel_suffix + ": letters, digits, '_' and '-' only, at most 40";
      return false;
    }
    suffix_ = o_.channel_suffix;
  }
  UdpmAddress a;
  if (error = parse_udpm_url(o_.url, a); !error.empty()) return false;
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) {
    error = std::string("cannot create a UDP socket: ") + std::strerror(errno);
    return false;
  }
  const int one = 1;
  ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);  // beside the bus's own processes
  // Room for the datagrams of a batch pause at any tick rate LCM carries (the kernel counts what overflows:
  // SO_RXQ_OVFL, shown on the page).
  const int bytes = 8 << 20;
  if (::setsockopt(fd_, SOL_SOCKET, SO_RCVBUFFORCE, &bytes, sizeof bytes) != 0) {
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);
  }
  ::setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(a.port);
  inet_pton(AF_INET, a.group.c_str(), &addr.sin_addr);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    error = "cannot bind " + a.group + ":" + std::to_string(a.port) + ": " + std::strerror(errno);
    return false;
  }
  ip_mreq mreq{};
  mreq.imr_multiaddr = addr.sin_addr;
  mreq.imr_interface.s_addr = htonl(INADDR_ANY);
  if (::setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq) != 0) {
    error = "cannot join " + a.group + ": " + std::strerror(errno) +
            " (no multicast route? e.g. ip route add 224.0.0.0/4 dev lo)";
    return false;
  }
  return true;
}

bool LcmListener::channel_of(const char* name, int& direction) {
  static constexpr std::string_view kBases[2] = {hil::kSensorChannel, hil::kActuatorChannel};
  const std::string_view n(name);
  for (int d = 0; d < 2; ++d) {
    if (n.substr(0, kBases[d].size()) != kBases[d]) continue;
    const std::string_view suffix = n.substr(kBases[d].size());
    std::lock_guard<std::mutex> lock(text_mutex_);
    if (suffix_.empty() && !o_.suffix_given) {  // the first frame channel heard names the suffix
      if (!hil::valid_channel_suffix(std::string(suffix))) return false;
      suffix_ = std::string(suffix);
      if (suffix_.empty()) o_.suffix_given = true;  // the plain channel names: keep them
    }
    if (suffix != suffix_) return false;
    direction = d;
    return true;
  }
  return false;
}

const msg::DeviceSignals* LcmListener::learn(bool (*should_stop)(), std::int64_t& tick_ns) {
  std::vector<std::uint8_t> buf(kDatagramBytes);
  tick_ns = 0;
  while (!should_stop()) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    for (;;) {
      const ssize_t n = ::recv(fd_, buf.data(), buf.size(), MSG_DONTWAIT);
      if (n < 0) break;
      const char* channel = nullptr;
      const std::uint8_t* payload = nullptr;
      std::size_t size = 0;
      int d = 0;
      if (!parse_short(buf.data(), static_cast<std::size_t>(n), channel, payload, size) || !channel_of(channel, d) ||
          size < 8) {
        continue;  // not a frame: the counts start once the view does
      }
      const std::uint64_t fp = be64(payload);
      if (device_ == nullptr) {
        for (const msg::DeviceSignals* dev : msg::kAllDeviceSignals) {
          if ((d == 0 ? dev->lcm_sensor_fingerprint : dev->lcm_actuator_fingerprint) == fp) device_ = dev;
        }
        if (device_ == nullptr) continue;  // a type no table of this build declares
      }
      if (pending_.size() < kMaxPending) pending_.push_back({std::vector<std::uint8_t>(buf.begin(), buf.begin() + n)});
      if (tick_ns == 0) {
        msg::AnySensorFrame s{};
        msg::AnyActuatorFrame a{};
        const bool ok = d == 0 ? hil::decode(payload, static_cast<int>(size), *device_, s) == hil::DecodeError::kOk
                               : hil::decode(payload, static_cast<int>(size), *device_, a) == hil::DecodeError::kOk;
        const std::uint64_t tick = d == 0 ? s.tick : a.tick;
        const std::int64_t t = d == 0 ? s.time_ns : a.time_ns;
        if (ok && tick > 0 && t > 0) tick_ns = t / static_cast<std::int64_t>(tick);
      }
      if (device_ != nullptr && tick_ns > 0) return device_;
    }
  }
  return nullptr;
}

void LcmListener::start(LiveRing& sensor, LiveRing& actuator) {
  rings_[0] = &sensor;
  rings_[1] = &actuator;
  row_.assign(std::max(sensor.width(), actuator.width()), 0.0);
  stopping_ = false;
  thread_ = std::thread([this] { run(); });
}

void LcmListener::stop() {
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
}

void LcmListener::run() {
  // The frames learn() read come first, in order.
  for (const Datagram& d : pending_) take(d.bytes.data(), d.bytes.size());
  pending_.clear();
  std::vector<std::uint8_t> bufs(static_cast<std::size_t>(kBatch) * kDatagramBytes);
  mmsghdr msgs[kBatch];
  iovec iov[kBatch];
  alignas(cmsghdr) char control[kBatch][CMSG_SPACE(sizeof(std::uint32_t))];
  while (!stopping_.load(std::memory_order_relaxed)) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    for (;;) {
      for (int i = 0; i < kBatch; ++i) {
        iov[i] = {bufs.data() + static_cast<std::size_t>(i) * kDatagramBytes, kDatagramBytes};
        msgs[i].msg_hdr = msghdr{};
        msgs[i].msg_hdr.msg_iov = &iov[i];
        msgs[i].msg_hdr.msg_iovlen = 1;
        msgs[i].msg_hdr.msg_control = control[i];
        msgs[i].msg_hdr.msg_controllen = sizeof control[i];
      }
      const int n = ::recvmmsg(fd_, msgs, kBatch, MSG_DONTWAIT, nullptr);
      if (n <= 0) break;
      for (int i = 0; i < n; ++i) {
        for (cmsghdr* c = CMSG_FIRSTHDR(&msgs[i].msg_hdr); c != nullptr; c = CMSG_NXTHDR(&msgs[i].msg_hdr, c)) {
          if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
            std::uint32_t dropped = 0;
            std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
            kernel_drops_ = dropped;
          }
        }
        take(static_cast<const std::uint8_t*>(iov[i].iov_base), msgs[i].msg_len);
      }
      if (n < kBatch) break;
    }
    // Let datagrams gather: one wake-up then takes tens to hundreds of them.
    std::this_thread::sleep_for(std::chrono::milliseconds(kBatchPauseMs));
  }
}

void LcmListener::take(const std::uint8_t* data, std::size_t size) {
  ++datagrams_;
  const char* channel = nullptr;
  const std::uint8_t* payload = nullptr;
  std::size_t n = 0;
  if (!parse_short(data, size, channel, payload, n)) {
    if (size >= 4 && be32(data) == kMagicLong) ++fragmented_;
    else ++not_lcm_;
    return;
  }
  int d = 0;
  if (!channel_of(channel, d)) {
    ++other_channels_;
    return;
  }
  DirectionCounts& counts = d == 0 ? sensor_ : actuator_;
  msg::AnySensorFrame s{};
  msg::AnyActuatorFrame a{};
  hil::LinkEnvelope e;
  const hil::DecodeError err = d == 0 ? hil::decode(payload, static_cast<int>(n), *device_, s, nullptr, &e)
                                      : hil::decode(payload, static_cast<int>(n), *device_, a, nullptr, &e);
  if (err != hil::DecodeError::kOk) {
    ++counts.undecodable;
    return;
  }
  ++counts.received;
  // With a key, nothing a forger sends changes what is shown — not even which session is: the MAC first.
  if (o_.key) {
    using namespace firmware::link;
    const std::uint32_t data_id = d == 0 ? hil::kSensorDataId : hil::kActuatorDataId;
    const auto covered = std::span<const std::uint8_t>(payload, static_cast<std::size_t>(hil::mac_covered_bytes(static_cast<int>(n))));
    const std::uint64_t expected = truncate_mac(authenticator(*o_.key, data_id, e.session, e.freshness, covered), 8);
    if (!mac_equal(expected, e.mac, 8)) {
      ++counts.bad_mac;
      return;
    }
  }
  const std::int64_t now = now_ns();
  if (!bound_ || (e.session != session_ && now - last_heard_ns_ > kSessionSilenceNs)) {
    bound_ = true;
    session_ = e.session;
    sender_[0] = sender_[1] = 0;
    freshness_[0] = freshness_[1] = 0;
    new_run_[0] = new_run_[1] = true;
    ++sessions_;
    session_now_ = e.session;
  }
  if (e.session != session_) {
    ++counts.other_session;
    return;
  }
  if (sender_[d] == 0) sender_[d] = e.sender;
  if (e.sender != sender_[d]) {
    ++counts.other_session;
    return;
  }
  if (o_.key) {
    if (e.freshness <= freshness_[d]) {
      ++counts.replayed;
      return;
    }
    freshness_[d] = e.freshness;
  }
  last_heard_ns_ = now;
  const bool end = d == 0 ? (s.status & msg::bit(msg::SensorStatusBit::kEndOfRun)) != 0u
                          : (a.status & msg::bit(msg::FaultBit::kEndOfRun)) != 0u;
  if (end) {
    ++counts.end_of_run;
    return;
  }
  RowHeader h;
  h.flags = (o_.key ? kAuthenticated : 0u) | (new_run_[d] ? kNewRun : 0u);
  if (d == 0) {
    h.tick = static_cast<std::int64_t>(s.tick);
    h.status = s.status;
    row_[0] = static_cast<double>(s.time_ns) * 1e-9;
    frame_values(s, *device_, row_.data() + 1);
  } else {
    h.tick = static_cast<std::int64_t>(a.tick);
    h.status = a.status;
    h.flags |= kHasStatus | ((a.status & msg::bit(msg::FaultBit::kSafeState)) != 0 ? kSafe : 0u);
    row_[0] = static_cast<double>(a.time_ns) * 1e-9;
    frame_values(a, *device_, row_.data() + 1);
  }
  if (rings_[d]->push(h, row_.data())) {
    ++counts.shown;
    new_run_[d] = false;
  } else {
    ++counts.ring_full;
  }
}

namespace {

nlohmann::json direction_json(const DirectionCounts& c) {
  const std::uint64_t refused = c.bad_mac + c.replayed + c.other_session + c.undecodable;
  std::string why;
  auto add = [&](std::uint64_t n, const char* what) {
    if (n == 0) return;
    why += (why.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(c.bad_mac, "bad MAC");
  add(c.replayed, "replayed");
  add(c.other_session, "other session or sender");
  add(c.undecodable, "not this device's type");
  return {{"received", c.received.load()}, {"shown", c.shown.load()}, {"refused", refused}, {"why", why},
          {"ring_full", c.ring_full.load()}, {"end_of_run", c.end_of_run.load()}};
}

}  // namespace

nlohmann::json LcmListener::link_json() const {
  std::string suffix;
  {
    std::lock_guard<std::mutex> lock(text_mutex_);
    suffix = suffix_;
  }
  const bool keyed = o_.key.has_value();
  std::string other = std::to_string(other_channels_.load()) + " on other channels";
  if (fragmented_ > 0) other += ", " + std::to_string(fragmented_.load()) + " fragmented";
  if (not_lcm_ > 0) other += ", " + std::to_string(not_lcm_.load()) + " not LCM";
  if (kernel_drops_ > 0) other += ", " + std::to_string(kernel_drops_.load()) + " dropped by the kernel (socket buffer full)";
  return {{"url", o_.url},
          {"channels", std::string(hil::kSensorChannel) + suffix + ", " + hil::kActuatorChannel + suffix},
          {"device", device_ != nullptr ? std::string(device_->device) : std::string("?")},
          {"session", sessions_ > 0 ? format_link_id(session_now_.load()) + (sessions_ > 1 ? " (run " + std::to_string(sessions_.load()) + " heard)" : "") : "—"},
          {"authenticated", keyed},
          {"authentication", keyed ? "frames authenticated with the key" : "NOT authenticated: no --key-file"},
          {"sensor", direction_json(sensor_)},
          {"actuator", direction_json(actuator_)},
          {"other", other}};
}

nlohmann::json LcmListener::summary_json() const {
  nlohmann::json j = link_json();
  j["datagrams"] = datagrams_.load();
  j["other_channels"] = other_channels_.load();
  j["fragmented"] = fragmented_.load();
  j["not_lcm"] = not_lcm_.load();
  j["kernel_drops"] = kernel_drops_.load();
  j["sessions"] = sessions_.load();
  for (const auto& [k, c] : {std::pair<const char*, const DirectionCounts*>{"sensor", &sensor_}, {"actuator", &actuator_}}) {
    j[k] = {{"received", c->received.load()}, {"shown", c->shown.load()}, {"bad_mac", c->bad_mac.load()},
            {"replayed", c->replayed.load()}, {"other_session", c->other_session.load()},
            {"undecodable", c->undecodable.load()}, {"ring_full", c->ring_full.load()},
            {"end_of_run", c->end_of_run.load()}};
  }
  return j;
}

}  // namespace gyrostab::tools::view
