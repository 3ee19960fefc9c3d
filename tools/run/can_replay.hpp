// `gyrostab replay LOG` for a candump log of the CAN bus (`--can-log`, or candump itself): the controller the
// scene builds is fed the recorded sensor frames and every CAN frame it would send is compared with the
// recorded one, bit for bit — identifier, length, FD flags and all data bytes, CRC and alive counter
// included. The replay runs the same decoder as the controller process (hil/can/frame_codec.hpp) and mirrors
// the lockstep protocol: a sensor set repeated for the tick just stepped (a plant resend) is not stepped
// again, and a recorded command set repeated for a tick (the controller's resend) is matched by encoding the
// last command again, with the next alive counters, as the controller did.
// Frames the decoder rejects (a flood, bad frames of a fault test) are counted and skipped, as the controller
// skipped them; a rejected frame where the controller's own frame is due is a mismatch.
// The scene: --scene, or the one in the log's header (`# scene-toml-base64` lines, written by --can-log).
// Exit codes as for LCM logs (replay_session.hpp): 0 identical, 4 mismatch (line and fields printed),
// 5 the log is unreadable past a line, or ends before the controller's answer to its last sensor set, or its
// header disagrees with the scene, 2 nothing replayed.
#pragma once

#include <time.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <deque>
#include <string>

#include "hil/can/candump_log.hpp"
#include "hil/can/frame_codec.hpp"
#include "tools/log/frame_diff.hpp"
#include "tools/run/can_link_setup.hpp"
#include "tools/run/replay_session.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

// The value of a "# key value" header line of a candump log ("" if absent).
inline std::string candump_header(const can::CandumpFile& f, const std::string& key) {
  for (const std::string& c : f.comments)
    if (c.size() > key.size() && c.compare(0, key.size(), key) == 0 && c[key.size()] == ' ') return c.substr(key.size() + 1);
  return "";
}

inline std::string base64_decode(const std::string& in) {
  std::string out;
  unsigned v = 0;
  int bits = 0;
  for (char c : in) {
    int d = -1;
    if (c >= 'A' && c <= 'Z') d = c - 'A';
    else if (c >= 'a' && c <= 'z') d = c - 'a' + 26;
    else if (c >= '0' && c <= '9') d = c - '0' + 52;
    else if (c == '+') d = 62;
    else if (c == '/') d = 63;
    else continue;  // '=' padding, whitespace
    v = (v << 6) | static_cast<unsigned>(d);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((v >> bits) & 0xFFu);
    }
  }
  return out;
}

// The scene text carried by a gyrostab candump log ("" if it has none).
inline std::string candump_scene_text(const can::CandumpFile& f) {
  std::string b64;
  const std::string key = "scene-toml-base64 ";
  for (const std::string& c : f.comments)
    if (c.compare(0, key.size(), key) == 0) b64 += c.substr(key.size());
  return base64_decode(b64);
}

inline std::string describe_can_frame(const can::CanFrame& f) {
  char line[can::kMaxCandumpLine];
  const std::size_t n = can::format_candump_line(f, "-", 0, line, sizeof line);
  // Drop "(0000000000.000000) - " and the newline.
  const std::string s(line, n);
  const std::size_t at = s.find(") - ");
  return at == std::string::npos ? s : s.substr(at + 4, s.size() - at - 5);
}

