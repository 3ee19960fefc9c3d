#include "tools/log/bus_log_writer.hpp"

#include "tools/signals/device_signals.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <lcm/eventlog.h>

#include <string_view>

#include "hil/lcm/lcm_transport.hpp"

namespace gyrostab::tools::buslog {

// The log's frame channels are the bus's (hil/lcm/lcm_transport.hpp), so a played-back log drives the same
// subscribers.
static_assert(std::string_view(kSensorChannel) == hil::kSensorChannel);
static_assert(std::string_view(kActuatorChannel) == hil::kActuatorChannel);

namespace {
constexpr std::size_t kStreamBufferBytes = 256 * 1024;  // ~700 ticks per write(2) at 360 B a tick
}

BusLogWriter::BusLogWriter() = default;

BusLogWriter::~BusLogWriter() {
  if (log_ != nullptr) {
    std::string ignored;
    close({-1, EndReason::kOther, 0, "writer destroyed before close"}, ignored);
  }
}

bool BusLogWriter::open(const std::string& path, const SceneEvent& scene, const std::string& channel_suffix,
                        std::string& error) {
  if (log_ != nullptr) {
    error = "bus log " + path_ + " is already open";
    return false;
  }
  if (scene.toml.find('\0') != std::string::npos) {
    error = "the scene text contains a NUL byte; scene_t cannot carry it";
    return false;
  }
  if (scene.tick_ns < 1000) {
    error = "tick_ns < 1000 ns: event timestamps in µs would not tell ticks apart";
    return false;
  }
  const std::string scene_channel = channel(kSceneChannel, channel_suffix);
  if (static_cast<int>(scene_channel.size()) > kMaxChannelLength) {
    error = "channel suffix too long (LCM logs hold channel names up to 999 bytes)";
    return false;
  }
  signals_ = find_device_signals(scene.device);
  if (signals_ == nullptr) {
    error = "device " + scene.device + " has no signal table: its frames cannot be logged";
    return false;
  }
  errno = 0;
  log_ = lcm_eventlog_create(path.c_str(), "w");
  if (log_ == nullptr) {
    error = "cannot create bus log " + path + ": " + (errno != 0 ? std::strerror(errno) : "unknown error");
    return false;
  }
  stream_buf_ = std::make_unique<char[]>(kStreamBufferBytes);
  std::setvbuf(log_->f, stream_buf_.get(), _IOFBF, kStreamBufferBytes);
  path_ = path;
  sensor_channel_ = channel(kSensorChannel, channel_suffix);
  actuator_channel_ = channel(kActuatorChannel, channel_suffix);
  end_channel_ = channel(kEndChannel, channel_suffix);
  tick_ns_ = scene.tick_ns;
  events_ = 0;
  failed_ = false;
  const std::vector<std::uint8_t> payload = encode(scene);
  if (payload.empty() || !write(scene_channel, 0, payload.data(), static_cast<int>(payload.size())) ||
      std::fflush(log_->f) != 0) {
    error = "cannot write the scene event to " + path + ": " + std::strerror(errno);
    lcm_eventlog_destroy(log_);
    log_ = nullptr;
    return false;
  }
  return true;
}

bool BusLogWriter::write(const std::string& ch, std::int64_t timestamp_us, const std::uint8_t* data, int size) {
  if (log_ == nullptr || failed_) return false;
  lcm_eventlog_event_t e{};
  e.timestamp = timestamp_us;
  e.channellen = static_cast<std::int32_t>(ch.size());
  e.datalen = size;
  e.channel = const_cast<char*>(ch.data());  // LCM only reads it
  e.data = const_cast<std::uint8_t*>(data);
  if (lcm_eventlog_write_event(log_, &e) != 0) {
    failed_ = true;
    return false;
  }
  ++events_;
  return true;
}

bool BusLogWriter::write_sensor(std::int64_t tick, const msg::AnySensorFrame& f) {
  const std::int64_t t = sim_time_us(tick, tick_ns_);
  const int n = hil::encode(f, *signals_, t, sensor_buf_.data(), static_cast<int>(sensor_buf_.size()));
  return n > 0 && write(sensor_channel_, t, sensor_buf_.data(), n);
}

bool BusLogWriter::write_actuator(std::int64_t tick, const msg::AnyActuatorFrame& f) {
  const std::int64_t t = sim_time_us(tick, tick_ns_);
  const int n = hil::encode(f, *signals_, t, actuator_buf_.data(), static_cast<int>(actuator_buf_.size()));
  return n > 0 && write(actuator_channel_, t, actuator_buf_.data(), n);
}

bool BusLogWriter::close(const EndEvent& end, std::string& error) {
  if (log_ == nullptr) {
    error = "bus log is not open";
    return false;
  }
  bool ok = !failed_;
  if (ok && end.ticks >= 0) {
    const std::vector<std::uint8_t> payload = encode(end);
    ok = !payload.empty() &&
         write(end_channel_, sim_time_us(end.ticks, tick_ns_), payload.data(), static_cast<int>(payload.size()));
  }
  errno = 0;
  if (std::fflush(log_->f) != 0) ok = false;
  const int saved = errno;
  // lcm_eventlog_destroy flushes again, closes and frees; a failed fclose it cannot report is caught by the
  // fflush above (nothing is left to write).
  lcm_eventlog_destroy(log_);
  log_ = nullptr;
  stream_buf_.reset();
  if (!ok) {
    error = "bus log " + path_ + " is incomplete: a write failed" +
            (saved != 0 ? std::string(" (") + std::strerror(saved) + ")" : std::string());
  }
  return ok;
}

}  // namespace gyrostab::tools::buslog