template <class Device>
int replay_controller_candump(Device& device, const LoopConfig& loop, const RunRequest& req) {
  const std::string& path = req.transport.replay_log;
  can::CandumpFile file;
  std::string error;
  if (!can::read_candump_file(path, file, error)) {
    std::fprintf(stderr, "gyrostab: %s\n", error.c_str());
    return kReplayExitBadLog;
  }
  // A gyrostab log names its run in its header: it must agree with the scene (unless --scene overrides).
  std::string differs;
  const auto check = [&](const char* key, const std::string& want) {
    const std::string got = candump_header(file, key);
    if (!got.empty() && got != want) differs += std::string(" ") + key + " '" + got + "' vs '" + want + "';";
  };
  check("scene", loop.name);
  check("device", loop.device);
  check("seed", std::to_string(loop.seed));
  check("tick_ns", std::to_string(loop.tick_ns));
  if (!differs.empty()) {
    if (!req.transport.replay_scene_override) {
      std::fprintf(stderr, "gyrostab: %s: the log's header disagrees with its scene:%s\n", path.c_str(),
                   differs.c_str());
      return kReplayExitBadLog;
    }
    std::fprintf(stderr, "gyrostab: %s: note: --scene differs from the recorded scene:%s\n", path.c_str(),
                 differs.c_str());
  }
  can::NodeSet nodes = can_nodes_of(loop.device);
  if (const std::string n = candump_header(file, "nodes"); !n.empty()) {
    nodes = static_cast<can::NodeSet>(std::atoi(n.c_str()) & can::kAllNodes);
  }

  auto& controller = device.controller();
  can::SetAssembler sensors(can::Direction::kSensor, nodes);
  can::SetAssembler commands(can::Direction::kActuator, nodes);
  can::FrameEncoder encoder(can::Direction::kActuator, nodes);
  std::deque<can::CanFrame> due;  // the controller's frames not yet matched against the log
  std::array<can::CanFrame, can::kMaxMessagesPerDirection> tx{};
  msg::SensorFrame sensor{};
  msg::ActuatorFrame out{}, recorded{};
  std::int64_t last_tick = -1;
  std::int64_t ticks = 0, compared = 0, skipped = 0;
  timespec pace{};
  clock_gettime(CLOCK_MONOTONIC, &pace);
  const auto push_encoded = [&](const msg::ActuatorFrame& a) {
    const std::size_t n = encoder.encode(a, tx);
    for (std::size_t i = 0; i < n; ++i) due.push_back(tx[i]);
    return n > 0;
  };
  const auto sensor_id = [&](std::uint32_t id) {
    const int i = can::message_index(id);
    return i >= 0 && can::kMessages[static_cast<std::size_t>(i)].direction == can::Direction::kSensor;
  };
  for (const can::CandumpRecord& r : file.frames) {
    const can::CanFrame& f = r.frame;
    const bool command_id = !(f.flags & (can::kFlagError | can::kFlagExtended)) && can::message_index(f.id) >= 0 &&
                            !sensor_id(f.id);
    if (!command_id) {
      if (sensors.accept(f) != can::FrameError::kNone) {
        ++skipped;
        continue;
      }
      if (!sensors.ready()) continue;
      sensors.take(sensor);
      const auto k = static_cast<std::int64_t>(sensor.tick);
      if (k == last_tick) continue;  // the plant sent this tick again: the controller answers from its cache
      if (!due.empty()) {
        std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH: the sensor set of tick %lld arrives while the controller's "
                     "%s for tick %lld is missing from the log\n", path.c_str(), r.line, static_cast<long long>(k),
                     describe_can_frame(due.front()).c_str(), static_cast<long long>(last_tick));
        return kReplayExitMismatch;
      }
      if (req.transport.replay_real_time) {
        const std::int64_t ns = static_cast<std::int64_t>(pace.tv_nsec) + loop.tick_ns;
        pace.tv_sec += static_cast<time_t>(ns / 1'000'000'000);
        pace.tv_nsec = static_cast<long>(ns % 1'000'000'000);
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &pace, nullptr) == EINTR) {
        }
      }
      controller.step(static_cast<std::uint64_t>(k), &sensor, out);
      last_tick = k;
      ++ticks;
      if (!push_encoded(out)) {
        std::fprintf(stderr, "gyrostab: %s: the controller's command for tick %lld sets a field no CAN node of "
                     "this device carries\n", path.c_str(), static_cast<long long>(k));
        return kReplayExitMismatch;
      }
      continue;
    }
    // A frame on a command identifier: the controller's.
    const can::FrameError e = commands.accept(f);
    if (e != can::FrameError::kNone) {
      if (!due.empty() && due.front().id == f.id) {
        std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH at tick %lld: the recorded frame is rejected (%s) where the "
                     "controller sends %s\n", path.c_str(), r.line, static_cast<long long>(last_tick),
                     std::string(can::frame_error_name(e)).c_str(), describe_can_frame(due.front()).c_str());
        return kReplayExitMismatch;
      }
      ++skipped;
      continue;
    }
    if (due.empty()) {
      // A command set recorded again for the tick just stepped: the controller's resend, re-encoded.
      if (last_tick < 0 || !push_encoded(out)) {
        std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH: a command frame before any sensor set: %s\n", path.c_str(),
                     r.line, describe_can_frame(f).c_str());
        return kReplayExitMismatch;
      }
    }
    const can::CanFrame want = due.front();
    due.pop_front();
    const bool same = want.id == f.id && want.len == f.len &&
                      (want.flags & (can::kFlagFd | can::kFlagBrs | can::kFlagEsi)) ==
                          (f.flags & (can::kFlagFd | can::kFlagBrs | can::kFlagEsi)) &&
                      std::memcmp(want.data, f.data, f.len) == 0;
    if (!same) {
      std::string fields;
      if (commands.ready() && commands.take(recorded)) fields = "; fields: " + buslog::frame_differences(recorded, out);
      std::fprintf(stderr, "gyrostab: %s:%d: MISMATCH at tick %lld (%lld frames before it identical): recorded %s, "
                   "controller %s%s\n", path.c_str(), r.line, static_cast<long long>(last_tick),
                   static_cast<long long>(compared), describe_can_frame(f).c_str(), describe_can_frame(want).c_str(),
                   fields.c_str());
      return kReplayExitMismatch;
    }
    ++compared;
    if (commands.ready()) commands.take(recorded);
  }
  if (ticks == 0) {
    std::fprintf(stderr, "gyrostab: %s: no complete sensor set in the log, nothing replayed\n", path.c_str());
    return 2;
  }
  if (!due.empty()) {
    std::fprintf(stderr, "gyrostab: %s: the log ends before the controller's %s for tick %lld; the %lld frames "
                 "before it are identical\n", path.c_str(), describe_can_frame(due.front()).c_str(),
                 static_cast<long long>(last_tick), static_cast<long long>(compared));
    return kReplayExitBadLog;
  }
  std::printf("%s: %lld ticks, every CAN frame of the controller identical (%lld frames, bit for bit); %lld recorded "
              "frames rejected by the decoder and skipped, as the controller skipped them\n",
              path.c_str(), static_cast<long long>(ticks), static_cast<long long>(compared),
              static_cast<long long>(skipped));
  return 0;
}

}  // namespace gyrostab::tools
